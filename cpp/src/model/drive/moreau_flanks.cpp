// DriveMoreau (moreau.hpp): a penalty flank's part of the Moreau-Jean step
// (bistop, cubic; docs/physics/drive_models.md, "Moreau-Jean on penalty
// flanks"): its normal impulse over the step and its Newton update (the
// discrete gradient linearised at the step's end, released where it would
// pull). Its force's linearisation and loss are moreau_contacts::PenaltyFlank,
// its friction the thread's flank LCP (DriveMoreau::solve_thread, moreau.cpp).
#include "moreau.hpp"

#include <cmath>

namespace leadscrew::model::drive {

double DriveMoreau::flank_impulse(double h, double theta, const CoordinateVector& v0,
                                  const CoordinateVector& v1) const {
  const elements::ThreadPair& thread = model_.thread_pair();
  const double rate = thread.play_gradient().dot((1.0 - theta) * v0 + theta * v1);
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
  const double rate = thread.play_gradient().dot((1.0 - theta) * v0 + theta * impulses.velocity);
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
