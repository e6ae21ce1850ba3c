// Element: a permanent-magnet DC motor on the rotor's coordinate, fed by a
// voltage-source driver (issue 19, item 1; scene section `motor`, type "dc").
//
// Armature:   L di/dt = U_d - R i - k_e omega      (omega: the rotor's speed)
// Torque:     T = k_t i on the rotor
// Driver:     U_d = U(t) (motor.voltage) while |i| < i_max. With a current
//             limit i_max (motor.current_limit) the driver is a voltage
//             source with current limiting: where |i| reaches i_max and U(t)
//             would drive it further, it lowers its output to
//             U_d = R i + k_e omega (L > 0: di/dt = 0, i held at +-i_max; an
//             event starts and ends the hold: its root in the driver,
//             drive/hybrid_motor.cpp), and
//             releases it where U(t) no longer drives |i| up. It never puts
//             out more than U(t) in magnitude.
// L = 0:      the quasi-static limit, exact: i = (U(t) - k_e omega) / R,
//             clamped to +-i_max (no state; U_d = R i + k_e omega).
// Energy:     electrical work in  int U_d i dt, copper loss int R i^2 dt,
//             magnetic energy L i^2 / 2. With k_e = k_t (SI, the default)
//             U_d i = R i^2 + d(L i^2/2)/dt + k_t i omega: the mechanical
//             work k_t i omega is what the circuit gives. Where k_e != k_t
//             the motor converts (k_t - k_e) i omega out of nothing; the
//             drive's work books it (work_drive = int (U_d i + (k_t - k_e)
//             i omega) dt), so that the account closes and says so.
// The current starts at 0 (the driver switched on at t = 0). The motor's own
// Coulomb friction (motor.friction_torque) is a friction stage of the train
// (train_friction.hpp), on the rigid drive without play.
#pragma once

#include <algorithm>
#include <cmath>

#include "leadscrew/excitation/excitation.hpp"

namespace leadscrew::model::elements {

struct DcMotor {
  int rotor = 0;
  Excitation voltage;          // motor.voltage [V]
  double resistance = 1.0;     // R [Ohm] > 0
  double inductance = 0.0;     // L [H] >= 0 (0: quasi-static)
  double torque_constant = 0.0;    // k_t [N m/A] > 0
  double back_emf_constant = 0.0;  // k_e [V s/rad] > 0
  double current_limit = 0.0;      // i_max [A] (0: none)

  // The current is a state of the drive's ODE (L > 0).
  bool has_state() const noexcept { return inductance > 0.0; }
  bool limited() const noexcept { return current_limit > 0.0; }
  // The torque on the rotor at a current [N m].
  double torque(double current) const noexcept { return torque_constant * current; }
  // di/dt with the driver at U(t) (L > 0).
  double free_rate(double t, double current, double omega) const {
    return (voltage(t) - resistance * current - back_emf_constant * omega) / inductance;
  }
  // The current without inductance: (U - k_e omega) / R within the limit.
  double quasi_static_current(double t, double omega) const {
    const double i = (voltage(t) - back_emf_constant * omega) / resistance;
    return limited() ? std::clamp(i, -current_limit, current_limit) : i;
  }
  // The driver's output voltage U_d [V]; `held`: the current is held at its
  // limit (L > 0). Without inductance U_d = R i + k_e omega, which is U(t)
  // where the limit does not act.
  double terminal_voltage(double t, double current, double omega, bool held) const {
    if (!has_state() || held) return resistance * current + back_emf_constant * omega;
    return voltage(t);
  }
  // The rates of the energy account: the electrical work in (with the
  // conversion mismatch (k_t - k_e) i omega, 0 by default) and the copper loss.
  double work_rate(double t, double current, double omega, bool held) const {
    return terminal_voltage(t, current, omega, held) * current +
           (torque_constant - back_emf_constant) * current * omega;
  }
  double copper_loss_rate(double current) const noexcept {
    return resistance * current * current;
  }
  double magnetic_energy(double current) const noexcept {
    return 0.5 * inductance * current * current;
  }

  // The theta method over a step h of the armature (Moreau-Jean's step):
  // L (i+ - i) = h (U - R i_theta - k_e omega_theta), with x_theta =
  // (1 - theta) x + theta x+, U at t + theta h. Linear in the rotor's speed
  // omega+ at the step's end: i_theta = mean + mean_slope omega+, i+ = end +
  // end_slope omega+. L = 0: the same formulas give the quasi-static current
  // at omega_theta as i_theta (the start's current cancels; i+ means
  // nothing). Held at the limit (sign `held`): i+ = held i_max (L = 0:
  // i_theta = held i_max), no slope. The current beyond the limit:
  // |i+| (L > 0) or |i_theta| (L = 0) > i_max (exceeds).
  struct ThetaStep {
    double mean = 0.0, mean_slope = 0.0, end = 0.0, end_slope = 0.0;
  };
  ThetaStep theta_step(double u_theta, double h, double theta, double current,
                       double omega, int held) const {
    ThetaStep s;
    if (held != 0) {
      s.end = held * current_limit;
      s.mean = has_state() ? (1.0 - theta) * current + theta * s.end : s.end;
      return s;
    }
    if (!has_state()) {  // (directly: theta = 0 would divide 0 by 0)
      s.mean = (u_theta - back_emf_constant * (1.0 - theta) * omega) / resistance;
      s.mean_slope = -theta * back_emf_constant / resistance;
      return s;
    }
    const double denominator = inductance + theta * h * resistance;
    s.end = (inductance * current + h * (u_theta - resistance * (1.0 - theta) * current -
                                         back_emf_constant * (1.0 - theta) * omega)) /
            denominator;
    s.end_slope = -h * theta * back_emf_constant / denominator;
    s.mean = (1.0 - theta) * current + theta * s.end;
    s.mean_slope = theta * s.end_slope;
    return s;
  }
  bool exceeds(const ThetaStep& s, double omega_next) const {
    const double i = has_state() ? s.end + s.end_slope * omega_next
                                 : s.mean + s.mean_slope * omega_next;
    return limited() && std::abs(i) > current_limit;
  }
};

}  // namespace leadscrew::model::elements
