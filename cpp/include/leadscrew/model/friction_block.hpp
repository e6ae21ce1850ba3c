// The friction benchmark of thesis section 3.2.6: a block on a rough plane,
//   m u'' = F_Exc(t) + F_spring - lambda_T,   lambda_N = m g      (eq. 3.9)
// with any friction law of the registry (friction/law.hpp): exact Coulomb
// (LCP, eq. 3.10-3.14) with a static coefficient, Stribeck's curve, the
// arctan regularizations in the velocity (eq. 3.16) and the acceleration
// (eq. 3.15), LuGre. With a spring of stiffness k to a point that starts at
// the block's initial position and moves at pull_speed V,
//   F_spring = k (u_0 + V t - u),
// it is the classic stick-slip oscillator.
//
// State y = [u, v, work_force, friction_loss (, z)]: the work integrals ride
// along so that the energy account is integrated to the same tolerance;
// work_force is the work of F_Exc and of the spring's moving end (F_spring V),
// the spring's energy k (u_0 + V t - u)^2 / 2 is elastic; LuGre's bristle
// deflection z is the last state.
//
// With a transverse slip w(t) (issue 34; docs/physics/transverse_slip.md)
// the plane also moves across the block's path at the prescribed velocity
// w: the slip is the vector (v, w) and friction an isotropic 2-D cone,
// -mu N (v, w) / |(v, w)| in slip, |lambda| <= mu_static N where both
// components vanish (cone_block.cpp, Moreau-Jean in moreau_block.cpp). The
// state then carries the transverse excitation's work (kTransverseWork).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "leadscrew/excitation/excitation.hpp"
#include "leadscrew/friction/law.hpp"
#include "leadscrew/integrate/ode.hpp"
#include "leadscrew/integrate/simulation_result.hpp"

namespace leadscrew::model {

// Immutable parameters (SI).
struct FrictionBlock {
  // mu_static < 0: equal to mu.
  FrictionBlock(double mass, double mu, double g, Excitation force, double initial_position = 0.0,
                double initial_velocity = 0.0, double mu_static = -1.0, double stiffness = 0.0,
                double pull_speed = 0.0,
                std::optional<Excitation> transverse_velocity = std::nullopt);
  double mass;
  double mu;
  double g;
  Excitation force;
  double initial_position;
  double initial_velocity;
  double mu_static;   // >= mu
  double stiffness;   // of the spring to the pulled point [N/m], >= 0
  double pull_speed;  // of the pulled point [m/s]
  // The plane's slip across the block's path, w(t) [m/s]; none: the 1-D
  // block (no transverse term at all, no cost).
  std::optional<Excitation> transverse_velocity;
  bool has_transverse() const { return transverse_velocity.has_value(); }
  double normal_force() const { return mass * g; }
  // The spring's force on the block at (t, u).
  double spring_force(double t, double u) const {
    return stiffness * (initial_position + pull_speed * t - u);
  }
};

struct BlockSimulationOptions {
  std::string friction = "coulomb";  // a law of friction::law_types()
  // The law's parameters other than mu and mu_static (the block's): k_v,
  // sigma0, ... by their keys.
  friction::LawValues law_values;
  // "event_driven" or "moreau" for a set-valued law; an ODE integrator for
  // the others ("cvode_bdf", "cvode_adams", "dopri5", ...), and for a
  // set-valued law that has a regularization (stribeck).
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
std::vector<std::string> integrators_for(const std::string& friction);

integrate::SimulationResult simulate(const FrictionBlock& block,
                                     const BlockSimulationOptions& options);

}  // namespace leadscrew::model
