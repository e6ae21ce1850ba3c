// DriveMoreau (moreau.hpp): LuGre's bristles where an exact end stop's row
// and the thread's fix every velocity of the Moreau-Jean step (the rigid
// drive at its stop, a nut-driven flexible nut's load on its stop, without
// play: exact play there is refused with the smooth laws,
// elements/end_stops.cpp; docs/physics/end_stops.md, "LuGre at a closed
// stop").
//
// With every velocity fixed the thread's slip gamma+ = c is the rows' (0
// where the stop holds, Newton's rebound's slip where it throws the load
// back), and the friction impulse moves only the rows' impulses: the
// thread's normal impulse P_N = beta + alpha P_T and the stop's. A set-
// valued law leaves P_T free in its cone there (stop_holds' rule: the
// stop carries it all); LuGre's friction is a function of the state: the
// bristles take their implicit Euler step at the rows' slip,
//   z+ = (z0 + h c) / (1 + h sigma0 |c| / mu(|c|))   (z+ = z0 at c = 0),
// and the friction impulse is the law's at (c, z+),
//   P_T = -kappa |P_N| - h sigma2 c,  kappa = (sigma0 z+ + sigma1 (z+ - z0) / h) / cos(beta/2),
// a constant kappa (d = 0): on the side s = sign(P_N) it is linear,
//   P_T = -(kappa s beta + h sigma2 c) / (1 + kappa s alpha),
// taken where s P_N >= 0. The stop carries the rest of the load (its
// impulse; a stop whose impulse pulls is released by update_stops and the
// step solved again without it). Where the thread is self-locking at the
// held rows (|kappa alpha| >= 1: the friction's normal impulse drives its
// own friction; alpha is cot(lead)-like there, 63 on the thesis thread) no
// friction may agree with the rows: the bristles' friction could hold the
// load only with a normal impulse that needs more friction again. The
// load's push into the stop has then turned (the rows' frictionless normal
// impulse beta has the sign opposite to the hold's), and the stop lets go:
// the step is solved without it (solve_thread), the self-locking thread's
// bristles holding the load on their own. Held at c = 0 the bristles keep their
// deflection and their force, which neither works nor stores energy (the
// row reports zero slip, as the set-valued hold's).
#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/law.hpp"
#include "moreau.hpp"

namespace leadscrew::model::drive {

namespace {

// The friction impulse of the held rows at the law's constant coefficient
// kappa (viscous: h sigma2 c): the root of P + kappa |beta + alpha P|
// + viscous = 0 on a side whose normal impulse agrees (sigma_fixed: a
// flank's one side; 0: either). Where kappa |alpha| < 1 the function rises
// with P: one root. Beyond (the thread self-locking against the stop) two
// roots may agree: the smaller friction is taken, the root that continues
// the frictionless rows' normal impulse beta (its sign; the other flips
// it); none: NaN.
double held_friction(double kappa, double viscous, double alpha, double beta, int sigma_fixed) {
  double chosen = std::numeric_limits<double>::quiet_NaN();
  for (const int s : {1, -1}) {
    if (sigma_fixed != 0 && s != sigma_fixed) continue;
    const double scale = 1.0 + kappa * s * alpha;
    if (scale == 0.0) continue;
    const double friction = -(kappa * s * beta + viscous) / scale;
    if (!(s * (beta + alpha * friction) >= 0.0)) continue;
    if (std::isnan(chosen) || std::abs(friction) < std::abs(chosen)) chosen = friction;
  }
  return chosen;
}

}  // namespace

bool DriveMoreau::stop_holds_bristles(double h, int sigma_fixed, const Impulses& without,
                                      const Impulses& unit, double normal_target,
                                      double rotor_target, Impulses& impulses, bool& stick) {
  const Eigen::VectorXd& tangent = model_.tangent_direction();
  const double noise = 64.0 * std::numeric_limits<double>::epsilon() *
                       (tangent.cwiseProduct(without.velocity).cwiseAbs().sum() +
                        tangent.cwiseProduct(free_).cwiseAbs().sum());
  double beta = without.normal, alpha = unit.normal - without.normal;
  const double viscous = model_.law().viscous() * h;
  // The rebound first (the rows' slip c), then, where no friction agrees
  // with it, the held step without rebound (as stop_holds: the stop's
  // target 0).
  for (int attempt = 0; attempt < 2; ++attempt) {
    bool targets_zero = normal_target == 0.0 && !p_.speed_controlled;
    for (int k = 0; k < kMaxStops; ++k)
      if (stop_active_[k] && stop_target_[k] != 0.0) targets_zero = false;
    double c = attempt == 0 ? tangent.dot(without.velocity) : 0.0;
    const bool held = std::abs(c) <= noise || targets_zero;
    if (held) c = 0.0;  // (its round-off: z+ = z0 exactly)
    const double kappa = smooth_coefficient(c, h);
    // (A rebound through a thread self-locking at the held rows, |kappa
    // alpha| >= 1, is not taken: the stop's target 0, as stop_holds'.)
    const double friction = held || std::abs(kappa * alpha) < 1.0
                                ? held_friction(kappa, viscous * c, alpha, beta, sigma_fixed)
                                : std::numeric_limits<double>::quiet_NaN();
    if (std::isnan(friction)) {
      if (held) return false;
      for (int k = 0; k < kMaxStops; ++k)
        if (stop_active_[k]) stop_target_[k] = 0.0;
      // (the rows' impulses at the new targets)
      beta = solve(true, normal_target, rotor_target, 0.0).normal;
      alpha = solve(true, normal_target, rotor_target, 1.0).normal - beta;
      continue;
    }
    impulses = solve(true, normal_target, rotor_target, friction);
    if (held && targets_zero) impulses.velocity.setZero();  // (their round-off)
    impulses.friction = friction;
    impulses.law_slip = c;  // (the rows' slip: the law's, z+'s)
    stick = held;
    return true;
  }
  return false;
}

DriveMoreau::Impulses DriveMoreau::bristles_at_held_stop(
    double t, double h, double theta, const CoordinateVector& v0, double normal_target,
    double rotor_target, int sigma_fixed, const Impulses& without, const Impulses& unit,
    bool& contact, bool& stick) {
  Impulses impulses;
  if (stop_holds_bristles(h, sigma_fixed, without, unit, normal_target, rotor_target, impulses,
                          stick))
    return impulses;
  const std::vector<elements::ExactEndStop>& exact = model_.elements().exact_stops;
  bool let_go[kMaxStops] = {false, false};
  for (std::size_t k = 0; k < exact.size(); ++k) {
    let_go[k] = stop_active_[k];
    stop_active_[k] = false;
  }
  impulses = solve_thread(t, h, theta, v0, normal_target, rotor_target, sigma_fixed, contact,
                          stick);
  // (A step without the stop that runs into it again: no state of the
  // step is consistent.)
  for (std::size_t k = 0; k < exact.size(); ++k)
    if (let_go[k] && exact[k].side * impulses.velocity[exact[k].coordinate] > 0.0)
      throw JammingError(t, "no friction impulse of friction.law = \"" + p_.friction +
                                "\" agrees with the thread's normal impulse where the exact "
                                "end stop holds the load, and the step without the stop runs "
                                "into it (dt = " + format_value(h) + " s); " +
                                dynamics_.jamming_report(),
                         "reduce the friction or the lead angle");
  return impulses;
}

}  // namespace leadscrew::model::drive
