// DriveHybrid's mode solver (mode_solver.hpp), chosen from the model's
// structure: the one place that picks a specialisation of the driver.
#include "mode_solver.hpp"

namespace leadscrew::model::drive {

// The rigid drive without play (one degree of freedom, no force element, a
// torque-controlled motor, exact Coulomb outside the Painleve regime) in
// closed form; every other model by the constrained solve. A further
// specialisation is a ModeSolver of its own and one line here, ahead of the
// general one. The rigid solver has no states or rates but the rotor's: it
// takes no element with events (DriveHybrid::Element; built before this).
std::unique_ptr<DriveHybrid::ModeSolver> DriveHybrid::make_mode_solver(DriveHybrid& hybrid) {
  if (hybrid.elements_.empty() && RigidDriveModes::applies(hybrid.model_, hybrid.dynamics_))
    return std::make_unique<RigidSolver>(hybrid);
  return std::make_unique<ConstrainedSolver>(hybrid);
}

}  // namespace leadscrew::model::drive
