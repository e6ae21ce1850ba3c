// DriveHybrid's mode solver (mode_solver.hpp), chosen from the model's
// structure: the one place that picks a specialisation of the driver.
#include "mode_solver.hpp"

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::model::drive {

// The rigid drive without play (one degree of freedom, no force element, a
// torque-controlled motor, exact Coulomb outside the Painleve regime) in
// closed form; every other model by the constrained solve. A further
// specialisation is a ModeSolver of its own and one line here, ahead of the
// general one. The rigid solver has no states or rates but the rotor's: it
// takes no element with events (DriveHybrid::Element; built before this).
// The rigid concept without play: every contact slips with the one speed.
// TrainSolver's closed forms take Coulomb's one kinetic coefficient (its
// stick test mu_static); arctan_velocity (the one other law the
// event-driven scheme runs with the stages there: train_event_driven_obstacle)
// takes the rotor's friction contact on the constrained solve, as off the
// rigid concept (hybrid_rotor_contact.cpp).
bool DriveHybrid::train_solver_applies(const DriveModel& model) {
  return model.parameters().concept == Concept::rigid && model.thread_pair().bilateral() &&
         model.parameters().friction == "coulomb";
}

std::unique_ptr<DriveHybrid::ModeSolver> DriveHybrid::make_mode_solver(DriveHybrid& hybrid) {
  // (Behind a prescribed rotor speed the stages change the motor's torque
  // alone: the constrained solve, which books their losses.)
  // (A torque or DC motor elsewhere: the rotor's friction contact, an element
  // on the constrained solve, hybrid_rotor_contact.cpp.)
  if (hybrid.model_.train_friction() && !hybrid.model_.motor().speed_controlled &&
      train_solver_applies(hybrid.model_)) {
    // The parameters' checks (build_drive_elements) admit the friction
    // stages where this holds but for the thread's Painleve regime.
    if (!RigidDriveModes::applies_to_thread(hybrid.model_, hybrid.dynamics_))
      throw InvalidArgument("the train's friction stages (gear.type = \"" +
                            gear_type_name(hybrid.p_.gear) + "\", motor.friction_torque = " +
                            format_value(hybrid.p_.motor_friction_torque) +
                            ") are invalid here: they need the rigid drive without play with "
                            "the thread outside the Painleve regime (mu' |G_NT| < G_NN)");
    auto solver = std::make_unique<TrainSolver>(hybrid);
    hybrid.train_ = solver.get();
    return solver;
  }
  if (hybrid.elements_.empty() && RigidDriveModes::applies(hybrid.model_, hybrid.dynamics_))
    return std::make_unique<RigidSolver>(hybrid);
  return std::make_unique<ConstrainedSolver>(hybrid);
}

}  // namespace leadscrew::model::drive
