// The core spec: a drive as the core runs it, in TOML. Every value is an SI
// number and every default and derived value is explicit (the fields of
// DriveParameters, the loads as constant, sine or table, and the options of
// the run), so that a program without Python (the C API,
// leadscrew/leadscrew.h) reads what leadscrew.Scene resolved from a scene
// file (Scene.to_core_toml(), `leadscrew scene resolve SCENE -o core.toml`).
// One writer and one reader, both here: the format is defined by them.
//
//   format = "leadscrew-core-spec"
//   version = 1
//   [drive]       concept, drive, support, backlash, initial_state, speed_controlled,
//                 gear, and each element section's presence (element_section.hpp:
//                 end_stops = "none" / "penalty" / "exact", dc_motor = true / false)
//   [thread]      pitch, mean_diameter, starts, flank_angle, hand
//   [friction]    law, and [friction.values]: the law's other parameters by key
//   [parameters]  every scalar field of DriveParameters by name (scalar_fields()),
//                 then each element section's numbers by attribute (end_stop_lower, ...)
//   [loads.drive_torque], [loads.drive_speed], [loads.axial_force], the
//                 elements' inputs by name ([loads.motor_voltage]; SectionInput):
//                 type = "constant" (value), "sine" (amplitude, omega, phase,
//                 offset) or "table" (times, values)
//   [options]     integrator, smooth_integrator, rtol, atol, max_steps,
//                 max_events, max_step, first_step, max_order, bounce_threshold
//
// Reading: a key left out takes the core's default (DriveParameters,
// DriveSimulationOptions); an unknown key, a value of the wrong type or a
// wrong format raise InvalidArgument naming the key path; the DriveModel
// built from the result checks the values.
#pragma once

#include <string>

#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_simulation.hpp"

namespace leadscrew::model {

struct CoreSpec {
  DriveParameters parameters;
  DriveSimulationOptions options;
};

// The spec's text. InvalidArgument for a load that is a callable (a Python
// function: no file can carry it), naming the load.
std::string write_core_spec(const DriveParameters& parameters,
                            const DriveSimulationOptions& options = {});
// `source`: the file's name in messages ("" for text).
CoreSpec read_core_spec(const std::string& text, const std::string& source = "");
CoreSpec read_core_spec_file(const std::string& path);

}  // namespace leadscrew::model
