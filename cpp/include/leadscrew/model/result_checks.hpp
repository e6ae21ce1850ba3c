// The physics every simulation's result must show, checked at the end of
// the run (the drive's and the friction block's simulate): a result either
// passes these checks or the run raises SimulationError naming the invariant
// (integrate::enforce_checks). The bounds are derived in
// docs/physics/result_checks.md:
//   finite          every channel and output time is a finite number;
//   event_times     every event lies in [0, t_end], in order;
//   friction_power  friction never does positive work: lambda_T gamma_T <=
//                   |lambda_T| times the slip velocity the integrator
//                   resolves (its atol through |W_T|) plus round-off, at
//                   every output point (not for eq. 3.15's law, which
//                   opposes the slip acceleration by construction);
//   friction_loss   the friction loss never falls by more than its
//                   integration error;
//   friction_cone   |lambda_T| <= mu' |lambda_N| within round-off and the
//                   root location (exact Coulomb only);
//   friction_law    where the contact slips, the friction force is the law's:
//                   on the cone's edge (exact Coulomb), eq. (3.16);
//   losses          the damping, contact and impact losses never fall;
//   flank_gap       exact play: the nut never passes a flank (beyond the
//                   flight check's tolerance, Moreau-Jean: three steps);
//   energy_balance  |energy_residual| within the integrator's tolerances
//                   carried through the energy: K (rtol E + atol G), with E
//                   the run's largest energy flow and G the energy's
//                   gradient bound over the state (momenta, spring forces,
//                   one per work or loss integral), at most 1e-2 of E
//                   (kResolvedEnergyShare); for Moreau-Jean time
//                   stepping, which dissipates by construction, the energy
//                   it creates (-energy_residual) within 1e-3 of E;
//   bristle_bound   LuGre: |z| <= max(mu, mu_static) / sigma0, the law's
//                   invariant set, and its friction inside the force that
//                   allows (bristle_friction).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "leadscrew/friction/law.hpp"
#include "leadscrew/integrate/simulation_result.hpp"

namespace leadscrew::model {

// What a friction contact's result is checked against: its channels, its
// law and the integration that produced it.
struct ResultCheckSpec {
  std::string slip = "slip_velocity";
  std::string friction = "friction_force";
  // +1: the friction channel is the force on the body whose slip velocity
  // the slip channel is (the drive's screw); -1: its reaction (the block's
  // lambda_T in m u'' = F - lambda_T).
  double friction_sign = 1.0;
  std::string normal = "normal_force";
  std::string friction_loss = "friction_loss";
  std::string residual = "energy_residual";
  // A 2-D friction cone (a transverse slip, issue 34): the channels of the
  // slip across the path and of the friction along it (same sign
  // convention as `friction`); empty: a 1-D contact. With them the force
  // checks take the 2-D vectors: the power lambda . gamma, the magnitude
  // |lambda| against the cone, the slip speed |gamma|.
  std::string transverse_slip, transverse_friction;
  // Channels of the energy account: work put in (either sign), energy
  // stored (kinetic, elastic) and losses (>= 0).
  std::vector<std::string> work, stored, losses;
  double t_end = 0.0;
  // The friction law that ran (its coefficients times coefficient_scale:
  // the drive's 1 / cos(beta / 2), the flank angle). A set-valued law's cone
  // |T| <= mu_static' |N| + viscous |gamma| is checked, and where the
  // contact slips its friction is the law's: mu(|gamma|)' |N| + viscous
  // |gamma| against the slip (set-valued), -kappa(gamma)' |N| - viscous
  // gamma (a velocity law); the acceleration law and LuGre are not (their
  // friction needs the slip acceleration or the bristles, no channels).
  const friction::Law* law = nullptr;
  double coefficient_scale = 1.0;
  std::string stick = "stick";
  // Exact play (the gap channel, >= 0 up to the flight check's tolerance):
  // its clearance [m], 0 without; Moreau-Jean's step [s] (its flanks close a
  // step late).
  double clearance = 0.0, time_step = 0.0;
  // Moreau-Jean: the largest rate of the play over its steps [m/s] (the
  // flank_gap tolerance's, not from the sampled rows: sparse output rows
  // would shrink it), and the energy its friction impulses book beyond the
  // step's own work [J]: a step's impulse P_T acts on the slip at the step's
  // end, gamma+, while the positions advance with gamma_theta = (1 - theta)
  // gamma- + theta gamma+, so the loss -P_T gamma+ exceeds the scheme's
  // friction work -P_T gamma_theta by -(1 - theta) P_T (gamma+ - gamma-)
  // wherever the slip speeds up: first order in the step, a residual that
  // looks like created energy. The sum of its positive parts widens the
  // creation bound.
  double step_play_rate = 0.0, step_friction_excess = 0.0;
  // false for eq. (3.15), whose friction may push (its energy balance is
  // checked only).
  bool friction_dissipates = true;
  // The slip velocity the integrator resolves [m/s]: |W_T| atol.
  double slip_resolution = 0.0;
  // Moreau-Jean time stepping: a dissipative account (see above).
  bool time_stepping = false;
  double rtol = 0.0, atol = 0.0;
  // The rows are the integrator's every step and event (no t_eval): E, the
  // largest energy flow of a row, is then the run's, and the energy bound
  // takes at most kResolvedEnergyShare of it. Rows at requested times may
  // miss the flow (a sine-driven block sampled once, where its work has
  // come back to 8e-8 J of a largest 0.17 J).
  bool rows_are_steps = false;
  // Bounds of the energy's gradient over the state: sum_i |M_i v_i| <=
  // momentum_factor sqrt(kinetic), sum |k x| <= force_factor sqrt(elastic).
  double momentum_factor = 0.0, force_factor = 0.0;
  int quadratures = 0;  // work and loss integrals in the state (atol each)
  // The energies' round-off scale: the channels of the applied forces [N]
  // and torques [N m] (over `lever` [m]), and the model's longest length [m].
  std::vector<std::string> load_forces, load_torques;
  double lever = 1.0, length_scale = 1.0;
  // The normal force the friction coefficient multiplies at a row's normal
  // and friction force (a preloaded nut: both halves', |N_A| + |N_B|,
  // elements/preloaded_nut.hpp); empty: |normal|.
  std::function<double(double normal, double friction)> flank_normal;
};

// The safety factor K of energy_balance: the largest ratio of
// |energy_residual| to rtol E + atol G measured over the test suite and
// 10,000 random scenes, times ten (docs/physics/result_checks.md).
constexpr double kEnergyToleranceFactor = 1e3;
// The largest share of the run's largest energy flow E an error-controlled
// run's energy_residual may reach, whatever its tolerances: K (rtol E +
// atol G) is E itself at rtol = 1e-3, and with a stiff contact's G far more
// (a back-driven self-locking drive at rtol 1e-3, atol 1e-5 left 0.31 E
// unbooked, its whole friction loss, against a bound of 60 E). Ten times
// the largest share measured over 788 returned runs of the fuzz's and the
// simulation tests (1.1e-3; docs/physics/result_checks.md, "energy_balance").
constexpr double kResolvedEnergyShare = 1e-2;
// The forces' round-off, relative to the run's largest friction and flank
// forces (friction_power, friction_cone).
constexpr double kForceResolution = 1e-12;
// The share of the run's largest energy flow Moreau-Jean may create.
constexpr double kTimeSteppingCreation = 1e-3;
// The share of that flow the friction impulses' booking may add to it
// (step_friction_excess, first order in dt): a run whose booking term is
// larger did not resolve its slip (a flexible nut at dt 1.8e-4 s created 57 %
// of its energy flow, 0.06 % at dt / 10) and is refused, not certified.
constexpr double kFrictionBookingShare = 1e-2;

// Fills result.checks. Does not throw (integrate::enforce_checks does).
void check_result(const ResultCheckSpec& spec, integrate::SimulationResult& result);

// LuGre's bristles (bristle_check.cpp; check_result calls it):
// bristle_bound, |z| <= max(mu, mu_static) / sigma0 within the bristle
// state's resolution, and bristle_friction, the friction inside the force
// that bound allows. Appends both (applies: the law has bristles).
void check_bristle_bound(const ResultCheckSpec& spec, integrate::SimulationResult& result);

}  // namespace leadscrew::model
