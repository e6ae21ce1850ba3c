// The DC motor's result checks (checks.hpp): its driver stays within its
// supply, and the drive's torque channel is the motor's k_t i
// (docs/physics/result_checks.md, "driver_voltage, motor_torque").
#include <algorithm>
#include <cmath>
#include <limits>

#include "checks.hpp"

namespace leadscrew::model::drive {

namespace {

// Channel `channel`'s value at output row `row` (the point-major table).
double value(const integrate::SimulationResult& result, int channel, std::size_t row) {
  return result.values[row * result.channel_count() + static_cast<std::size_t>(channel)];
}

integrate::InvariantCheck motor_check(const char* name, const char* what, const char* unit) {
  integrate::InvariantCheck c;
  c.name = name;
  c.what = what;
  c.unit = unit;
  c.value = -std::numeric_limits<double>::infinity();
  return c;
}

// Keeps the worst of value <= bound (the excess value - bound).
void offer(integrate::InvariantCheck& c, double& worst, double value, double bound, double t) {
  if (!(value - bound <= worst)) {
    worst = value - bound;
    c.value = value, c.bound = bound, c.time = t;
  }
  if (!(value <= bound)) c.passed = false;
}

// U_d = R i + k_e omega at every row of a motor without inductance, the
// quasi-static armature (docs/physics/dc_motor.md): at the row's speed on
// the event-driven scheme, on Moreau-Jean at omega_theta of the step that
// ends at the row (its rows report the step's armature; row 0 its own
// speed; rows interpolated between steps are skipped, as by driver_voltage).
// Round-off: 1e-12 of the circuit's largest voltage term `volts`. (A step
// that held the current limit and ended where the free current lies below
// it once reported the hold's voltage with the free current: 0.05 V off of
// 16 V, every other check passing.)
integrate::InvariantCheck armature_check(const elements::DcMotor& dc, double resistance,
                                         double back_emf_constant, double theta,
                                         bool time_stepping, double volts,
                                         const integrate::SimulationResult& result) {
  integrate::InvariantCheck c = motor_check(
      "armature", "without inductance the DC motor's armature is quasi-static: "
                  "motor_voltage = R motor_current + k_e omega (docs/physics/dc_motor.md)", "V");
  c.applies = !dc.has_state() && !(time_stepping && result.interpolated);
  const int current = result.channel_index("motor_current");
  const int voltage = result.channel_index("motor_voltage");
  const int omega = result.channel_index("omega_drive");
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < result.point_count() && c.applies; ++i) {
    double speed = value(result, omega, i);
    if (time_stepping && i > 0) speed = (1.0 - theta) * value(result, omega, i - 1) + theta * speed;
    offer(c, worst,
          std::abs(value(result, voltage, i) - resistance * value(result, current, i) -
                   back_emf_constant * speed),
          1e-12 * volts, result.time[i]);
  }
  return c;
}

}  // namespace

void check_dc_motor_result(const DriveModel& model, const DriveSimulationOptions& options,
                           bool time_stepping, integrate::SimulationResult& result) {
  const elements::DcMotor* dc = model.dc_motor();
  if (!dc || result.checks.empty() || !result.checks.front().passed) return;  // (not finite)
  const DriveParameters& p = model.parameters();
  const int current = result.channel_index("motor_current");
  const int voltage = result.channel_index("motor_voltage");
  const int torque = result.channel_index("drive_torque");
  const int omega = result.channel_index("omega_drive");
  const double torque_constant = p.motor_torque_constant;  // the rotor's
  const double back_emf_constant =
      p.motor_back_emf_constant < 0.0 ? torque_constant : p.motor_back_emf_constant;
  // The round-off scales: the circuit's largest voltage term and torque.
  double volts = 0.0, newton_metres = 0.0;
  for (std::size_t i = 0; i < result.point_count(); ++i) {
    const double t = result.time[i], u = std::abs(dc->voltage(t));
    volts = std::max({volts, u, std::abs(value(result, voltage, i)),
                      p.motor_resistance * std::abs(value(result, current, i)),
                      back_emf_constant * std::abs(value(result, omega, i))});
    newton_metres = std::max(newton_metres, std::abs(value(result, torque, i)));
  }
  // |U_d| <= |U| where the driver's voltage applies at the row: the
  // event-driven scheme's row time; Moreau-Jean's last step's t + theta h
  // (its rows are its step ends; rows interpolated between them are not
  // the scheme's: skipped, as the force checks skip them). The event-driven
  // row just before an event is at its located root, where the supply's
  // margin has just changed sign by up to its rate times the root's time
  // resolution (a voltage step of the end_stop_jam study: 5e-7 V at 2e10
  // V/s): skipped as the force checks skip it; the row after it is the new
  // mode's.
  integrate::InvariantCheck supply = motor_check(
      "driver_voltage", "the DC motor's driver puts out no more than its supply: "
                        "|motor_voltage| <= |U(t)| (docs/physics/dc_motor.md)", "V");
  supply.applies = !(time_stepping && result.interpolated);
  double worst = -std::numeric_limits<double>::infinity();
  const std::size_t n = result.point_count();
  for (std::size_t i = 0; i < n && supply.applies; ++i) {
    double t = result.time[i];
    if (!time_stepping && i + 1 < n && result.time[i + 1] == t) continue;  // (at an event's root)
    if (time_stepping && i > 0) t = result.time[i - 1] + options.theta * (t - result.time[i - 1]);
    offer(supply, worst, std::abs(value(result, voltage, i)),
          std::abs(dc->voltage(t)) + 1e-12 * volts, result.time[i]);
  }
  result.checks.push_back(supply);
  // drive_torque = k_t motor_current at every row (the rotor's torque).
  integrate::InvariantCheck channel = motor_check(
      "motor_torque", "drive_torque is the DC motor's torque k_t motor_current at every row",
      "N*m");
  worst = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < result.point_count(); ++i)
    offer(channel, worst,
          std::abs(value(result, torque, i) - torque_constant * value(result, current, i)),
          1e-12 * newton_metres, result.time[i]);
  result.checks.push_back(channel);
  result.checks.push_back(armature_check(*dc, p.motor_resistance, back_emf_constant,
                                         options.theta, time_stepping, volts, result));
}

}  // namespace leadscrew::model::drive
