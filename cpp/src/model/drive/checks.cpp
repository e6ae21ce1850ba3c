// The checks of a drive's result (checks.hpp).
#include "checks.hpp"

#include <algorithm>
#include <cmath>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/integrate/event_driven.hpp"
#include "leadscrew/model/result_checks.hpp"
#include "channels.hpp"
#include "declaration.hpp"
#include "state_layout.hpp"

namespace leadscrew::model::drive {

namespace {

// The energy account's channels, by their roles.
ResultCheckSpec account_spec(const std::vector<Declaration>& declarations) {
  ResultCheckSpec spec;
  // The energy account's channels, the base's then the elements' (each loss
  // an integral in y: one quadrature each), by their roles.
  spec.quadratures = kEnergyCount + 1;  // and the impact loss, booked at events
  auto account = [&](const ChannelSpec& c, bool element) {
    switch (c.role) {
      case Role::work: spec.work.push_back(c.name); break;
      case Role::stored: spec.stored.push_back(c.name); break;
      case Role::loss:
        spec.losses.push_back(c.name);
        spec.quadratures += element ? 1 : 0;
        break;
      case Role::load_force: spec.load_forces.push_back(c.name); break;
      case Role::load_torque: spec.load_torques.push_back(c.name); break;
      case Role::flank_normal: spec.normal = c.name; break;
      case Role::none: break;
    }
  };
  for (const std::vector<ChannelSpec>* list : {&base_channels(), &account_channels()})
    for (const ChannelSpec& c : *list) account(c, false);
  for (const Declaration& d : declarations)
    for (const ChannelSpec& c : d.channels) account(c, true);
  return spec;
}

// The scales of the state's round-off: |p| <= sqrt(2 E m) and |k x| <=
// sqrt(2 E k).
void scale_spec(const DriveModel& model, const std::vector<Declaration>& declarations,
                ResultCheckSpec& spec) {
  const DriveParameters& p = model.parameters();
  // (An element's kinetic-like energy, a DC motor's L i^2 / 2: |L i| <= sqrt(2 E L).)
  double momentum_mass = model.mass().sum();
  for (const Declaration& d : declarations)
    if (d.momentum_mass != 0.0) momentum_mass += d.momentum_mass;
  spec.momentum_factor = std::sqrt(2.0 * momentum_mass);
  // sum |k x| <= sqrt(2 E sum k) for the springs at their stiffest over the
  // screw's length (the stiffness of eq. 4.24 grows toward its ends; the
  // nut's whole length stays on it), and the flank's force for a penalty
  // contact, whose energy is not quadratic: taken as its largest stiffness.
  double stiffness = p.contact_stiffness;
  model.elements().forces.for_each([&](const auto& element) {
    double k = 0.0;
    for (const double a : {0.5 * p.nut_length, p.nut_position,
                           p.screw_length - 0.5 * p.nut_length}) {
      double derivative = 0.0;
      k = std::max(k, element.stiffness_at(a, &derivative));
    }
    stiffness += k;
  });
  // The elements' (a lift-off nut's spring), and the normal force their
  // friction multiplies (a preloaded nut's halves).
  for (const Declaration& d : declarations) {
    if (d.stiffness != 0.0) stiffness += d.stiffness;
    if (d.flank_normal) spec.flank_normal = d.flank_normal;
  }
  spec.force_factor = std::sqrt(2.0 * stiffness);
}

void check_half_b_slip(const DriveModel& model, const integrate::SimulationResult& result) {
  // A lift-off nut's half B books its friction on its own slip gamma_T -
  // sin(a) e' with the direction of the nut's slip (one friction mode for
  // both halves, preloaded_nut.hpp): where the play's motion reverses half
  // B's own slip against the nut's, that friction would push, and its loss
  // falls. The check catches it; the reason is the model's limit, not the
  // tolerances (a new user's review: vibration of 200 N at 50 Hz on a
  // slowly driven split nut in bistop play).
  const elements::PreloadedNut* nut = model.preloaded_nut();
  if (nut && nut->lift_off)
    for (const integrate::InvariantCheck& check : result.checks)
      if (check.applies && !check.passed && std::string(check.name) == "friction_loss")
        throw SimulationError(
            check.time,
            "the preloaded nut's half B slips against the nut's slip (its friction loss falls "
            "by " + format_value(check.value) + " J against the bound " +
            format_value(check.bound) + " J): the halves slip apart, which the model's one "
            "friction mode for both halves does not resolve",
            "docs/physics/preloaded_nut.md, \"Lift-off\"; a stiffer nut.preload_stiffness "
            "or a larger nut.preload keeps half A on its flank");
}

}  // namespace

void check_drive_result(const DriveModel& model, const friction::Law& law,
                        const DriveSimulationOptions& options, bool time_stepping,
                        integrate::SimulationResult& result, double step_play_rate,
                        double step_friction_excess) {
  const DriveParameters& p = model.parameters();
  // The elements' declarations (declaration.hpp), as the run's layout has them.
  const std::vector<Declaration> declarations =
      declare_elements(model, law);
  ResultCheckSpec spec = account_spec(declarations);
  // A transverse slip's cone: the friction checks take the 2-D vectors
  // (|lambda| against mu' |N|, lambda . (gamma, w) >= 0).
  if (has_transverse_slip(p)) {
    spec.transverse_slip = "transverse_velocity";
    spec.transverse_friction = "transverse_friction";
  }
  spec.t_end = options.output.t_end;
  spec.law = &law;
  spec.coefficient_scale = model.flank_factor();
  // Eq. (3.15)'s law can do positive work (its friction follows the slip
  // acceleration), and LuGre's bristles give back what they stored.
  spec.friction_dissipates = law.resolution() != friction::Resolution::acceleration &&
                             law.resolution() != friction::Resolution::bristle;
  spec.clearance = model.thread_pair().exact_play() ? p.clearance : 0.0;
  spec.time_step = time_stepping ? options.dt : 0.0;
  spec.step_play_rate = step_play_rate;
  spec.step_friction_excess = step_friction_excess;
  spec.slip_resolution =
      model.tangent_direction().cwiseAbs().sum() * options.integrator_options.atol;
  spec.time_stepping = time_stepping;
  spec.rtol = options.integrator_options.rtol;
  spec.atol = options.integrator_options.atol;
  spec.rows_are_steps = options.output.t_eval.empty();
  scale_spec(model, declarations, spec);
  // (the drive torque is the rotor's: n times it acts on the driven part)
  spec.lever = p.thread.mean_radius() / std::abs(model.gear().ratio);
  spec.length_scale = p.screw_length;
  check_result(spec, result);
  // The elements' own checks (model/element.hpp: a DC motor's driver and
  // armature).
  for (const std::shared_ptr<const Element>& element : model.elements().elements)
    element->check_result(options, time_stepping, result);
  if (result.checks.front().passed)  // (finite: else the others are not compared)
    result.checks.push_back(exact_stop_check(model, options, time_stepping, result));
  if (!options.check) return;
  check_half_b_slip(model, result);
  integrate::enforce_checks(result);
}

}  // namespace leadscrew::model::drive
