// Which integrators fit a drive (from its friction law's type and its
// contact), the checks of simulate()'s options, and the options each scheme
// runs with.
#include "integrators.hpp"
#include "transverse_slip.hpp"

#include <algorithm>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/law.hpp"
#include "leadscrew/integrate/ode.hpp"
#include "leadscrew/model/element_section.hpp"
#include "leadscrew/model/elements/drive_elements.hpp"
#include "leadscrew/model/simulation_checks.hpp"

namespace leadscrew::model {

namespace {

// The integrators that fit the friction law `friction` on a thread pair with
// exact flanks, or penalty flanks or no play (the same list); a preloaded nut
// runs on the event-driven scheme and on Moreau-Jean (moreau_preload.cpp;
// its lift-off, half B's own flank beside the penalty flank, with Coulomb
// friction, exact or on Stribeck's curve, without a viscous term:
// moreau_lift_off.cpp, check_preload_integrator). End stops run on every
// scheme the thread pair admits (Moreau-Jean: moreau.hpp).
const std::vector<std::string>& integrators_for(const std::string& friction,
                                                friction::Resolution resolution, bool exact_play,
                                                bool preloaded, bool lift_off) {
  // From the law's type (friction/law.hpp): a set-valued law runs in the
  // event-driven scheme, in Moreau-Jean's time stepping (without play, on
  // exact flanks and on penalty flanks: moreau.hpp), and where it has a
  // regularization in the ODE methods; a smooth law in the ODE methods and
  // the event-driven scheme, and a velocity law and LuGre's bristles on
  // Moreau-Jean too, their friction implicit in the step
  // (moreau_smooth_friction.cpp); eq. (3.15) not there (its friction
  // follows the slip acceleration, which a velocity-level step has not:
  // check_simulation_options says so). Exact play needs the event-driven
  // scheme's flank events or Moreau-Jean's.
  static const std::vector<std::string> event_driven_only = {"event_driven"};
  static const std::vector<std::string> with_moreau = {"event_driven", "moreau"};
  static const std::vector<std::string> smooth = [] {
    std::vector<std::string> names = integrate::integrator_names();
    names.push_back("event_driven");
    return names;
  }();
  static const std::vector<std::string> smooth_with_moreau = [] {
    std::vector<std::string> names = smooth;
    names.push_back("moreau");
    return names;
  }();
  static const std::vector<std::string> set_valued_all = [] {
    std::vector<std::string> names = {"event_driven", "moreau"};
    for (const std::string& name : integrate::integrator_names()) names.push_back(name);
    return names;
  }();
  const friction::LawType& type = friction::law_type(friction);
  // A preloaded nut: the set-valued laws on the event-driven scheme and
  // Moreau-Jean, the smooth laws on the event-driven scheme, the ODE
  // methods (their driver takes the halves: drive_dynamics.cpp) and
  // Moreau-Jean (moreau_smooth_friction.cpp); with lift-off the smooth laws
  // on the event-driven scheme and the ODE methods.
  if (preloaded) {
    // (lift-off: the set-valued laws, exact Coulomb and Stribeck's curve
    // without a viscous term, on Moreau-Jean: check_preload_integrator)
    if (lift_off) return type.time_stepping ? with_moreau : smooth;
    if (type.time_stepping) return with_moreau;  // (Stribeck's too: moreau_preload.cpp)
    return resolution != friction::Resolution::acceleration ? smooth_with_moreau : smooth;
  }
  if (type.time_stepping) {  // set-valued
    if (exact_play) return with_moreau;
    if (type.ode) return set_valued_all;
    return with_moreau;
  }
  const bool moreau = resolution != friction::Resolution::acceleration;
  if (exact_play) return moreau ? with_moreau : event_driven_only;
  return moreau ? smooth_with_moreau : smooth;
}

}  // namespace

namespace {

// The train's friction stages (train_friction.hpp): both schemes on the
// rigid drive without play with plain Coulomb friction, Moreau-Jean alone
// elsewhere (its obstacle).
// Exact end stops with exact play where the load rides on the part that
// carries the flank (the rigid concept, the nut-driven flexible nut): a
// flank's impact while the stop holds the load is two impacts at once on a
// tied body, which Moreau-Jean's step solves as its rows and the
// event-driven flank impact does not take (docs/physics/end_stops.md, "The
// rigid drive at an exact stop"). elements/end_stops.cpp refuses the
// smooth laws there.
// Whether a preloaded nut of p lifts off (its halves can move apart: the
// flexible concepts with penalty play; elements/build_drive.cpp).
bool preload_lifts_off(const DriveParameters& p) {
  return p.nut_preload > 0.0 && p.concept != Concept::rigid &&
         (p.backlash == BacklashContact::bistop || p.backlash == BacklashContact::cubic);
}

bool stops_need_moreau(const DriveParameters& p) {
  const bool load_on_flank =
      p.concept == Concept::rigid ||
      (p.concept == Concept::flexible_nut && p.drive == DrivenPart::nut);
  return load_on_flank && p.backlash == BacklashContact::exact &&
         elements::has_exact_end_stops(p);
}

const std::vector<std::string>& moreau_only() {
  static const std::vector<std::string> names = {"moreau"};
  return names;
}

// A transverse slip's set-valued cone runs on Moreau-Jean alone off the
// rigid concept, with exact play and with exact end stops
// (check_transverse_slip): there it is the default, not a refusal of the
// event-driven scheme the user did not choose (a new user's review).
bool cone_needs_moreau(const DriveParameters& p, friction::Resolution resolution) {
  if (!has_transverse_slip(p) || resolution != friction::Resolution::set_valued) return false;
  return p.concept != Concept::rigid || p.backlash == BacklashContact::exact ||
         elements::has_exact_end_stops(p);
}

const std::vector<std::string>& train_integrators(const elements::TrainFriction& train) {
  static const std::vector<std::string> both = {"event_driven", "moreau"};
  static const std::vector<std::string> moreau_first = {"moreau", "event_driven"};
  static const std::vector<std::string> moreau_only = {"moreau"};
  if (!train.event_driven_obstacle.empty()) return moreau_only;
  return train.moreau_default ? moreau_first : both;
}

// The stages behind a prescribed rotor speed: the event-driven scheme runs
// every drive it runs without them (`without`: the scene's list without
// the stages; the stages change the motor's torque alone), Moreau-Jean
// where it runs the drive, and stays the default there, as before the
// event-driven scheme took them (issue 32: results unchanged; rtol and atol
// choose the event-driven scheme, _option_rules.py). LuGre's bristles,
// which Moreau-Jean took beside the rotor's contact later (the held rows'
// bristles: moreau_held_bristles.cpp), keep the event-driven scheme their
// default (the default's results unchanged).
const std::vector<std::string>& speed_train_integrators(const std::vector<std::string>& without,
                                                        friction::Resolution resolution) {
  static const std::vector<std::string> moreau_first = {"moreau", "event_driven"};
  static const std::vector<std::string> event_driven_first = {"event_driven", "moreau"};
  static const std::vector<std::string> event_driven = {"event_driven"};
  if (std::find(without.begin(), without.end(), "moreau") == without.end()) return event_driven;
  return resolution == friction::Resolution::bristle ? event_driven_first : moreau_first;
}

}  // namespace

const std::vector<std::string>& drive_integrators(const DriveParameters& p) {
  const bool stages =
      p.motor_friction_torque > 0.0 || p.gear == GearType::lossy || p.gear == GearType::worm;
  // The train's stages with a torque or DC motor: whether the event-driven
  // scheme runs them needs the built model (the thread's Painleve regime,
  // from the masses).
  if (stages && !p.speed_controlled) {
    // (A lift-off nut's model carries the assembled nut's play, beyond the
    // play's half: initial.play_position is ignored with it, 0 here.)
    if (!preload_lifts_off(p)) return drive::model_integrators(DriveModel(p));
    DriveParameters assembled = p;
    assembled.play_position = 0.0;
    return drive::model_integrators(DriveModel(assembled));
  }
  if (stops_need_moreau(p)) return moreau_only();
  // (The law's type, from its defaults: every law's parameters have one.)
  const friction::Resolution resolution = friction::make_law(p.friction, {})->resolution();
  if (!stages && cone_needs_moreau(p, resolution)) return moreau_only();
  const std::vector<std::string>& without =
      integrators_for(p.friction, resolution, p.backlash == BacklashContact::exact,
                      p.nut_preload > 0.0, preload_lifts_off(p));
  // (Behind a prescribed rotor speed the parameters tell: a built model's
  // parameters of a nut that lifts off carry its assembled play, beyond
  // the play's half, which a model built from them again refuses.)
  return stages ? speed_train_integrators(without, resolution) : without;
}

const std::vector<std::string>& drive::model_integrators(const DriveModel& model) {
  const elements::ThreadPair& thread = model.thread_pair();
  const DriveParameters& p = model.parameters();
  if (stops_need_moreau(p)) return moreau_only();
  if (!model.train_friction() && cone_needs_moreau(p, model.law().resolution()))
    return moreau_only();
  const elements::PreloadedNut* nut = model.preloaded_nut();
  const std::vector<std::string>& without =
      integrators_for(p.friction, model.law().resolution(), thread.exact_play(), nut != nullptr,
                      nut != nullptr && nut->lift_off);
  if (model.train_friction())
    return p.speed_controlled
               ? speed_train_integrators(without, model.law().resolution())
               : train_integrators(*model.train_friction());
  return without;
}

namespace {

// The theta-method steps the springs (W = M + theta h C + theta^2 h^2 K) in
// a stable way for every step only where theta >= 1/2; below, a spring's
// mode grows from step to step unless the step resolves its period, which
// the flexible models' stiff modes (periods of microseconds) never allow at
// a useful dt. A new user's theta = 0.3 on the flexible seat ran the nut
// 0.337 m off its screw and was told to change the loads. Refused, naming
// theta.
void check_theta_stable_with_springs(const DriveModel& model,
                                     const DriveSimulationOptions& options) {
  if (!(options.theta < 0.5)) return;
  const bool penalty_flanks = model.thread_pair().penalty();
  if (model.elements().forces.empty() && !penalty_flanks) return;
  throw InvalidArgument(
      "theta = " + format_value(options.theta) +
      " is invalid for this drive: its springs (" +
      (!model.springs().empty()                ? "the flexible screw's or nut's"
       : !model.elements().end_stops().empty() ? "the penalty end stops'"
       : penalty_flanks                        ? "the penalty flanks'"
                                               : "its force elements'") +
      ") need theta in [0.5, 1], where Moreau-Jean's theta-method is stable at every step "
      "(below 0.5 their modes grow from step to step)");
}

// A preloaded nut runs on the event-driven scheme; with a set-valued law on
// Moreau-Jean (moreau_preload.cpp; lifting off without a viscous term:
// moreau_lift_off.cpp); with a smooth law on the ODE methods too
// (drive_dynamics.cpp): the element's own reason first (the list of
// integrators leaves it out).
void check_preload_integrator(const DriveModel& model, const std::string& integrator) {
  const DriveParameters& p = model.parameters();
  const elements::PreloadedNut* nut = model.preloaded_nut();
  if (!nut || integrator == "event_driven") return;
  const friction::Law& law = model.law();
  const bool set_valued = law.resolution() == friction::Resolution::set_valued;
  if (integrator != "moreau" && !set_valued) return;  // (the law's own list decides)
  if (integrator == "moreau" && nut->lift_off && !(set_valued && law.viscous() == 0.0))
    throw InvalidArgument(
        "integrator = \"moreau\" is invalid with nut.preload = " + format_value(p.nut_preload) +
        " N, backlash.contact = \"" + backlash_contact_name(p.backlash) +
        "\" and friction.law = \"" + p.friction + "\"" +
        (set_valued ? " with friction.viscous = " + format_value(law.viscous()) : "") +
        ": Moreau-Jean's step takes a preloaded nut that lifts off (penalty play on a "
        "flexible concept) with Coulomb friction (exact, or on Stribeck's curve) without a "
        "viscous term only (its halves' modes, moreau_lift_off.cpp); the other laws run it on "
        "the event-driven scheme (integrator = \"event_driven\")");
  if (integrator == "moreau") return;  // (lift-off with a law but exact Coulomb: above)
  // An ODE method with a set-valued law (its regularization has no halves).
  throw InvalidArgument(
      "integrator = \"" + integrator + "\" is invalid with nut.preload = " +
      format_value(p.nut_preload) + " N and friction.law = \"" + p.friction +
      "\": a preloaded nut with a set-valued law runs on the event-driven scheme or "
      "Moreau-Jean (integrator = \"event_driven\" or \"moreau\")");
}

}  // namespace

namespace {

// The train's friction stages (a lossy or worm gear stage, the motor's
// friction torque) run on Moreau-Jean and, within its reach
// (train_event_driven_obstacle), the event-driven scheme: any other
// integrator is refused, saying where the stages run.
void check_train_integrator(const DriveModel& model, const std::string& integrator) {
  const elements::TrainFriction* train = model.train_friction();
  if (!train || integrator == "moreau" ||
      (integrator == "event_driven" && train->event_driven_obstacle.empty()))
    return;
  const DriveParameters& p = model.parameters();
  const std::string what = train->stage ? "gear.type = \"" + gear_type_name(p.gear) + "\""
                                        : "motor.friction_torque = " +
                                              format_value(p.motor_friction_torque);
  throw InvalidArgument(
      "integrator = \"" + integrator + "\" is invalid with " + what +
      (integrator == "event_driven"
           ? ": the event-driven scheme runs the train's friction stages with a torque or "
             "DC motor on the rigid concept without play with Coulomb friction on the thread "
             "(friction.law = \"coulomb\", mu_static too) or \"arctan_velocity\", and on "
             "the flexible concepts without play and with exact or penalty play (backlash."
             "contact \"exact\", \"bistop\" or \"cubic\") with \"coulomb\" (mu_static too), "
             "\"stribeck\" or \"arctan_velocity\" (the rotor's friction contact), there with "
             "exact end stops (without exact play) and a preloaded nut too (lifting off with "
             "\"stribeck\" without friction.viscous); and behind a prescribed "
             "rotor speed (loads.drive_speed) on every concept and play with every law, "
             "here " + train->event_driven_obstacle +
                 "; use integrator = \"moreau\" (Moreau-Jean, every concept and play)"
           : p.speed_controlled
           ? ": behind a prescribed rotor speed the train's friction stages run on the "
             "event-driven scheme (integrator = \"event_driven\") and, but with "
             "arctan_acceleration or lugre, Moreau-Jean (integrator = \"moreau\")"
           : ": the train's friction stages run on Moreau-Jean (integrator = \"moreau\", "
             "every thread law but arctan_acceleration)" +
                 (train->event_driven_obstacle.empty()
                      ? std::string(" and the event-driven scheme "
                                    "(integrator = \"event_driven\")")
                      : "; this scene runs on Moreau-Jean only (here " +
                            train->event_driven_obstacle + ")")));
}

// The integrator against the scene's physics: eq. (3.15)'s slip
// acceleration (not on Moreau-Jean's velocity-level step), the double
// impact of exact play and an exact stop on one part (Moreau-Jean only),
// and the integrators that run the play and the law (model_integrators).
void check_integrator_takes_scene(const DriveModel& model, const std::string& integrator,
                                  const std::vector<std::string>& allowed) {
  const DriveParameters& p = model.parameters();
  if (integrator == "moreau" &&
      model.law().resolution() == friction::Resolution::acceleration)
    throw InvalidArgument(
        "integrator = \"moreau\" is invalid with friction.law = \"" + p.friction +
        "\": eq. (3.15) takes the friction from the slip acceleration, which Moreau-Jean's "
        "velocity-level step does not have (its velocities jump at the flanks' impacts and its "
        "acceleration is a difference quotient of the step, so the friction would follow dt); "
        "use friction.law = \"arctan_velocity\" or \"lugre\" on Moreau-Jean, or this law on "
        "the event-driven scheme or an ODE method");
  if (stops_need_moreau(p) && integrator != "moreau")
    throw InvalidArgument(
        "integrator = \"" + integrator + "\" is invalid with end_stops.contact = \"exact\" and "
        "backlash.contact = \"exact\" on concept = \"" + concept_name(p.concept) +
        "\" and drive = \"" + drive_name(p.drive) + "\": the load rides on the part that "
        "carries the flank, and a flank's impact while the stop holds it is two impacts at "
        "once, which Moreau-Jean's step solves and the event-driven scheme does not; use "
        "integrator = \"moreau\"");
  if (std::find(allowed.begin(), allowed.end(), integrator) == allowed.end())
    require_choice("integrator", integrator, allowed,
                   (p.backlash != BacklashContact::none
                        ? "backlash.contact = \"" + backlash_contact_name(p.backlash) + "\" with "
                        : std::string()) +
                       "friction.law = \"" + p.friction + "\"" +
                       (find_section(p, "end_stops") ? " and end_stops" : ""));
}

// The options of the ODE method of the smooth phases (an ODE integrator, or
// the one between the event-driven scheme's events): tolerances, the
// slip's resolution, the method and its limits.
void check_ode_options(const DriveModel& model, const std::string& integrator,
                       const DriveSimulationOptions& options) {
  check_meaningful_tolerances(options.integrator_options, options.output.t_end);
  drive::check_slip_resolved(model, integrator, options);
  if (!options.smooth_integrator.empty())
    require_choice("smooth_integrator", options.smooth_integrator, integrate::integrator_names());
  // What make_integrator checks as the smooth phases start, the method's
  // own limits included (max_order of a one-step method, CVODE's orders).
  integrate::validate_options(options.integrator_options);
  const std::string method = drive::ode_method(model, integrator, options);
  try {
    integrate::check_method_limits(method, options.integrator_options);
  } catch (const InvalidArgument& e) {
    if (method == integrator || !options.smooth_integrator.empty()) throw;  // the user named it
    // The default method between events: say which it is.
    throw InvalidArgument(std::string(e.what()) + "; integrator \"event_driven\" runs \"" +
                          method + "\" between events here (smooth_integrator chooses another)");
  }
}

}  // namespace

void check_simulation_options(const DriveModel& model, const DriveSimulationOptions& options) {
  const DriveParameters& p = model.parameters();
  const std::vector<std::string>& allowed = drive::model_integrators(model);
  const std::string& integrator = drive::chosen_integrator(model, options);
  // The elements' own reasons first (the list below leaves them out).
  check_preload_integrator(model, integrator);
  check_train_integrator(model, integrator);
  drive::check_transverse_slip(model, integrator, options.smooth_integrator,
                               options.output.t_end);
  check_integrator_takes_scene(model, integrator, allowed);
  require_nonnegative("bounce_threshold", options.bounce_threshold);
  integrate::validate_output_request(options.output, 0.0);
  if (options.max_events < 0)
    throw InvalidArgument("max_events = " + std::to_string(options.max_events) +
                          " is invalid: must be an integer >= 0");
  if (!options.smooth_integrator.empty() && integrator != "event_driven")
    throw InvalidArgument("smooth_integrator = \"" + options.smooth_integrator +
                          "\" is invalid with integrator = \"" + integrator +
                          "\": only \"event_driven\" takes one (the method between its events)");
  if (integrator == "moreau") {  // what simulate_moreau checks, from t = 0
    integrate::check_moreau_options(options.output.t_end, drive::moreau_options(options));
    check_step_resolves_loads(options.dt, options.output.t_end,
                              {&rotor_drive(p), &p.axial_force, &p.base_acceleration,
                               &p.base_angular_acceleration});
    check_theta_stable_with_springs(model, options);
    return;
  }
  check_ode_options(model, integrator, options);
}

namespace drive {

// The integrator simulate() runs ("" in the options: the model's default).
// The list's first: the event-driven scheme where it runs the scene, else
// Moreau-Jean (the train's stages beyond the event-driven scheme's reach:
// model_integrators), so that a valid scene runs at its defaults.
const std::string& chosen_integrator(const DriveModel& model,
                                     const DriveSimulationOptions& options) {
  return options.integrator.empty() ? model_integrators(model).front() : options.integrator;
}

// The ODE method of the smooth phases: the integrator itself, or inside
// "event_driven" the smooth_integrator option (default: our Verner 6(5)
// with exact event location for a model without force elements (the rigid
// concept), an order of magnitude cheaper than CVODE; BDF where springs and
// dampers make it stiff (the flexible concepts). CVODE used to lose
// flank events of a rattling nut, 3 to 8 of 36 at rtol 1e-12; with
// handle_event's touch below resolution it finds the same ones:
// tests/test_integrate_flank_events.py).
std::string ode_method(const DriveModel& model, const std::string& integrator,
                       const DriveSimulationOptions& options) {
  if (integrator != "event_driven") return integrator;
  if (!options.smooth_integrator.empty()) return options.smooth_integrator;
  // (A transverse slip's set-valued cone jumps at its apex, where CVODE's
  // restarts missed the creep: the explicit pair, also beside force
  // elements such as penalty end stops; check_transverse_slip.)
  if (has_transverse_slip(model.parameters()) &&
      model.law().resolution() == friction::Resolution::set_valued)
    return "rk_verner6";
  return model.elements().forces.empty() ? "rk_verner6" : "cvode_bdf";
}

// Moreau-Jean's dt, theta and step count from the options.
integrate::MoreauOptions moreau_options(const DriveSimulationOptions& options) {
  return {options.dt, options.theta, options.integrator_options.max_steps};
}

integrate::EventDrivenOptions event_driven_options(const DriveModel& model,
                                                   const friction::Law& law,
                                                   const std::string& integrator,
                                                   const DriveSimulationOptions& options) {
  integrate::EventDrivenOptions driver;
  driver.integrator_options = options.integrator_options;
  driver.max_events = options.max_events;
  driver.integrator = ode_method(model, integrator, options);
  // The springs and dampers of the flexible models carry their stiff modes.
  const bool stiff = !model.elements().forces.empty();
  // The regularized friction laws are stiff near zero slip, and with the
  // flexible models' lightly damped modes BDF above order 3 is not stable
  // enough there: capped at 3 it was faster in every case measured
  // (flexible_nut and flexible, no play and bistop, rtol 1e-4 ... 1e-8: 1.1 to
  // 2.1x) and it no longer fails at loose tolerances (order 5: CV_ERR_FAILURE
  // at rtol 1e-4). Tighter than 1e-9 the higher orders pay again. The smooth
  // phases of exact Coulomb carry no such law: there order 5 took 1.4 to 2.5x
  // fewer steps at the same error (no play and exact backlash, rtol 1e-6 and
  // 1e-8), and order 3 ran past a million steps for a rattling flexible nut at
  // rtol 1e-9.
  if (driver.integrator == "cvode_bdf" && stiff &&
      law.resolution() != friction::Resolution::set_valued &&
      driver.integrator_options.max_order == 0 &&
      driver.integrator_options.rtol >= 1e-9)
    driver.integrator_options.max_order = 3;
  // Eq. (3.15)'s friction follows the slip acceleration, which carries the
  // stiff modes of the flexible drives: the tangential inertia the law adds,
  // (2/pi) mu' k_V |N| d / (1 + (k_V gamma_T')^2), switches on and off
  // within one period of the fastest mode. CVODE's modified Newton, its
  // Jacobian frozen over several steps, then needs more than its default 3
  // iterations: with 3 it failed at every step (a nut-driven flexible drive,
  // 0.2 s: 229,147 steps, 225,258 convergence failures, 14 s), with 10 it
  // took 10,985 steps and 0.13 s.
  if (law.resolution() == friction::Resolution::acceleration && stiff)
    driver.integrator_options.max_nonlinear_iterations = 10;
  return driver;
}

}  // namespace drive

}  // namespace leadscrew::model
