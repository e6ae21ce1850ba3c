// Which integrators fit a drive and how simulate() runs them: the default
// integrator, the ODE method between events, Moreau-Jean's and the
// event-driven scheme's options (drive_integrators and
// check_simulation_options, the public part, are in
// model/drive_simulation.hpp). Internal to cpp/src/model.
#pragma once

#include <string>

#include "leadscrew/friction/law.hpp"
#include "leadscrew/integrate/event_driven.hpp"
#include "leadscrew/integrate/moreau.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_simulation.hpp"

namespace leadscrew::model::drive {

// The integrator simulate() runs ("" in the options: the model's default).
const std::string& chosen_integrator(const DriveModel& model,
                                     const DriveSimulationOptions& options);

// The ODE method of the smooth phases: the integrator itself, or inside
// "event_driven" the smooth_integrator option (default: our Verner 6(5)
// with exact event location for a model without force elements (the rigid
// concept), an order of magnitude cheaper than CVODE; BDF where springs and
// dampers make it stiff (the flexible concepts). CVODE used to lose
// flank events of a rattling nut, 3 to 8 of 36 at rtol 1e-12; with
// handle_event's touch below resolution it finds the same ones:
// tests/test_integrate_flank_events.py).
std::string ode_method(const DriveModel& model, const std::string& integrator,
                       const DriveSimulationOptions& options);

// The integrators that fit a built model: drive_integrators(parameters)
// from its thread pair's kind of play and its friction law.
const std::vector<std::string>& model_integrators(const DriveModel& model);

// A velocity-regularized law (arctan_velocity; a set-valued law's
// regularization in an ODE method) needs the slip velocity resolved within
// its stick band: InvalidArgument naming atol where k_v |W_T| atol > 0.05
// (slip_resolution_check.cpp).
void check_slip_resolved(const DriveModel& model, const std::string& integrator,
                         const DriveSimulationOptions& options);

// Moreau-Jean's dt, theta and step count from the options.
integrate::MoreauOptions moreau_options(const DriveSimulationOptions& options);

// The event-driven scheme's options for `integrator` ("event_driven") with
// `law` running: the method between events (ode_method) and its settings,
// with the stiff laws' heuristics for CVODE.
integrate::EventDrivenOptions event_driven_options(const DriveModel& model,
                                                   const friction::Law& law,
                                                   const std::string& integrator,
                                                   const DriveSimulationOptions& options);

}  // namespace leadscrew::model::drive
