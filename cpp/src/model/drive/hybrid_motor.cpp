// DriveHybrid (hybrid.hpp): a DC motor's current (elements/dc_motor.hpp): its
// rates and channels, and the current limit's root and hold. The motor's
// torque k_t i enters the forces through DriveDynamics (set_motor_current,
// set_state), so every mode, root and impact sees it as a state's function.
#include <cmath>

#include "channels.hpp"
#include "hybrid.hpp"

namespace leadscrew::model::drive {

void DriveHybrid::motor_rates(double t, double* ydot, double* energy) const {
  const elements::DcMotor& dc = *model_.dc_motor();
  const double current = dynamics_.motor_current();
  const double omega = v_[dc.rotor];
  if (layout_.motor_current() >= 0)
    ydot[layout_.motor_current()] = current_held_ != 0 ? 0.0 : dc.free_rate(t, current, omega);
  ydot[layout_.copper_loss()] = dc.copper_loss_rate(current);
  energy[kWorkDrive] = dc.work_rate(t, current, omega, current_held_ != 0);
}

void DriveHybrid::motor_channels(double t, const double* y, ChannelState& state) const {
  const elements::DcMotor& dc = *model_.dc_motor();
  const double current = dynamics_.motor_current();
  state.motor_current = current;
  state.motor_voltage = dc.terminal_voltage(t, current, v_[dc.rotor], current_held_ != 0);
  state.copper_loss = y[layout_.copper_loss()];
  state.magnetic = dc.magnetic_energy(current);
}

double DriveHybrid::current_limit_margin(double t) const {
  const elements::DcMotor& dc = *model_.dc_motor();
  const double current = dynamics_.motor_current();
  if (current_held_ == 0) return dc.current_limit - std::abs(current);
  return current_held_ * dc.free_rate(t, current, v_[dc.rotor]);
}

std::string DriveHybrid::change_current_hold(double t, double* y) {
  const elements::DcMotor& dc = *model_.dc_motor();
  set(t, y);
  if (current_held_ != 0) {
    current_held_ = 0;
    return "current limit released";
  }
  const int sign = dynamics_.motor_current() >= 0.0 ? 1 : -1;
  y[layout_.motor_current()] = sign * dc.current_limit;  // at the limit, to round-off
  set(t, y);
  // The current reached the limit driven beyond it (a touch without push
  // stays free).
  if (sign * dc.free_rate(t, dynamics_.motor_current(), v_[dc.rotor]) <= 0.0) return "";
  current_held_ = sign;
  return "current limit reached";
}

void DriveHybrid::recheck_current_hold(double t, const double* y) {
  if (current_held_ == 0) return;
  set(t, y);
  if (current_limit_margin(t) < 0.0) current_held_ = 0;
}

}  // namespace leadscrew::model::drive
