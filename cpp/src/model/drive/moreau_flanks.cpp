// DriveMoreau (moreau.hpp): the flanks' parts of the Moreau-Jean step. A
// penalty flank's (bistop, cubic; docs/physics/drive_models.md, "Moreau-Jean
// on penalty flanks"): its normal impulse over the step and its Newton
// update (the discrete gradient linearised at the step's end, released where
// it would pull). Its force's linearisation and loss are
// moreau_contacts::PenaltyFlank, its friction the thread's flank LCP
// (DriveMoreau::solve_thread, moreau.cpp). An exact flank's: the contact of
// a step that ends beyond it (exact_flank_closes).
#include "moreau.hpp"

#include <cmath>

namespace leadscrew::model::drive {

// Exact play: plan_contacts activates a flank where the play and its rate
// at the step's start predict it closes, e0 + h e'0 beyond the half
// clearance; that prediction leaves out the step's forces. A flank that
// carries the springs' load at rest (a holding drive: e0 at the flank, e'0
// zero) is predicted open wherever round-off leaves e0 a few 1e-21 m inside
// the clearance; the step without the contact then released the loaded
// springs (the shipped seat_adjuster held by its thread at theta = 1/2: 10
// rad/s on the screw in one step, the flank 5e-6 m deep, the drive turning
// 0.13 rad over 0.2 s where it holds). So a step planned open whose result
// ends beyond a flank, |e0 + h grad e . v_theta| > c / 2, is a step that
// closes it: taken again with its contact (the LCP's normal impulse pushes
// or the flank separates, as on a step the prediction closes). Its target is
// W_N v+ = 0 (W_N v_theta = 0 where the start separates: held_flank_target),
// without Newton's restitution: the step's forces, not the
// start's velocity, close the flank (the approach at the start is below the
// clearance left over h), and so the step ends at most h (1 - theta) e'0
// short of the flank and holds there while loaded; a restitution there
// would be taken at every step of the hold (each is "closing"), at three
// solves a step (Newton's target, the plastic one, the account's) for a
// rebound of that small approach. Before, such a step ran into the flank
// unopposed, and the next one met it passed (target 0 too) and kept the
// penetration. It is decided once: a flank activated here stays active for
// the step's passes.
bool DriveMoreau::exact_flank_closes(StepState& s) const {
  const elements::ThreadPair& thread = model_.thread_pair();
  if (!thread.exact_play() || s.contact_at_start) return false;
  const double half = 0.5 * p_.clearance;
  const double end = s.play0 + s.h * thread.play_gradient().dot((1.0 - s.theta) * s.v0 +
                                                                s.theta * s.impulses.velocity);
  if (!(std::abs(end) > half)) return false;
  s.contact_at_start = true;
  s.sigma_fixed = end > 0.0 ? -1 : 1;
  s.normal_target = held_flank_target(s);
  s.restituting = false;
  return true;
}

// The target of an exact flank the step holds (not the one Newton's
// restitution closes): W_N v+ = 0, or, where the flank separates at the
// step's start (sigma W_N v0 > 0), W_N v_theta = 0. The step's account
// books the normal impulse's work P_N W_N v_theta (result_checks.md,
// "Moreau-Jean time stepping": the residual's term -P_N g_N,theta); at
// W_N v+ = 0 that is P_N (1 - theta) W_N v0, which creates energy where
// the start separates and the step's forces press the flank (sigma P_N >
// 0): the play beyond the flank or the nut's stiff mode ringing at the
// step's frequency (theta = 1/2 does not damp it) turned it back into the
// flank within the step, and one stuck step of a self-locking flexible nut
// created 0.49 J, 1.5e4 J over the run at dt / 4 (drive-train fuzz case
// 9717, seed 20261127). At W_N v_theta = 0 the flank's term is zero (the
// LCP's complementarity: P_N = 0 or g_N,theta = 0) and the play moves no
// further into the flank over the step (q1 = q0 + h v_theta); an
// approaching start keeps W_N v+ = 0, whose term P_N (1 - theta) W_N v0
// dissipates. (theta = 0: v_theta = v0, which no impulse changes.)
double DriveMoreau::held_flank_target(const StepState& s) const {
  const double normal_rate = model_.normal_direction().dot(s.v0);
  if (!(s.sigma_fixed * normal_rate > 0.0) || !(s.theta > 0.0)) return 0.0;
  return -(1.0 - s.theta) / s.theta * normal_rate;
}

double DriveMoreau::flank_impulse(double h, double theta, const CoordinateVector& v0,
                                  const CoordinateVector& v1) const {
  const elements::ThreadPair& thread = model_.thread_pair();
  const double rate = theta_dot(thread.play_gradient(), v0, v1, theta);
  // (generalized force -F grad e = (-F / cos(a)) W_N)
  return -h * flank_.force(flank_.e0 + h * rate, rate) / thread.cos_lead();
}

// The penalty flank from the step's result: released where its force over
// the step would pull; else linearised again at the step's end where that
// moved beyond round-off (Newton on the discrete gradient). True where it
// changed.
bool DriveMoreau::update_flank(double h, double theta, const CoordinateVector& v0,
                               const Impulses& impulses) {
  const elements::ThreadPair& thread = model_.thread_pair();
  const double rate = theta_dot(thread.play_gradient(), v0, impulses.velocity, theta);
  const double end = flank_.e0 + h * rate;
  if (flank_.released) {
    // (Without a force the step runs into a flank, U(e1) > U(e0): its
    // spring alone, which pushes.)
    if (flank_.undamped || !(thread.flank_potential(end) > flank_.potential0))
      return false;
    flank_.released = false;
    flank_.undamped = true;
    flank_.linearise(thread, flank_.e1k);
    return true;
  }
  // (The force at the step's end, not its linearisation's; the next
  // linearisation where Newton takes the step's end itself.)
  moreau_contacts::PenaltyFlank at_end = flank_;
  const bool active = flank_.active();
  if (active) {
    at_end.linearise(thread, end);
    if (at_end.side * (at_end.secant + at_end.damping * rate) < 0.0) {
      flank_.released = true;
      return true;
    }
  }
  const double scale = std::max(std::abs(flank_.e0), std::abs(end));
  if (std::abs(end - flank_.e1k) <= 1e-13 * scale) return false;
  // (The fixed point lies beyond e1k on end's side: the bracket narrows.)
  (end > flank_.e1k ? flank_.low : flank_.high) = flank_.e1k;
  if (!(flank_.high - flank_.low > 1e-13 * scale)) return false;
  const double next = end > flank_.low && end < flank_.high
                          ? end
                          : 0.5 * (flank_.low + flank_.high);
  const moreau_contacts::PenaltyFlank before = flank_;
  if (active && next == end) {  // (at_end's, as linearise(thread, next) gives it)
    at_end.low = flank_.low;
    at_end.high = flank_.high;
    flank_ = at_end;
  } else {
    flank_.linearise(thread, next);
  }
  return flank_.secant != before.secant || flank_.slope != before.slope ||
         flank_.damping != before.damping;
}

}  // namespace leadscrew::model::drive
