// A DC motor's current (elements/dc_motor.hpp) as an element of the
// event-driven driver (driver_element.hpp): its rates and channels, and the
// current limit's root and hold. The motor's torque k_t i enters the forces
// through DriveDynamics (set_motor_current, set_state), so every mode, root
// and impact sees it as a state's function.
#include <cmath>

#include "driver_element.hpp"

namespace leadscrew::model::drive {

namespace {

class DcMotorElement final : public DriveHybrid::Element {
 public:
  DcMotorElement(DriveHybrid& hybrid, const elements::DcMotor& dc)
      : Element(hybrid), dc_(dc), limit_root_(dc.has_state() && dc.limited()) {}

  // One root with inductance and a current limit: the margin to the limit,
  // or while held the driver's push beyond it.
  int root_count() const override { return limit_root_ ? 1 : 0; }
  void roots(double t, double* g) const override {
    if (limit_root_) g[0] = limit_margin(t);
  }
  void root_directions(int* directions) const override {
    if (limit_root_) directions[0] = -1;  // the limit reached, or the push ends
  }
  // The event holds or releases the current (snapped to the limit); the
  // mechanical mode changes only with another root.
  Event handle(double t, double* y, const int* root_info) override {
    (void)root_info;
    return {change_hold(t, y), false};
  }
  // After a mechanical event: an impact's jump of the rotor's speed may end
  // the driver's push at once (the root would start beyond its zero).
  void after_mode_change(double t, const double* y) override {
    if (held_ == 0) return;
    set(t, y);
    if (limit_margin(t) < 0.0) held_ = 0;
  }

  // Its current's rate, its copper loss rate and the electrical work's rate
  // (which replaces the motor torque's power in the drive's work).
  void rates(double t, const double* y, double* ydot, double* energy) const override {
    (void)y;
    const double current = dynamics().motor_current();
    const double omega = v()[dc_.rotor];
    if (layout().motor_current() >= 0)
      ydot[layout().motor_current()] = held_ != 0 ? 0.0 : dc_.free_rate(t, current, omega);
    ydot[layout().copper_loss()] = dc_.copper_loss_rate(current);
    energy[kWorkDrive] = dc_.work_rate(t, current, omega, held_ != 0);
  }
  // Its channels: current, the driver's voltage, copper loss, magnetic energy.
  void output(double t, const double* y, ChannelState& state) const override {
    const double current = dynamics().motor_current();
    state.motor_current = current;
    state.motor_voltage = dc_.terminal_voltage(t, current, v()[dc_.rotor], held_ != 0);
    state.copper_loss = y[layout().copper_loss()];
    state.magnetic = dc_.magnetic_energy(current);
  }
  // Its torque k_t i depends on the state: its roots are the state's.
  bool forces_from_loads_alone() const override { return false; }

 private:
  double limit_margin(double t) const {
    const double current = dynamics().motor_current();
    if (held_ == 0) return dc_.current_limit - std::abs(current);
    return held_ * dc_.free_rate(t, current, v()[dc_.rotor]);
  }

  std::string change_hold(double t, double* y) {
    set(t, y);
    if (held_ != 0) {
      held_ = 0;
      return "current limit released";
    }
    const int sign = dynamics().motor_current() >= 0.0 ? 1 : -1;
    y[layout().motor_current()] = sign * dc_.current_limit;  // at the limit, to round-off
    set(t, y);
    // The current reached the limit driven beyond it (a touch without push
    // stays free).
    if (sign * dc_.free_rate(t, dynamics().motor_current(), v()[dc_.rotor]) <= 0.0) return "";
    held_ = sign;
    return "current limit reached";
  }

  const elements::DcMotor& dc_;
  bool limit_root_;  // with inductance and a current limit
  int held_ = 0;     // the current held at +-current_limit (its sign; 0: free)
};

}  // namespace

std::unique_ptr<DriveHybrid::Element> make_dc_motor_element(DriveHybrid& hybrid,
                                                            const DriveModel& model) {
  if (!model.dc_motor()) return nullptr;
  return std::make_unique<DcMotorElement>(hybrid, *model.dc_motor());
}

}  // namespace leadscrew::model::drive
