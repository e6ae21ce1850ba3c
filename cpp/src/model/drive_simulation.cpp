// simulate() of a DriveModel: the law that runs, the initial state, and the
// scheme (event-driven, Moreau-Jean, an ODE method through the event-driven
// system). The driver's parts are under model/drive/ (docs/architecture.md).
#include "leadscrew/model/drive_simulation.hpp"

#include <memory>

#include "drive/checks.hpp"
#include "drive/hybrid.hpp"
#include "drive/integrators.hpp"
#include "drive/moreau.hpp"
#include "drive/run_setup.hpp"
#include "drive/state_layout.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/friction/law.hpp"
#include "leadscrew/integrate/event_driven.hpp"
#include "leadscrew/integrate/moreau.hpp"
#include "leadscrew/integrate/simulation_result.hpp"

namespace leadscrew::model {

using drive::check_drive_result;
using drive::chosen_integrator;
using drive::DriveHybrid;
using drive::DriveMoreau;
using drive::moreau_options;
using drive::StateLayout;

integrate::SimulationResult simulate(const DriveModel& model,
                                     const DriveSimulationOptions& options) {
  check_simulation_options(model, options);
  const DriveParameters& p = model.parameters();
  const std::string& integrator = chosen_integrator(model, options);

  // The law that runs, the state at t = 0 (drive/run_setup.hpp).
  std::unique_ptr<friction::Law> regularization;
  const friction::Law& law = drive::running_law(model, integrator, regularization);
  const StateLayout layout = drive::state_layout(model, law);
  const Eigen::VectorXd y0 = drive::initial_vector(model, layout);

  if (integrator == "moreau") {
    DriveMoreau system(model);
    system.initialize(0.0, y0.data());
    // simulate's default step (not the user's) is shortened where the
    // drive's stiffness needs it: a valid scene is not refused for a dt
    // nobody chose (issue 31: the drive-train fuzz's case 8897, dt 1e-4 s
    // against the 8.5e-5 s its springs allow).
    DriveSimulationOptions shortened;
    const bool choose = !options.dt_given;
    if (choose) {
      shortened = options;
      shortened.dt = system.default_step(options.dt, options.theta);
    }
    const DriveSimulationOptions& run = choose ? shortened : options;
    system.check_step(run.dt, run.theta);
    integrate::SimulationResult result =
        integrate::simulate_moreau(system, 0.0, y0, run.output, moreau_options(run));
    result.friction = p.friction;
    check_drive_result(model, law, run, true, result, system.largest_play_rate(),
                       system.friction_excess());
    return result;
  }

  DriveHybrid system(model, law, options.bounce_threshold, options.output.t_end,
                     options.integrator_options);
  const integrate::EventDrivenOptions driver =
      drive::event_driven_options(model, law, integrator, options);
  integrate::SimulationResult result;
  try {
    result = integrate::simulate_event_driven(system, 0.0, y0, options.output, driver);
  } catch (const SimulationError& e) {
    // A transverse slip's cone is stiff where |w| is small against the
    // drive's inertia (the helix friction's slope mu' |N| / |w|): the
    // explicit pair's steps collapse (RK_STIFF, RK_TOO_MUCH_WORK). That
    // regime is Moreau-Jean's, not CVODE's, which the generic hint names
    // (it missed the block's cone creep by 37-110 %: friction_block.cpp).
    // (LuGre's bristles are smooth at the apex: the generic hint stands.)
    if (!has_transverse_slip(p) || law.resolution() == friction::Resolution::bristle ||
        e.reason().rfind("RK_", 0) != 0)
      throw;
    throw SimulationError(e.time(), e.reason(),
                          "the transverse slip's friction cone is stiff where |w| is small "
                          "against the drive's inertia (its helix slope mu' |N| / |w|); use "
                          "integrator = \"moreau\" (docs/physics/transverse_slip.md)");
  }
  result.integrator = integrator;
  result.friction = p.friction;
  check_drive_result(model, law, options, false, result);
  return result;
}

}  // namespace leadscrew::model
