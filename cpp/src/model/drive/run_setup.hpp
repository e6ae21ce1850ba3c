// What every run of a drive starts from, shared by simulate() and the
// stepper (model/drive_stepper.hpp): the friction law that runs and the
// initial state vector. Internal to cpp/src/model.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>

#include "leadscrew/friction/law.hpp"
#include "leadscrew/model/drive.hpp"
#include "state_layout.hpp"

namespace leadscrew::model::drive {

// The law that runs with `integrator`: the model's, or a set-valued law's
// regularization (stored in `regularization`) where an ODE method runs it
// alone. InvalidArgument where the law has none.
const friction::Law& running_law(const DriveModel& model, const std::string& integrator,
                                 std::unique_ptr<friction::Law>& regularization);

// The layout of y for `law`, and y at t = 0 (initial.state: relaxed or in
// equilibrium), the work and loss integrals zero.
StateLayout state_layout(const DriveModel& model, const friction::Law& law);
Eigen::VectorXd initial_vector(const DriveModel& model, const StateLayout& layout);
// The model's elements' states at t = 0 (Element::initial_states) at the
// start's coordinates q and velocities v, written into their blocks of y
// (the layout's, zeros before). at_equilibrium: initial.state =
// "equilibrium" (the equilibrium's solve takes their forces at them too).
void initial_element_states(const DriveModel& model, const StateLayout& layout, const double* q,
                            const double* v, bool at_equilibrium, double* y);

}  // namespace leadscrew::model::drive
