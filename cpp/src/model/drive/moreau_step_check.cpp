// DriveMoreau (moreau.hpp): the check that a Moreau-Jean step resolves the
// drive's stiffness, the flank's friction impulse coupling into its normal
// impulse through the iteration matrix (a jam of the time discretization
// where mu' |alpha| >= 1), and the longest step that resolves it.
#include "moreau.hpp"

#include <cmath>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::model::drive {

// The step's coupling of the flank's friction impulse into its normal
// impulse, alpha = dP_N / dP_T, at the positions q_: W^-1 in place of
// M^-1 in the Delassus terms, alpha = -G~_NT / G~_NN (the rotor held
// where speed-controlled). For h -> 0 it is the drive's own.
double DriveMoreau::step_coupling(double h, double theta) {
  Square stiffness, damping;
  assemble(h, theta, stiffness, damping);
  free_ = CoordinateVector::Zero(model_.coordinate_count());
  if (model_.thread_pair().penalty()) {  // (the flank's force's normal impulse)
    const CoordinateVector rest = CoordinateVector::Zero(model_.coordinate_count());
    return flank_impulse(h, theta, rest, solve(false, 0.0, 0.0, 1.0).velocity) -
           flank_impulse(h, theta, rest, solve(false, 0.0, 0.0, 0.0).velocity);
  }
  return solve(true, 0.0, 0.0, 1.0).normal - solve(true, 0.0, 0.0, 0.0).normal;
}

// A Moreau-Jean step whose flank problem has mu' |alpha| >= 1 has the
// Painleve paradox's structure although the drive has not (mu' |G_NT| <
// G_NN): the springs' stiffness in W (theta^2 h^2 K) dominates the masses
// and turns the flank's friction into a lever on its own normal impulse.
// No consistent impulse, or a spurious one, follows: a jam of the time
// discretization, not of the drive (dt 7e-4 s "jammed" a flexible nut at
// rest that dt 3e-4 s and the event-driven scheme run).
std::string DriveMoreau::step_too_long(double theta, double alpha) {
  return "in the Moreau-Jean step (iteration matrix W = M + theta h C + theta^2 h^2 K, "
         "theta = " + format_value(theta) + ") the flank's "
         "friction impulse drives its own normal impulse, mu' |G~_NT| / G~_NN = " +
         format_value(model_.effective_mu() * std::abs(alpha)) +
         " >= 1, a jam of the time discretization that the drive does not have (mu' |G_NT| "
         "/ G_NN = " +
         format_value(model_.effective_mu() * std::abs(dynamics_.coupling())) +
         " with the masses alone)";
}

// The longest step up to h whose flank coupling stays below 1 / mu' at q_
// (bisection; the coupling falls to the drive's own as h -> 0).
double DriveMoreau::resolving_step(double h, double theta) {
  const CoordinateVector free = free_;
  double low = 0.0, high = h;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double middle = 0.5 * (low + high);
    (model_.effective_mu() * std::abs(step_coupling(middle, theta)) < 1.0 ? low : high) = middle;
  }
  free_ = free;
  return low;
}

void DriveMoreau::check_step(double h, double theta) {
  if (dynamics_.painleve_possible()) return;  // the drive's own condition decides
  // (A penalty flank has no constraint row: solve_thread checks its steps.)
  if (model_.thread_pair().penalty()) return;
  const double alpha = step_coupling(h, theta);
  if (model_.effective_mu() * std::abs(alpha) >= 1.0)
    throw InvalidArgument("dt = " + format_value(h) + " is invalid: must be < " +
                          format_value(resolving_step(h, theta)) +
                          " s for the stiffness of this drive: " +
                          step_too_long(theta, alpha));
}

double DriveMoreau::default_step(double h, double theta) {
  if (dynamics_.painleve_possible() || model_.thread_pair().penalty()) return h;
  if (model_.effective_mu() * std::abs(step_coupling(h, theta)) < 1.0) return h;
  return 0.5 * resolving_step(h, theta);
}

}  // namespace leadscrew::model::drive
