// Simulation of a DriveModel: the event-driven scheme for exact Coulomb
// friction and exact flank contacts, smooth integration for the regularized
// and compliant formulations, Moreau-Jean time stepping.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "leadscrew/integrate/ode.hpp"
#include "leadscrew/integrate/simulation_result.hpp"
#include "leadscrew/model/drive.hpp"

namespace leadscrew::model {

struct DriveSimulationOptions {
  std::string integrator = "event_driven";  // "": the model's default (drive_integrators()[0])
  // The smooth integrator inside "event_driven" ("": rk_verner6 for a model
  // without springs or dampers (the rigid concept), cvode_bdf for the stiff
  // flexible ones).
  std::string smooth_integrator;
  integrate::IntegratorOptions integrator_options;
  double dt = 1e-4;    // moreau
  // false: dt is simulate's default, not the user's: Moreau-Jean shortens it
  // where the drive's stiffness needs a shorter step (DriveMoreau::
  // default_step), instead of refusing a step nobody chose.
  bool dt_given = true;
  double theta = 0.5;  // moreau
  long max_events = 100000;
  // An impact slower than this (normal velocity, m/s) is plastic: the flank
  // stays closed (ends an infinite sequence of ever smaller bounces).
  double bounce_threshold = 1e-6;
  integrate::OutputRequest output;
  // Check the result's physics (model/result_checks.hpp) and raise
  // SimulationError where it fails; false: result.checks only reports.
  bool check = true;
};

// Integrators that fit a model (the first is the default).
const std::vector<std::string>& drive_integrators(const DriveParameters& parameters);

// The SI unit of every result channel a drive may write, by name ("m", "N*m",
// "J", "" for the flag stick), as the core's elements declare them
// (cpp/src/model/drive/declaration.hpp): the base channels and every
// registered element's. Not the coordinates' pairs u_<body>, v_<body>,
// phi_<body>, omega_<body> beyond the base's u_load, v_load, phi_drive,
// omega_drive.
std::vector<std::pair<std::string, std::string>> drive_channel_units();

// The checks simulate() makes of its options before it integrates, without
// simulating: the integrator fits the model's friction law and contact;
// tolerances, step controls and bounds, with the limits of the ODE method
// that will run (max_order of a one-step method, CVODE's order range);
// output times; Moreau's dt, theta and step count against max_steps. A sweep
// refuses up front what would fail every case alike. InvalidArgument naming
// the option, its value and the valid range.
void check_simulation_options(const DriveModel& model, const DriveSimulationOptions& options);

integrate::SimulationResult simulate(const DriveModel& model,
                                     const DriveSimulationOptions& options);

}  // namespace leadscrew::model
