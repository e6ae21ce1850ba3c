// Element: the motor on the rotor's coordinate, torque- or speed-controlled.
// Torque-controlled it adds the drive torque to the rotor's generalized
// force (its work is the drive's work in); speed-controlled it is a
// rheonomic constraint on the rotor's velocity (one row and column of the
// constrained solve, e_rotor, with the prescribed speed's derivative as the
// right-hand side; its multiplier is the motor torque).
// Behind a gear stage (gear.hpp) its coordinate is the gear's output: the
// torque it applies there is n T, the speed it prescribes omega(t) / n.
#pragma once

#include "leadscrew/excitation/excitation.hpp"
#include "leadscrew/model/elements/gear.hpp"

namespace leadscrew::model::elements {

struct Motor {
  int rotor = 0;
  bool speed_controlled = false;
  Excitation torque;  // loads.drive_torque [N m]
  Excitation speed;   // loads.drive_speed [rad/s]
  Gear gear;          // the stage between the rotor and its coordinate (ratio 1: none)

  // The torque it applies as a force at time t (0 when speed-controlled:
  // then its torque is the constraint's multiplier).
  double applied_torque(double t) const {
    return speed_controlled ? 0.0 : gear.driven_torque(torque(t));
  }
  // The number of constraint rows it adds (0 or 1).
  int constraint_count() const noexcept { return speed_controlled ? 1 : 0; }
  // Its power, the drive's work rate [W], at a motor torque (the applied
  // one, or the constraint's multiplier) and the velocities v.
  template <class Vector>
  double power(double motor_torque, const Vector& v) const {
    return motor_torque * v[rotor];
  }
  // The prescribed rotor acceleration, the constraint's right-hand side.
  double prescribed_acceleration(double t) const {
    return gear.driven_speed(speed.continuous_derivative(t, "loads.drive_speed"));
  }
  // The coordinate's prescribed speed (speed-controlled).
  double prescribed_speed(double t) const { return gear.driven_speed(speed(t)); }
};

}  // namespace leadscrew::model::elements
