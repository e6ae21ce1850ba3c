// DriveMoreau (moreau.hpp): an exact end stop on the rigid drive, where
// its row and the thread's fix every velocity of the Moreau-Jean step
// (docs/physics/end_stops.md, "The rigid drive at a closed stop").
#include <algorithm>
#include <cmath>
#include <limits>

#include "moreau.hpp"

namespace leadscrew::model::drive {

// The step where an exact stop's row and the thread's fix every velocity
// (the rigid drive at its stop; solve_thread): the stop's impulse and the
// thread's friction impulse are one unknown too many. At zero slip (a held
// step, or a closing one without rebound) the stop carries it all and the
// friction nothing (end_stops.md, "The rigid drive at a closed stop"); a
// rebound that slips the thread at the step's end (Newton's target
// -e u'-) slides it with the friction at the cone's edge against that
// slip, N = beta + alpha T, T = -mu' s |N| (the prescribed slip's; on the
// velocity level the impact's whole normal impulse carries it, which may
// book more loss than the impact has: the step's restitution is then
// reduced as a closing flank's, DriveMoreau::step); where
// none is consistent (mu' |alpha| >= 1: the self-locking thread, which the
// stop cannot back-drive) the stop's target is 0: no rebound, as the
// event-driven impact's held stop.
DriveMoreau::Impulses DriveMoreau::stop_holds(const Impulses& without, const Impulses& unit,
                                              double normal_target, double rotor_target,
                                              bool& stick) {
  const Eigen::VectorXd& tangent = model_.tangent_direction();
  const double c = tangent.dot(without.velocity);
  const double noise = 64.0 * std::numeric_limits<double>::epsilon() *
                       (tangent.cwiseProduct(without.velocity).cwiseAbs().sum() +
                        tangent.cwiseProduct(free_).cwiseAbs().sum());
  bool targets_zero = normal_target == 0.0 && !p_.speed_controlled;
  for (int k = 0; k < kMaxStops; ++k)
    if (stop_active_[k] && stop_target_[k] != 0.0) targets_zero = false;
  if (std::abs(c) <= noise || targets_zero) {
    Impulses held = without;
    if (targets_zero) held.velocity.setZero();  // (their round-off)
    held.friction = 0.0;
    stick = true;
    return held;
  }
  // (A transverse slip's cone at the prescribed slip (c, w+): its helix
  // component mu'(s0) |c| / |(c, w+)|, the cone's direction, whose
  // transverse rest book_transverse puts on the cone; transverse_slip.cpp.)
  const double mu = transverse_state_ >= 0 && transverse_next_ != 0.0
                        ? transverse_mu_ * std::abs(c) / std::hypot(c, transverse_next_)
                        : model_.effective_mu();
  const double beta = without.normal, alpha = unit.normal - without.normal;
  const int s = c > 0.0 ? 1 : -1;
  for (const int sigma : {1, -1}) {
    const double scale = 1.0 + mu * s * sigma * alpha;
    if (!(scale > 0.0)) continue;
    const double friction = -mu * s * sigma * beta / scale;
    if (sigma * (beta + alpha * friction) < 0.0) continue;
    Impulses slid = solve(true, normal_target, rotor_target, friction);
    slid.friction = friction;
    stick = false;
    return slid;
  }
  for (int k = 0; k < kMaxStops; ++k)
    if (stop_active_[k]) stop_target_[k] = 0.0;
  Impulses held = solve(true, normal_target, rotor_target, 0.0);
  if (normal_target == 0.0 && !p_.speed_controlled) held.velocity.setZero();
  held.friction = 0.0;
  stick = true;
  return held;
}

// An active exact stop's row and the thread's without play (or its closed
// flank) fix every velocity: the rigid drive at its stop.
bool DriveMoreau::stops_fix_every_velocity() const {
  if (model_.thread_pair().penalty()) return false;
  int rows = 1 + (p_.speed_controlled ? 1 : 0);
  bool stop = false;
  for (int k = 0; k < kMaxStops; ++k)
    if (stop_active_[k]) ++rows, stop = true;
  return stop && rows >= model_.coordinate_count();
}

// An exact stop closing with e > 0 in a step whose rows fix every
// velocity, with friction in the thread (stop_holds slides the thread at
// the cone's edge): the rebound may create energy.
bool DriveMoreau::restitution_through_thread() const {
  if (dynamics_.law().frictionless() || !stops_fix_every_velocity()) return false;
  for (int k = 0; k < kMaxStops; ++k)
    if (stop_active_[k] && stop_closing_[k] && stop_target_[k] != 0.0) return true;
  return false;
}

// A held exact stop (its gap closed at the start) whose load separates from
// it at the start (-side du0 > 0) but which the step's forces press: as a
// held flank (held_flank_target, moreau_flanks.cpp), its row at u'_theta =
// 0, -side u'+ = -(1 - theta) / theta (-side du0). At u'+ = 0 its impulse P
// did the work P (1 - theta) (-side du0) > 0, energy created: a flexible
// screw ringing at the step's frequency (theta = 1/2) pressed the load onto
// its stop that way, 9.7e-7 J in one frictionless step of a run whose work
// was 4.4e-4 J (tests/test_moreau_exact_flank_held.py).
double DriveMoreau::held_stop_target(int side, double du0, double theta) const {
  const double separating = -side * du0;
  if (!(separating > 0.0) || !(theta > 0.0)) return 0.0;
  return -(1.0 - theta) / theta * separating;
}

// As a closing flank's (step): the largest share of the stops' restitution
// up to 1 whose step creates no more energy than its plastic version, by
// bisection (the velocity level's friction impulse at the cone's edge of
// the whole impact's normal impulse, Kane and Levinson's paradox).
void DriveMoreau::limit_stop_restitution(double t, double h, double theta, const double* y,
                                         double* y_next, double excess, double play_rate) {
  const StepAccount first = energy_created(t, h, y, y_next);
  auto retake = [&](double share) {
    friction_excess_ = excess;
    play_rate_ = play_rate;
    stop_share_ = share;
    take_step(t, h, theta, y, y_next, p_.restitution);
    return energy_created(t, h, y, y_next);
  };
  const StepAccount plastic = retake(0.0);
  const double allowed =
      std::max(plastic.created, 0.0) + std::max(first.round_off, plastic.round_off);
  if (first.created <= allowed) {
    retake(1.0);
    return;
  }
  double low = 0.0, high = 1.0;
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double middle = 0.5 * (low + high);
    (retake(middle).created <= allowed ? low : high) = middle;
  }
  retake(low);
}

}  // namespace leadscrew::model::drive
