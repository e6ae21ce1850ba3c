#include "leadscrew/model/friction_block.hpp"

#include <algorithm>
#include <cmath>

#include "block/block_system.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/model/result_checks.hpp"
#include "leadscrew/model/simulation_checks.hpp"

namespace leadscrew::model {

FrictionBlock::FrictionBlock(double mass_, double mu_, double g_, Excitation force_,
                             double initial_position_, double initial_velocity_,
                             double mu_static_, double stiffness_, double pull_speed_,
                             std::optional<Excitation> transverse_velocity_)
    : mass(require_positive("mass", mass_)),
      mu(require_nonnegative("mu", mu_)),
      g(require_nonnegative("g", g_)),
      force(std::move(force_)),
      initial_position(require_finite("initial_position", initial_position_)),
      initial_velocity(require_finite("initial_velocity", initial_velocity_)),
      mu_static(mu_static_ < 0.0 ? mu_ : require_finite("mu_static", mu_static_)),
      stiffness(require_nonnegative("stiffness", stiffness_)),
      pull_speed(require_finite("pull_speed", pull_speed_)),
      transverse_velocity(std::move(transverse_velocity_)) {
  if (!(mu_static >= mu))
    throw InvalidArgument("mu_static = " + format_value(mu_static) +
                          " is invalid: must be >= mu = " + format_value(mu));
}

std::vector<std::string> integrators_for(const std::string& friction) {
  const friction::LawType& type = friction::law_type(friction, "friction");
  std::vector<std::string> names;
  if (type.time_stepping) names = {"event_driven", "moreau"};
  if (type.ode)
    for (const std::string& name : integrate::integrator_names()) names.push_back(name);
  return names;
}

namespace {

// The law of a block: the block's mu and mu_static, the options' values;
// key paths are simulate's keywords.
std::unique_ptr<friction::Law> block_law(const FrictionBlock& block,
                                         const BlockSimulationOptions& options) {
  const friction::LawType& type = friction::law_type(options.friction, "friction");
  friction::LawValues values = {{"mu", block.mu}};
  for (const friction::ParameterInfo& p : type.parameters)
    if (std::string(p.key) == "mu_static") values.emplace_back("mu_static", block.mu_static);
  if (block.mu_static != block.mu && values.size() == 1)
    throw InvalidArgument("mu_static = " + format_value(block.mu_static) +
                          " is invalid for friction = \"" + options.friction +
                          "\": the law has one coefficient (set mu_static = mu, or a law "
                          "with a static coefficient: coulomb, stribeck, lugre)");
  for (const auto& entry : options.law_values) values.push_back(entry);
  return friction::make_law(options.friction, values, "");
}

// A transverse slip (issue 34) runs the 2-D cone of the set-valued laws
// (exact Coulomb, Stribeck's curve on the slip speed |(v, w)|) on their two
// schemes, and LuGre's 2-D bristles on its ODE integrators; the other laws'
// cones (the arctan laws', Stribeck's regularization) are not implemented:
// refused, not run as a 1-D law.
void check_transverse_supported(const FrictionBlock& block, const BlockSimulationOptions& options) {
  if (!block.has_transverse() || options.friction == "lugre") return;
  if (options.friction != "coulomb" && options.friction != "stribeck")
    throw InvalidArgument("friction = \"" + options.friction +
                          "\" is invalid with transverse_velocity: the 2-D friction cone is "
                          "implemented for friction = \"coulomb\", \"stribeck\" and "
                          "\"lugre\" only");
  if (options.integrator != "event_driven" && options.integrator != "moreau")
    throw InvalidArgument("integrator = \"" + options.integrator +
                          "\" is invalid with transverse_velocity and friction = \"" +
                          options.friction +
                          "\": must be \"event_driven\" or \"moreau\" (the cone's "
                          "regularization is not implemented)");
}

// The cone block's event-driven run. Its slip is stiff where |w| is small
// against the inertia (rate mu N / (m |w|)): where the explicit pair's steps
// collapse (a deep quasi-static regime, a w that leaves zero tangentially)
// its failure names Moreau-Jean, not the integrators' generic hint (an
// implicit ODE method: CVODE missed the cone's creep by 37-110 %, starting at
// the apex where the slip's right-hand side jumps).
integrate::SimulationResult run_cone_event_driven(integrate::HybridSystem& system,
                                                  const Eigen::VectorXd& y0,
                                                  const integrate::OutputRequest& output,
                                                  const integrate::EventDrivenOptions& driver) {
  try {
    return integrate::simulate_event_driven(system, 0.0, y0, output, driver);
  } catch (const SimulationError& e) {
    // (the explicit pair's step collapse: RK_STIFF, RK_TOO_MUCH_WORK; any
    // other failure, a load's NaN, keeps its own hint)
    if (e.reason().rfind("RK_", 0) != 0) throw;
    throw SimulationError(e.time(), e.reason(),
                          "the transverse slip's cone is stiff where |w| is small against the "
                          "block's inertia (rate mu N / (m |w|)); use integrator = \"moreau\" "
                          "(docs/physics/transverse_slip.md)");
  }
}

// What a block's result is checked against (model/result_checks.hpp).
ResultCheckSpec block_check_spec(const FrictionBlock& block, const BlockSimulationOptions& options,
                                 const friction::Law& law,
                                 const integrate::SimulationResult& result) {
  ResultCheckSpec spec;
  spec.slip = "v";
  spec.friction_sign = -1.0;  // lambda_T opposes the block: m u'' = F - lambda_T
  spec.work = {"work_force"};
  if (block.has_transverse()) {
    spec.work.push_back("work_transverse");
    spec.transverse_slip = "transverse_velocity";
    spec.transverse_friction = "transverse_friction";
  }
  spec.stored = {"kinetic", "elastic"};
  spec.losses = {"friction_loss"};
  spec.t_end = options.output.t_end;
  const friction::Resolution resolution = law.resolution();
  spec.law = &law;
  // LuGre's bristles store energy: with bristle damping (sigma1 > 0) the law
  // is not passive in general (its friction loss may fall), and friction may
  // push while the bristles relax: checked for its energy balance.
  spec.friction_dissipates = resolution != friction::Resolution::acceleration &&
                             resolution != friction::Resolution::bristle;
  spec.slip_resolution = options.integrator_options.atol;  // the slip is the state's velocity
  spec.time_stepping = options.integrator == "moreau";
  spec.time_step = spec.time_stepping ? options.dt : 0.0;
  spec.rtol = options.integrator_options.rtol;
  spec.atol = options.integrator_options.atol;
  spec.rows_are_steps = options.output.t_eval.empty();
  spec.momentum_factor = std::sqrt(2.0 * block.mass);
  spec.force_factor = std::sqrt(2.0 * block.stiffness);
  spec.quadratures = (block.has_transverse() ? block::kConeStateSize : block::kStateSize) - 2;
  spec.load_forces = {"force", "spring_force"};
  // The block's length: how far it goes (at least the distance the largest
  // force moves its mass in the run's time, F t^2 / m).
  double travel = 0.0;
  const int position = result.channel_index("u");
  for (std::size_t i = 0; i < result.point_count(); ++i)
    travel = std::max(travel, std::abs(result.values[i * result.channel_count() + position]));
  spec.length_scale = std::max(travel, block.normal_force() * spec.t_end * spec.t_end / block.mass);
  return spec;
}

}  // namespace

integrate::SimulationResult simulate(const FrictionBlock& block,
                                     const BlockSimulationOptions& options) {
  const std::vector<std::string> allowed = integrators_for(options.friction);
  if (std::find(allowed.begin(), allowed.end(), options.integrator) == allowed.end())
    require_choice("integrator", options.integrator, allowed,
                   "friction = \"" + options.friction + "\"");
  check_transverse_supported(block, options);
  std::unique_ptr<friction::Law> law = block_law(block, options);
  integrate::validate_output_request(options.output, 0.0);
  if (options.integrator == "moreau") {
    if (block.has_transverse())
      check_step_resolves_loads(options.dt, options.output.t_end,
                                {&block.force, &*block.transverse_velocity});
    else
      check_step_resolves_loads(options.dt, options.output.t_end, {&block.force});
  } else {
    check_meaningful_tolerances(options.integrator_options, options.output.t_end);
  }
  const bool event_scheme = options.integrator == "event_driven" || options.integrator == "moreau";
  // A set-valued law run by an ODE integrator: its regularization.
  if (law->resolution() == friction::Resolution::set_valued && !event_scheme)
    law = law->regularized();
  const bool bristle = law->resolution() == friction::Resolution::bristle;

  const int state_size = block.has_transverse() ? block::kConeStateSize + (bristle ? 2 : 0)
                         : bristle              ? block::kStateSize + 1
                                                : block::kStateSize;
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(state_size);
  y0[block::kPosition] = block.initial_position;
  y0[block::kVelocity] = block.initial_velocity;
  integrate::SimulationResult result;
  if (options.integrator == "moreau") {
    auto system = block.has_transverse() ? block::make_moreau_cone_block(block, *law)
                                         : block::make_moreau_block(block, *law);
    const integrate::MoreauOptions moreau{options.dt, options.theta,
                                          options.integrator_options.max_steps};
    result = integrate::simulate_moreau(*system, 0.0, y0, options.output, moreau);
  } else {
    integrate::EventDrivenOptions driver;
    driver.integrator_options = options.integrator_options;
    driver.max_events = options.max_events;
    if (law->resolution() == friction::Resolution::set_valued) {
      // Smooth phases of the block are non-stiff: our own Verner 6(5) pair
      // with exact event location is an order of magnitude cheaper than CVODE.
      // (The same for a transverse slip's cone, whose rate mu N / (m |w|)
      // grows near the plane's reversals: CVODE's multistep methods, whose
      // stability would not limit, missed its quasi-static creep by 37-50 %
      // at rtol 1e-6 where both Runge-Kutta pairs agree to 1e-8 (the
      // restarts at the cone's apex, where the right-hand side jumps); the
      // stiff regime is Moreau-Jean's, run_cone_event_driven.)
      driver.integrator = "rk_verner6";
      auto system = block.has_transverse() ? block::make_cone_block(block, *law)
                                           : block::make_exact_block(block, *law);
      if (block.has_transverse()) {
        result = run_cone_event_driven(*system, y0, options.output, driver);
      } else {
        result = integrate::simulate_event_driven(*system, 0.0, y0, options.output, driver);
      }
      result.integrator = "event_driven";
    } else {
      driver.integrator = options.integrator;
      // The thesis's arctan laws: the fast path; the others (Stribeck's
      // regularization, LuGre): the general smooth block.
      const bool thesis_law =
          options.friction == "arctan_velocity" || options.friction == "arctan_acceleration";
      auto system = block.has_transverse() ? block::make_cone_bristle_block(block, *law)
                    : thesis_law           ? block::make_regularized_block(block, *law)
                                           : block::make_smooth_block(block, *law);
      result = integrate::simulate_event_driven(*system, 0.0, y0, options.output, driver);
    }
  }
  result.friction = options.friction;

  const ResultCheckSpec spec = block_check_spec(block, options, *law, result);
  check_result(spec, result);
  if (options.check) integrate::enforce_checks(result);
  return result;
}

}  // namespace leadscrew::model
