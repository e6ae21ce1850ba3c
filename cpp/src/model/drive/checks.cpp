// The checks of a drive's result (checks.hpp).
#include "checks.hpp"

#include <algorithm>
#include <cmath>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/integrate/event_driven.hpp"
#include "leadscrew/model/result_checks.hpp"
#include "state_layout.hpp"

namespace leadscrew::model::drive {

void check_drive_result(const DriveModel& model, const friction::Law& law,
                        const DriveSimulationOptions& options, bool time_stepping,
                        integrate::SimulationResult& result, double step_play_rate,
                        double step_friction_excess) {
  const DriveParameters& p = model.parameters();
  ResultCheckSpec spec;
  spec.work = {"work_drive", "work_axial"};
  spec.stored = {"kinetic", "elastic"};
  spec.losses = {"friction_loss", "damping_loss", "contact_loss", "impact_loss"};
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
  // (A DC motor's magnetic energy L i^2 / 2 is kinetic-like: |L i| <= sqrt(2 E L).)
  const elements::DcMotor* dc = model.dc_motor();
  spec.momentum_factor = std::sqrt(2.0 * (model.mass().sum() + (dc ? dc->inductance : 0.0)));
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
  spec.force_factor = std::sqrt(2.0 * stiffness);
  spec.quadratures = kEnergyCount + 1;  // and the impact loss, booked at events
  if (dc) {  // the electrical work is work_drive's
    spec.stored.push_back("magnetic_energy");
    spec.losses.push_back("copper_loss");
    spec.quadratures += 1;
  }
  // The train's friction stages: each loss its own channel, never falling.
  if (const elements::TrainFriction* train = model.train_friction()) {
    for (const char* name : {"motor_friction_loss", "gear_loss"}) {
      if (name[0] == 'm' ? !train->motor_friction_present() : !train->stage) continue;
      spec.losses.push_back(name);
      spec.quadratures += 1;
    }
  }
  spec.load_forces = {"axial_force"};
  spec.load_torques = {"drive_torque"};
  if (const elements::PreloadedNut* nut = model.preloaded_nut(); nut && nut->lift_off) {
    // A lift-off nut: its channel |N_A| + |N_B| (half A's force is the
    // penalty flanks', the spring's changes with the play), its spring's rate.
    spec.normal = "flank_normal";
    stiffness += nut->stiffness;
    spec.force_factor = std::sqrt(2.0 * stiffness);
  } else if (nut) {
    spec.flank_normal = [nut = *nut](double normal, double friction) {
      return nut.flank_normal(normal, friction);
    };
  }
  // (the drive torque is the rotor's: n times it acts on the driven part)
  spec.lever = p.thread.mean_radius() / std::abs(model.gear().ratio);
  spec.length_scale = p.screw_length;
  check_result(spec, result);
  if (!options.check) return;
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
  integrate::enforce_checks(result);
}

}  // namespace leadscrew::model::drive
