// The friction benchmark of thesis section 3.2.6: a block on a rough plane,
//   m u'' = F_Exc(t) - lambda_T,   lambda_N = m g          (eq. 3.9)
// with exact Coulomb friction (LCP, eq. 3.10-3.14), its arctan regularization
// in the velocity (eq. 3.16) or in the acceleration (eq. 3.15).
//
// State y = [u, v, work_force, friction_loss]: the two work integrals ride
// along so that the energy account is integrated to the same tolerance.
#pragma once

#include <string>

#include "leadscrew/excitation/excitation.hpp"
#include "leadscrew/friction/laws.hpp"
#include "leadscrew/integrate/ode.hpp"
#include "leadscrew/integrate/simulation_result.hpp"

namespace leadscrew::model {

// Immutable parameters (SI).
struct FrictionBlock {
  FrictionBlock(double mass, double mu, double g, Excitation force, double initial_position = 0.0,
                double initial_velocity = 0.0);
  double mass;
  double mu;
  double g;
  Excitation force;
  double initial_position;
  double initial_velocity;
  double normal_force() const { return mass * g; }
};

struct BlockSimulationOptions {
  FrictionLaw friction = FrictionLaw::coulomb;
  double k_v = 100.0;  // regularization gain [s/m] (velocity) or [s^2/m] (acceleration)
  // "event_driven" or "moreau" for coulomb; an ODE integrator for the
  // regularized laws ("cvode_bdf", "cvode_adams", "dopri5", ...).
  std::string integrator = "event_driven";
  integrate::IntegratorOptions integrator_options;
  double dt = 1e-3;    // moreau
  double theta = 0.5;  // moreau
  long max_events = 100000;
  integrate::OutputRequest output;
  // Check the result's physics (model/result_checks.hpp) and raise
  // SimulationError where it fails; false: result.checks only reports.
  bool check = true;
};

// Integrators that fit a friction law (the first is the default).
std::vector<std::string> integrators_for(FrictionLaw law);

integrate::SimulationResult simulate(const FrictionBlock& block,
                                     const BlockSimulationOptions& options);

}  // namespace leadscrew::model
