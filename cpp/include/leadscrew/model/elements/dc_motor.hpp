// Element: a permanent-magnet DC motor on the rotor's coordinate, fed by a
// voltage-source driver (issue 19, item 1; scene section `motor`, type "dc";
// docs/physics/dc_motor.md).
//
// Armature:   L di/dt = U_d - R i - k_e omega      (omega: the rotor's speed)
// Torque:     T = k_t i on the rotor
// Driver:     U_d = U(t) (motor.voltage) while |i| < i_max. With a current
//             limit i_max (motor.current_limit) the driver is a voltage
//             source with current limiting, bounded by its supply:
//             |U_d| <= |U(t)| (a four-quadrant bridge fed with |U(t)|).
//             Where |i| reaches i_max and U(t) would drive it further, it
//             puts out the voltage that holds the current there,
//             U_d = R i + k_e omega (L > 0: di/dt = 0), as far as its supply
//             allows; where the back-EMF asks for more than |U(t)| (a load
//             driving the rotor), it saturates at -side |U(t)|, its utmost
//             against the current, and the current passes the limit:
//             i = (U_d - k_e omega) / R at L = 0. It releases the hold where
//             U(t) no longer drives |i| up, a saturation where |i| is back
//             at i_max. (L > 0: events start and end the modes, Limiter,
//             elements/dc_motor.cpp.)
// L = 0:      the quasi-static limit, exact: i = (U_d - k_e omega) / R with
//             U_d as above (no state).
// Energy:     electrical work in  int U_d i dt, copper loss int R i^2 dt,
//             magnetic energy L i^2 / 2. With k_e = k_t (SI, the default)
//             U_d i = R i^2 + d(L i^2/2)/dt + k_t i omega: the mechanical
//             work k_t i omega is what the circuit gives. Where k_e != k_t
//             the motor converts (k_t - k_e) i omega out of nothing; the
//             drive's work books it (work_drive = int (U_d i + (k_t - k_e)
//             i omega) dt), so that the account closes and says so.
// The current starts at 0 (the driver switched on at t = 0); in a static
// equilibrium at its steady value at rest, U(0) / R within the limit
// (dc_motor.cpp, initial_states). The motor's own
// Coulomb friction (motor.friction_torque) is a friction stage of the train
// (train_friction.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>

#include "leadscrew/excitation/excitation.hpp"

namespace leadscrew::model {
class Element;
}

namespace leadscrew::model::elements {

struct DcMotor {
  int rotor = 0;
  Excitation voltage;          // motor.voltage [V]
  double resistance = 1.0;     // R [Ohm] > 0
  double inductance = 0.0;     // L [H] >= 0 (0: quasi-static)
  double torque_constant = 0.0;    // k_t [N m/A] > 0
  double back_emf_constant = 0.0;  // k_e [V s/rad] > 0
  double current_limit = 0.0;      // i_max [A] (0: none)

  // The driver's current limiter with inductance (the current a state):
  // free (U_d = U(t)), holding the current at side i_max (U_d = R i +
  // k_e omega, di/dt = 0), or saturated beyond it (U_d = -side |U(t)|).
  struct Limiter {
    enum Mode { free, holding, saturated };
    Mode mode = free;
    int side = 0;  // +-1 where limiting
  };

  // The current is a state of the drive's ODE (L > 0).
  bool has_state() const noexcept { return inductance > 0.0; }
  bool limited() const noexcept { return current_limit > 0.0; }
  // The torque on the rotor at a current [N m].
  double torque(double current) const noexcept { return torque_constant * current; }
  // The voltage that keeps the current where it is (di/dt = 0).
  double hold_voltage(double current, double omega) const noexcept {
    return resistance * current + back_emf_constant * omega;
  }
  // The driver's output U_d [V] at the limiter's mode (L > 0).
  double driver_voltage(double t, double current, double omega, Limiter limiter) const {
    switch (limiter.mode) {
      case Limiter::holding: return hold_voltage(current, omega);
      case Limiter::saturated: return -limiter.side * std::abs(voltage(t));
      default: return voltage(t);
    }
  }
  // di/dt (L > 0) at the limiter's mode.
  double rate(double t, double current, double omega, Limiter limiter) const {
    if (limiter.mode == Limiter::holding) return 0.0;
    return (driver_voltage(t, current, omega, limiter) - hold_voltage(current, omega)) /
           inductance;
  }
  // How far U(t) drives the current beyond the limit at side (> 0: the
  // limiter acts) and how far the supply reaches beyond the hold (< 0: it
  // cannot hold, the current passes the limit), both [V], at |i| = i_max.
  double push_beyond(double t, int side, double omega) const {
    return side * (voltage(t) - hold_voltage(side * current_limit, omega));
  }
  double supply_margin(double t, int side, double omega) const {
    return std::abs(voltage(t)) + side * hold_voltage(side * current_limit, omega);
  }
  // The current without inductance: (U_d - k_e omega) / R with the
  // driver's U_d (the limit held within the supply |U(t)|).
  double quasi_static_current(double t, double omega) const {
    const double u = voltage(t);
    const double free = (u - back_emf_constant * omega) / resistance;
    if (!limited() || std::abs(free) <= current_limit) return free;
    const double side = free > 0.0 ? 1.0 : -1.0;
    const double supply = std::abs(u);
    const double driver = std::clamp(hold_voltage(side * current_limit, omega), -supply, supply);
    return (driver - back_emf_constant * omega) / resistance;
  }
  // The driver's output U_d [V]; `limiter`: its mode (L > 0). Without
  // inductance U_d = R i + k_e omega, which is U(t) where the limit does not act.
  double terminal_voltage(double t, double current, double omega, Limiter limiter) const {
    if (!has_state()) return hold_voltage(current, omega);
    return driver_voltage(t, current, omega, limiter);
  }
  // The rates of the energy account: the electrical work in (with the
  // conversion mismatch (k_t - k_e) i omega, 0 by default) and the copper loss.
  double work_rate(double t, double current, double omega, Limiter limiter) const {
    return terminal_voltage(t, current, omega, limiter) * current +
           (torque_constant - back_emf_constant) * current * omega;
  }
  double copper_loss_rate(double current) const noexcept {
    return resistance * current * current;
  }
  double magnetic_energy(double current) const noexcept {
    return 0.5 * inductance * current * current;
  }

  // Moreau-Jean's step of the armature. Over a step h with the driver's
  // voltage u and the back-EMF at omega_theta = (1 - theta) omega + theta
  // omega+ held, L i' = u - R i - k_e omega_theta is linear with constant
  // coefficients and is integrated exactly (docs/physics/dc_motor.md,
  // "Moreau-Jean"): i(s) = i_inf + (i - i_inf) e^(-s R / L), i_inf =
  // (u - k_e omega_theta) / R, so with x = h R / L
  //   i+     = i_inf + (i - i_inf) e^-x
  //   i_mean = i_inf + (i - i_inf) (1 - e^-x) / x      (the step's mean)
  //   int R i^2 = h R (i_inf^2 + 2 i_inf d (1 - e^-x) / x + d^2 (1 - e^-2x) / 2x),
  //   d = i - i_inf.
  // Linear in the rotor's speed omega+ at the step's end: i_mean = mean +
  // mean_slope omega+, i+ = end + end_slope omega+. The factor e^-x lies in
  // (0, 1) at every step: the current never alternates (the theta-method's
  // (1 - (1 - theta) x) / (1 + theta x) does beyond x = 1 / (1 - theta)); it
  // is the trapezoidal rule's to O(x^3) where the step resolves L / R, and
  // L = 0 (x -> infinity) gives the quasi-static current at omega_theta.
  // Held at the limit (side `held`): i+ = held i_max (L = 0: i_mean =
  // held i_max), i_inf from it; the driver's voltage over the step is
  // R i_inf + k_e omega_theta either way (u where free).
  struct ArmatureStep {
    double steady = 0.0, steady_slope = 0.0;  // i_inf = steady + steady_slope omega+
    double start = 0.0;                       // i at the step's start (L > 0)
    double decay = 0.0, mean_weight = 0.0, square_weight = 0.0;  // e^-x, (1-e^-x)/x, (1-e^-2x)/2x
    double mean = 0.0, mean_slope = 0.0, end = 0.0, end_slope = 0.0;

    double steady_current(double omega_next) const { return steady + steady_slope * omega_next; }
    double mean_current(double omega_next) const { return mean + mean_slope * omega_next; }
    double end_current(double omega_next) const { return end + end_slope * omega_next; }
  };
  ArmatureStep armature_step(double u, double h, double theta, double current, double omega,
                             int held) const {
    ArmatureStep s;
    double rise = 1.0;  // 1 - e^-x (L = 0: x infinite)
    if (has_state()) {
      const double x = h * resistance / inductance;
      rise = -std::expm1(-x);
      s.start = current;
      s.decay = std::exp(-x);
      s.mean_weight = rise / x;
      s.square_weight = -std::expm1(-2.0 * x) / (2.0 * x);
    }
    if (held != 0) {
      s.steady = (held * current_limit - s.start * s.decay) / rise;
    } else {
      s.steady = (u - back_emf_constant * (1.0 - theta) * omega) / resistance;
      s.steady_slope = -theta * back_emf_constant / resistance;
    }
    s.mean = s.steady * (1.0 - s.mean_weight) + s.start * s.mean_weight;
    s.mean_slope = s.steady_slope * (1.0 - s.mean_weight);
    s.end = s.steady * (1.0 - s.decay) + s.start * s.decay;
    s.end_slope = s.steady_slope * (1.0 - s.decay);
    return s;
  }
  // The copper loss over the step [J] and the driver's voltage over it [V]
  // at the step's end speed omega+ (omega_theta: the back-EMF's speed).
  double step_copper_loss(const ArmatureStep& s, double h, double omega_next) const {
    const double steady = s.steady_current(omega_next), d = s.start - steady;
    return h * resistance *
           (steady * steady + 2.0 * steady * d * s.mean_weight + d * d * s.square_weight);
  }
  double step_voltage(const ArmatureStep& s, double omega_theta, double omega_next) const {
    return hold_voltage(s.steady_current(omega_next), omega_theta);
  }
  // The current the step's limit is judged on: i+ (L > 0), i_mean (L = 0).
  double step_current(const ArmatureStep& s, double omega_next) const {
    return has_state() ? s.end_current(omega_next) : s.mean_current(omega_next);
  }
};

// The motor as an element of the drive (model/element.hpp; its file
// cpp/src/model/elements/dc_motor.cpp): `rotor_torque_constant` and
// `rotor_back_emf_constant` are the motor's own, at its shaft (dc's are its
// coordinate's, behind a gear), for its result checks.
std::shared_ptr<const Element> dc_motor_element(const DcMotor& dc, double rotor_torque_constant,
                                                double rotor_back_emf_constant);

}  // namespace leadscrew::model::elements
