// DriveDynamics::solve (model/drive_dynamics.hpp): the accelerations and
// the thread's forces of one mode (ModeSpec: contact, friction, a held
// load), from the state set. Its parts: the mode's given forces (the law's
// viscous term, a preloaded nut's half B), the constraint rows, the flank's
// resultant forces; eq. (3.15)'s friction force by Newton on the affine map
// or, in the Painleve regime, every consistent solution; the prescribed
// slip's stick or slip decision.
#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/flank_lcp.hpp"
#include "leadscrew/model/drive_dynamics.hpp"
#include "constrained_solve.hpp"

namespace leadscrew::model {

using detail::ColumnMatrix;
using detail::ConstraintMatrix;
using detail::SmallVector;
using detail::solve_constrained;

double DriveDynamics::friction_factor(const ModeSpec& spec, double slip_acceleration) const {
  const double factor = model_.flank_factor();
  switch (spec.friction) {
    case FrictionMode::slip:
      // mu' itself for one coefficient (the same bits as before the laws
      // were types); Stribeck's curve at the slip speed otherwise.
      return spec.slip_sign * (plain_coulomb_ ? model_.effective_mu()
                                                     : law_->slip_mu(std::abs(slip_)) * factor);
    case FrictionMode::regularized_velocity:
      if (transverse_)
        return cone_coefficient(slip_, transverse_slip_,
                                cone_mu(std::hypot(slip_, transverse_slip_)));
      return law_->velocity_coefficient(slip_) * factor;
    case FrictionMode::regularized_acceleration:
      return law_->acceleration_coefficient(slip_acceleration) * factor;
    case FrictionMode::bristle:
      // (A transverse slip's bristles relax at the 2-D slip speed.)
      if (transverse_)
        return (law_->bristle_stiffness() * bristle_ + law_->bristle_damping() * bristle_rate()) *
               factor;
      return law_->bristle_coefficient(slip_, bristle_) * factor;
    default:
      return 0.0;
  }
}

// A preloaded nut's and the law's given forces of a mode (ModeForces): which
// rows the mode has, the viscous term, and the nut's half B, set once per
// solve before any row is assembled.
DriveDynamics::ModeForces DriveDynamics::mode_forces(const ModeSpec& spec) const {
  ModeForces m;
  m.normal_multiplier =
      spec.contact == ThreadContact::bilateral || spec.contact == ThreadContact::closed;
  m.stick = spec.friction == FrictionMode::stick;

  // The law's viscous term, a force -viscous gamma along the helix where the
  // flank is in contact and not stuck.
  const bool in_contact = m.normal_multiplier ||
                          (spec.contact == ThreadContact::penalty && penalty_.normal_force != 0.0);
  m.viscous = in_contact && !m.stick && spec.friction != FrictionMode::none
                  ? -law_->viscous() * slip_
                  : 0.0;
  // A preloaded nut slipping: its preload half is a given flank force (N_B^s,
  // T_B^s) of the slip's direction, the multiplier half A's normal force.
  m.nut = model_.preloaded_nut();
  const elements::PreloadedNut* nut = m.nut;
  // Half B at the law's coefficient kappa' (a smooth law, or Stribeck's
  // curve in slip): its given force N_B(kappa') W_N + T_B(kappa') W_T.
  m.kappa_half = nut && preload_at_kappa(spec);
  m.preload_half =
      nut && m.normal_multiplier && spec.friction == FrictionMode::slip && !m.kappa_half;
  m.smooth_half = m.kappa_half && m.normal_multiplier;
  m.half_b_kappa = m.kappa_half ? half_b_coefficient(*nut, spec) : 0.0;  // (eq. 3.15: solve)
  // A lift-off nut on penalty flanks: half B a given force in every mode,
  // the spring's along grad(e) (its slip force in slip).
  m.lift_off_half = nut && nut->lift_off && spec.contact == ThreadContact::penalty;
  m.lift_off_slip = m.lift_off_half && spec.friction == FrictionMode::slip && !m.kappa_half;
  set_lift_off_forces(spec, m);
  // The rotor's friction contact (ModeSpec::rotor): a row of its own where
  // it fixes the rotor's acceleration, else eliminated into the rotor's
  // inverse mass and force (a self-locking stage back-driven: negative).
  const int rotor = model_.rotor();
  m.rotor_fixed = spec.rotor.fixes(1.0 / inverse_mass_[rotor]);
  m.rotor_eliminated = spec.rotor.active && !m.rotor_fixed;
  if (m.rotor_eliminated) {
    const double effective = spec.rotor.a_q / inverse_mass_[rotor] - spec.rotor.a_w;
    if (!(std::abs(effective) > 1e-12 * std::abs(spec.rotor.a_q / inverse_mass_[rotor])))
      m.rotor_singular = true;  // (the stage's Painleve case, k J_s + R = 0)
    else {
      m.eliminated_inverse_mass = inverse_mass_;
      m.eliminated_inverse_mass[rotor] = spec.rotor.a_q / effective;
    }
  }
  return m;
}

// A lift-off nut's half B at half_b_kappa (eq. (3.15) moves it: solve).
void DriveDynamics::set_lift_off_forces(const ModeSpec& spec, ModeForces& m) const {
  const elements::PreloadedNut* nut = m.nut;
  m.lift_off_normal = !m.lift_off_half  ? 0.0
                      : m.kappa_half    ? nut->normal_at(m.half_b_kappa, preload_spring_)
                      : m.lift_off_slip ? nut->normal(spec.slip_sign, preload_spring_)
                                        : nut->side * preload_spring_ / nut->cos_lead;
  if (m.lift_off_half && !m.lift_off_slip && !m.kappa_half && spec.half_b_edge != 0)
    m.lift_off_normal += spec.half_b_share *
                         (nut->normal(spec.half_b_edge, preload_spring_) - m.lift_off_normal);
  m.lift_off_friction = !m.lift_off_half  ? 0.0
                        : m.kappa_half    ? nut->friction_at(m.half_b_kappa, preload_spring_)
                        : m.lift_off_slip ? nut->split_friction(spec.slip_sign, preload_spring_)
                                          : 0.0;
}

// The mode's applied forces f of M a = f + B lambda: the elements' and
// loads', a given friction force and the viscous term along W_T, the nut's
// half B, and a penalty flank's normal force N (with its friction -kappa |N|
// out of stick). normal_force: N on a penalty flank, else 0.
CoordinateVector DriveDynamics::mode_applied_forces(const ModeSpec& spec, const ModeForces& m,
                                                    double kappa, double given_tangential,
                                                    double& normal_force) const {
  const Eigen::VectorXd& normal = model_.normal_direction();
  const Eigen::VectorXd& tangent = model_.tangent_direction();
  const elements::PreloadedNut* nut = m.nut;
  CoordinateVector f = forces_;
  if (m.rotor_eliminated) f[model_.rotor()] -= spec.rotor.r / spec.rotor.a_q;
  f += (given_tangential + m.viscous) * tangent;
  if (m.preload_half)
    f += nut->normal(spec.slip_sign) * normal + nut->friction(spec.slip_sign) * tangent;
  if (m.smooth_half)
    f += nut->normal_at(m.half_b_kappa, nut->preload) * normal +
         nut->friction_at(m.half_b_kappa, nut->preload) * tangent;
  if (m.lift_off_half) f += m.lift_off_normal * normal + m.lift_off_friction * tangent;
  normal_force = 0.0;
  if (spec.contact == ThreadContact::penalty) {
    normal_force = penalty_.normal_force;
    f += normal_force * normal;
    if (!m.stick) f -= kappa * std::abs(normal_force) * tangent;
  }
  return f;
}

// The mode at a friction factor kappa and a given friction force: its
// constraint rows (the flank's normal multiplier with its friction
// -sigma kappa W_T, stick's W_T, the speed-controlled rotor's prescribed
// acceleration, a held load), solved with the applied forces.
void DriveDynamics::evaluate_mode(const ModeSpec& spec, const ModeForces& m, double kappa,
                                  double given_tangential, ModeSolution& out) {
  const elements::Motor& motor = model_.motor();
  const int n = model_.coordinate_count();
  const Eigen::VectorXd& normal = model_.normal_direction();
  const Eigen::VectorXd& tangent = model_.tangent_direction();
  double normal_force = 0.0;
  const CoordinateVector f = mode_applied_forces(spec, m, kappa, given_tangential, normal_force);
  const int nc = (m.normal_multiplier ? 1 : 0) + (m.stick ? 1 : 0) + motor.constraint_count() +
                 (spec.held_load >= 0 ? 1 : 0) + (m.rotor_fixed ? 1 : 0);
  ColumnMatrix B = ColumnMatrix::Zero(n, nc);
  ConstraintMatrix C = ConstraintMatrix::Zero(nc, n);
  SmallVector r = SmallVector::Zero(nc);
  int row = 0, normal_row = -1, stick_row = -1, rotor_row = -1;
  if (m.normal_multiplier) {
    normal_row = row++;
    B.col(normal_row) = normal - spec.sigma * kappa * tangent;
    C.row(normal_row) = normal.transpose();
  }
  if (m.stick) {
    stick_row = row++;
    B.col(stick_row) = tangent;
    C.row(stick_row) = tangent.transpose();
  }
  if (motor.speed_controlled) {
    rotor_row = row++;
    B(motor.rotor, rotor_row) = 1.0;
    C(rotor_row, motor.rotor) = 1.0;
    if (std::isnan(rotor_acceleration_)) rotor_acceleration_ = motor.prescribed_acceleration(t_);
    r[rotor_row] = rotor_acceleration_;
  }
  int stop_row = -1;
  if (spec.held_load >= 0) {
    stop_row = row++;
    B(spec.held_load, stop_row) = 1.0;
    C(stop_row, spec.held_load) = 1.0;
  }
  int friction_row = -1;
  if (m.rotor_fixed) {
    const int rotor = model_.rotor();
    friction_row = row++;
    B(rotor, friction_row) = -1.0;
    C(friction_row, rotor) = spec.rotor.a_w;
    r[friction_row] = spec.rotor.r;
  }
  SmallVector lambda;
  out.regular = solve_constrained(m.rotor_eliminated ? m.eliminated_inverse_mass : inverse_mass_,
                                  f, B, C, r, out.acceleration, lambda);
  if (!out.regular) return;
  if (m.normal_multiplier) normal_force = lambda[normal_row];
  const double stick_force = m.stick ? lambda[stick_row] : 0.0;
  set_thread_forces(spec, m, kappa, given_tangential, normal_force, stick_force, out);
  out.motor_torque = motor.speed_controlled ? lambda[rotor_row] : applied_torque_;
  out.stop_force = stop_row >= 0 ? lambda[stop_row] : 0.0;
  out.rotor_friction =
      m.rotor_fixed ? lambda[friction_row]
      : m.rotor_eliminated
          ? (spec.rotor.r - spec.rotor.a_w * out.acceleration[model_.rotor()]) / spec.rotor.a_q
          : 0.0;
  out.slip_acceleration = tangent.dot(out.acceleration);
}

// The flank's resultant forces of a solved mode: the normal force N and the
// friction (stick's multiplier, or the law's -kappa sigma N, -kappa |N| on a
// penalty flank), with the given friction, the viscous term and the nut's
// half B added (its own parts in preload_normal, preload_friction).
void DriveDynamics::set_thread_forces(const ModeSpec& spec, const ModeForces& m, double kappa,
                                      double given_tangential, double normal_force,
                                      double stick_force, ModeSolution& out) const {
  const elements::PreloadedNut* nut = m.nut;
  out.normal_force = normal_force;
  if (m.stick)
    out.friction_force = stick_force;
  else if (m.normal_multiplier)
    out.friction_force = -kappa * spec.sigma * normal_force;
  else if (spec.contact == ThreadContact::penalty)
    out.friction_force = -kappa * std::abs(normal_force);
  else
    out.friction_force = 0.0;
  out.friction_force += given_tangential + m.viscous;
  if (m.preload_half) {
    out.preload_normal = nut->normal(spec.slip_sign);
    out.normal_force += out.preload_normal;
    out.friction_force += nut->friction(spec.slip_sign);
  }
  if (m.smooth_half) {
    out.preload_normal = nut->normal_at(m.half_b_kappa, nut->preload);
    out.preload_friction = nut->friction_at(m.half_b_kappa, nut->preload);
    out.normal_force += out.preload_normal;
    out.friction_force += out.preload_friction;
  }
  if (m.lift_off_half) {
    out.preload_normal = m.lift_off_normal;
    if (m.kappa_half) out.preload_friction = m.lift_off_friction;
    out.normal_force += m.lift_off_normal;
    out.friction_force += m.lift_off_friction;
  }
}

// LuGre's bristles where a closed exact stop holds the rigid drive: their
// friction is the law's at the held zero slip, -sigma0 z |N|' with z held
// (z' = 0), a function of the state, which the mode's normal row takes as
// any slip's kappa; the stop carries the rest (the Moreau-Jean step's
// stop_holds_bristles, end_stops.md, "LuGre at a closed stop"). A thread
// self-locking at the held rows (|kappa alpha| >= 1) may agree with both
// signs of N: as Moreau-Jean's, the smaller |T| (the root that keeps the
// frictionless rows' sign of N; the other's stop pulls, and the load,
// released, runs into it again: Zeno). Neither: not regular (the rule's
// T = 0 then, off the law; Moreau-Jean lets the stop go there).
ModeSolution DriveDynamics::solve_held_bristles(const ModeSpec& spec, const ModeForces& m) {
  ModeSolution chosen;
  chosen.regular = false;
  for (const int sigma : {1, -1}) {
    ModeSpec side = spec;
    side.sigma = sigma;
    ModeSolution s;
    evaluate_mode(side, m, friction_factor(side, 0.0), side.given_tangential, s);
    if (!s.regular || !(sigma * s.normal_force >= 0.0)) continue;
    if (!chosen.regular || std::abs(s.friction_force) < std::abs(chosen.friction_force))
      chosen = s;
  }
  return chosen;
}

ModeSolution DriveDynamics::solve(const ModeSpec& spec) {
  const int n = model_.coordinate_count();
  ModeForces m = mode_forces(spec);
  const elements::PreloadedNut* nut = m.nut;
  ModeSolution solution;
  if (m.rotor_singular) {
    solution.regular = false;  // (the stage's Painleve case, k J_s + R = 0)
    return solution;
  }
  // A closed exact stop whose row and the thread's fix every velocity (the
  // rigid drive without play, or with its flank closed): the thread's
  // friction and the stop's force are one unknown too many. The rule
  // (docs/physics/end_stops.md, "The rigid drive at a closed stop"): the
  // stop carries what it can, the friction nothing while it holds; the
  // stop opens where its force would pull, and the thread decides then.
  // LuGre's bristles are no such unknown (solve_held_bristles). (The other
  // smooth laws' friction is 0 at zero slip: the rule's.)
  if (spec.held_load >= 0 && m.normal_multiplier && spec.friction != FrictionMode::none &&
      2 + model_.motor().constraint_count() >= n) {
    if (spec.friction == FrictionMode::bristle && nut == nullptr) {
      const ModeSolution held = solve_held_bristles(spec, m);
      if (held.regular) return held;
    }
    ModeSpec base = spec;
    base.friction = FrictionMode::none;
    base.given_tangential = 0.0;
    return solve(base);
  }
  if (m.stick && m.normal_multiplier && (slip_prescribed_ || (m.rotor_fixed && rotor_fixes_slip_))) {
    // The stick row would repeat the others (every velocity is fixed): the
    // friction force is statically indeterminate, chosen as
    // prescribed_slip_decision does.
    ModeSpec base = spec;
    base.friction = FrictionMode::none;
    const friction::FlankLcpResult decision = prescribed_slip_decision(
        base, spec.contact == ThreadContact::closed ? spec.sigma : 0);
    base.given_tangential = decision.friction_force;
    solution = solve(base);
    if (nut) solution.preload_normal = nut->normal(nut->edge_of(solution.friction_force));
    return solution;
  }
  if ((m.smooth_half || (m.lift_off_half && m.kappa_half)) &&
      spec.friction == FrictionMode::regularized_acceleration) {
    // Eq. (3.15) on a preloaded nut's halves (preloaded_acceleration_law):
    // the mode at a given coefficient kappa', its slip acceleration.
    auto at = [&](double kappa) {
      m.half_b_kappa = kappa;
      set_lift_off_forces(spec, m);
      evaluate_mode(spec, m, kappa, spec.given_tangential, solution);
      return solution.regular ? solution.slip_acceleration
                              : std::numeric_limits<double>::quiet_NaN();
    };
    at(preloaded_acceleration_law(spec, m.smooth_half, at));
    return solution;
  }
  if (spec.friction == FrictionMode::regularized_acceleration &&
      spec.contact == ThreadContact::bilateral && painleve_possible_)
    return solve_acceleration_law(spec);
  if (spec.friction != FrictionMode::regularized_acceleration ||
      spec.contact == ThreadContact::open) {
    evaluate_mode(spec, m, friction_factor(spec, 0.0), spec.given_tangential, solution);
    // In stick the multipliers are the net forces; half B at the edge the
    // friction force heads for (its preload_normal, for the sign of half A's).
    if (nut && m.stick && m.normal_multiplier && solution.regular)
      solution.preload_normal = nut->normal(nut->edge_of(solution.friction_force));
    return solution;
  }
  return solve_acceleration_by_newton(spec, m);
}

// Eq. (3.15) on the flank: kappa depends on the slip acceleration it
// produces. With the friction force T as the unknown (the law's kappa set
// to 0 and T given), the solution is affine in T: normal force N_0 +
// alpha T, slip acceleration x_0 + d T, accelerations a_0 + T (a_1 - a_0).
// The law T = -kappa(x) m with m = sigma N (a flank's multiplier) or |N|
// (a penalty flank's given force) is one smooth scalar equation
//   Phi(T) = T + kappa(x_0 + d T) m(T) = 0,
// solved by Newton to round-off, safeguarded by bisection on a bracket:
// |T| = |kappa| m < mu' (|N_0| + |alpha| |T|) bounds it by
// mu' |N_0| / (1 - mu' |alpha|). (An Illinois iteration on x that the
// rhs ran before stopped at 4e-16 of the bracket's slip accelerations,
// 1e-7 relative to a small root: CVODE's difference-quotient Jacobian of
// that noise failed Newton at every step, 225,000 failures in 0.2 s.)
ModeSolution DriveDynamics::solve_acceleration_by_newton(const ModeSpec& spec,
                                                         const ModeForces& m) {
  ModeSolution solution, zero, unit;
  evaluate_mode(spec, m, 0.0, spec.given_tangential, zero);
  evaluate_mode(spec, m, 0.0, spec.given_tangential + 1.0, unit);
  if (!zero.regular || !unit.regular) {
    solution.regular = false;
    return solution;
  }
  const double mu = model_.effective_mu();
  const bool penalty = spec.contact == ThreadContact::penalty;
  const double n0 = zero.normal_force, alpha = unit.normal_force - n0;
  const double x0 = zero.slip_acceleration, d = unit.slip_acceleration - x0;
  const double k_v = law_->gain();
  auto multiplier = [&](double T) { return penalty ? std::abs(n0) : spec.sigma * (n0 + alpha * T); };
  auto phi = [&](double T) {
    return T + kTwoOverPi * mu * std::atan(k_v * (x0 + d * T)) * multiplier(T);
  };
  if (!(mu * std::abs(alpha) < 1.0) || !(d >= 0.0))
    throw SimulationError(t_, "eq. (3.15) has no unique friction force here (mu' |dN/dT| = " +
                                  format_value(mu * std::abs(alpha)) + ")",
                          "lower friction.mu or use arctan_velocity");
  const double bound = mu * std::abs(n0) / (1.0 - mu * std::abs(alpha));
  double low = -bound, high = bound, T = 0.0;
  double value = phi(T);
  for (int iteration = 0; iteration < 200 && value != 0.0; ++iteration) {
    (value < 0.0 ? low : high) = T;
    const double x = x0 + d * T;
    const double u = k_v * x;
    const double slope = 1.0 + kTwoOverPi * mu *
                                   (k_v * d / (1.0 + u * u) * multiplier(T) +
                                    std::atan(u) * (penalty ? 0.0 : spec.sigma * alpha));
    double next = slope > 0.0 ? T - value / slope : 0.5 * (low + high);
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    if (std::abs(next - T) <= 4.0 * std::numeric_limits<double>::epsilon() * std::abs(T) ||
        high - low <= 4.0 * std::numeric_limits<double>::epsilon() * bound) {
      T = next;
      break;
    }
    T = next;
    value = phi(T);
  }
  solution = zero;
  solution.acceleration = zero.acceleration + T * (unit.acceleration - zero.acceleration);
  solution.normal_force = n0 + alpha * T;
  solution.friction_force = zero.friction_force + T;
  solution.motor_torque = zero.motor_torque + T * (unit.motor_torque - zero.motor_torque);
  solution.slip_acceleration = x0 + d * T;
  return solution;
}

// Eq. (3.15) on the thread without play, every consistent solution. With
// the friction force T as the unknown, the normal force and the slip
// acceleration are affine in it (every other constraint enforced):
// N = N_0 + alpha T, x = x_0 + d T (d > 0), and the law with the normal
// force's sign sigma = sign N consistent by construction is
//   Phi(T) = T + kappa(x) |N| = 0,   kappa(x) = (2/pi) mu' atan(k_V x).
// Phi runs from -inf to +inf (|kappa| < mu' and kappa takes the sign of T for
// large |T|), so a solution always exists: the law never jams for lack of a
// consistent sign, unlike exact Coulomb in slip. Phi' = 1 + kappa' d |N| +
// kappa sigma alpha > 0 when mu' |alpha| = mu' |G_NT| / G_NN < 1, so the
// solution is unique outside the Painleve regime (the general solve above
// handles that case). Inside it several solutions can coexist: the friction
// factor of one slip acceleration cancels the inertia the normal force sees
// (|kappa| > G_NN / |G_NT| somewhere between them). All of them are found on
// the compact interval u = atan(k_V x) in (-pi/2, pi/2), where
//   H(u) = cos(u) Phi = C cos u + D sin u + (2/pi) mu' u |A cos u + B sin u|
// (C = -x_0 / d, D = 1 / (d k_V), A = N_0 - alpha x_0 / d, B = alpha / (d k_V))
// has H(-pi/2) < 0 < H(pi/2) and |H''| <= hypot(C, D) + (2/pi) mu' hypot(A, B)
// (2 + pi/2) between the kink of |N|: a scan with certified steps (no sign
// change passed unseen; a double root narrower than 1e-12 is taken for a
// touch) and Illinois at every sign change.
ModeSolution DriveDynamics::solve_acceleration_law(const ModeSpec& spec) {
  ModeSpec free = spec;
  free.friction = FrictionMode::none;
  free.given_tangential = 0.0;
  const ModeSolution without = solve(free);
  free.given_tangential = 1.0;
  const ModeSolution unit = solve(free);
  ModeSolution solution;
  if (!without.regular || !unit.regular) return solution;
  const double n0 = without.normal_force, x0 = without.slip_acceleration;
  const double alpha = unit.normal_force - n0, d = unit.slip_acceleration - x0;
  const double k_v = law_->gain(), mu = model_.effective_mu();
  if (!(d > 0.0)) return solution;
  const double C = -x0 / d, D = 1.0 / (d * k_v), A = n0 - alpha * x0 / d, B = alpha / (d * k_v);
  const double factor = kTwoOverPi * mu;
  auto H = [&](double u) {
    const double c = std::cos(u), s = std::sin(u);
    return C * c + D * s + factor * u * std::abs(A * c + B * s);
  };
  auto slope = [&](double u) {
    const double c = std::cos(u), s = std::sin(u);
    const double inner = A * c + B * s;
    const double sign = (inner > 0.0) - (inner < 0.0);
    return -C * s + D * c + factor * (std::abs(inner) + u * sign * (-A * s + B * c));
  };
  const double half_pi = 1.57079632679489661923;
  const double curvature =
      (std::hypot(C, D) + factor * std::hypot(A, B) * (2.0 + half_pi)) * (1.0 + 1e-9);
  // The kink of |N| splits the interval (the bound holds on each side).
  const double kink = B != 0.0 ? std::atan(-A / B) : half_pi;
  const double floor_step = 1e-12 * half_pi;
  // Roots of H in increasing u. Several make the drive jam (the caller
  // raises), so which one is returned then does not matter: the first.
  double chosen = 0.0;
  int count = 0;
  double u = -half_pi;
  double value = H(u);
  for (long step = 0; step < 1000000 && u < half_pi; ++step) {
    double h = floor_step;
    if (value != 0.0) {
      const double g = std::abs(slope(u)), f = std::abs(value);
      h = std::max(2.0 * f / (g + std::sqrt(g * g + 2.0 * curvature * f)), floor_step);
    }
    double next = std::min(u + h, half_pi);
    if (u < kink && next > kink) next = kink;
    const double next_value = H(next);
    const bool root_at_next = next_value == 0.0;
    const bool crossing = value != 0.0 && next_value != 0.0 && (next_value > 0.0) != (value > 0.0);
    if (root_at_next || crossing) {
      // (-H if H falls there: first_negative wants f(low) >= 0)
      const double direction = value > 0.0 ? 1.0 : -1.0;
      if (count++ == 0)
        chosen = root_at_next ? next
                              : first_negative([&](double x) { return direction * H(x); }, u,
                                               next, 1e-16);
    }
    u = next;
    value = next_value;
  }
  if (count == 0) return solution;  // unreachable: H changes sign on the interval
  const double x = std::tan(chosen) / k_v;
  free.given_tangential = (x - x0) / d;  // the friction force T
  solution = solve(free);
  solution.consistent_solutions = count;
  return solution;
}

friction::FlankLcpResult DriveDynamics::prescribed_slip_decision(const ModeSpec& base,
                                                                 int sigma) {
  ModeSpec spec = base;
  spec.given_tangential = 0.0;
  const ModeSolution without = solve(spec);
  spec.given_tangential = 1.0;
  const ModeSolution unit = solve(spec);
  friction::FlankLcpResult result;
  if (!without.regular || !unit.regular) return result;
  // The prescribed slip acceleration; zero within the round-off of its terms.
  const double c = without.slip_acceleration;
  const double noise = 64.0 * std::numeric_limits<double>::epsilon() *
                       model_.tangent_direction().cwiseProduct(without.acceleration).cwiseAbs().sum();
  // sigma 0: the thread without play, whose normal force takes either sign
  // (the one it has without friction; friction within the cone keeps it).
  if (const elements::PreloadedNut* nut = model_.preloaded_nut())
    return nut->prescribed_slip(c, std::abs(c) <= noise, unit.normal_force - without.normal_force,
                                without.normal_force, without.motor_torque,
                                unit.motor_torque - without.motor_torque);
  if (sigma == 0) sigma = without.normal_force >= 0.0 ? 1 : -1;
  // (Held by the rotor's stuck contact: the least |Q|, its torque.)
  const bool by_rotor = !model_.motor().speed_controlled;
  const double held0 = by_rotor ? without.rotor_friction : without.motor_torque;
  const double held1 = (by_rotor ? unit.rotor_friction : unit.motor_torque) - held0;
  // (The rotor's stuck contact holds the thread at rest: its static cone,
  // mu_static', as Moreau-Jean's "stuck together".)
  return friction::solve_flank_prescribed_slip(
      c, std::abs(c) <= noise, unit.normal_force - without.normal_force, without.normal_force,
      by_rotor ? model_.effective_mu_static() : model_.effective_mu(), sigma, held0, held1);
}

ModeSolution DriveDynamics::solve_with_forces(const ModeSpec& spec,
                                             const CoordinateVector& forces) {
  const CoordinateVector own = forces_;
  forces_ = forces;
  const ModeSolution solution = solve(spec);
  forces_ = own;
  return solution;
}

}  // namespace leadscrew::model
