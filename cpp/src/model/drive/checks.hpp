// The checks of a drive's result: its ResultCheckSpec (the energy account's
// channels, the friction law's bounds, the round-off scales) for
// model/result_checks.hpp. Internal to cpp/src/model.
#pragma once

#include "leadscrew/friction/law.hpp"
#include "leadscrew/integrate/simulation_result.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_simulation.hpp"

namespace leadscrew::model::drive {

// The checks of a drive's result (model/result_checks.hpp), raised unless
// options.check is off.
// `step_play_rate`, `step_friction_excess`: Moreau-Jean's (ResultCheckSpec).
void check_drive_result(const DriveModel& model, const friction::Law& law,
                        const DriveSimulationOptions& options, bool time_stepping,
                        integrate::SimulationResult& result, double step_play_rate = 0.0,
                        double step_friction_excess = 0.0);

// The check exact_stops: the load's position against the exact end stops'
// faces (exact_stop_check.cpp; applies only where the model has them).
integrate::InvariantCheck exact_stop_check(const DriveModel& model,
                                           const DriveSimulationOptions& options,
                                           bool time_stepping,
                                           const integrate::SimulationResult& result);

}  // namespace leadscrew::model::drive
