// The nut's transverse slip on the flank (loads.transverse_slip_velocity,
// issue 34; docs/physics/transverse_slip.md): the flank's friction is the
// isotropic cone on the slip (gamma, w) (exact Coulomb, Stribeck's curve on
// the slip speed |(gamma, w)|), gamma the helix slip and w
// the prescribed slip across it. Its declaration (the excitation's work on
// the transverse slip, a work integral in y; the channels w, the transverse
// friction and that work), the refusal of what is not implemented, and the
// event-driven driver's element (driver_element.hpp): a root at every zero
// of w, where the integrator restarts (no step straddles the cone's apex,
// where the slip vector vanishes for an instant), and the transverse
// friction's loss, (mu'(s) |N| + c s) w^2 / s, s = |(gamma, w)|, which the
// excitation's work balances. The helix coefficient mu'(s) gamma / s is
// DriveDynamics' (cone_coefficient): a smooth function of the slip that
// rides on the normal force as a velocity law's kappa does
// (FrictionMode::regularized_velocity). Moreau-Jean's step takes the exact
// cone in moreau_smooth_friction.cpp. LuGre's bristles are 2-D on it
// (DriveDynamics::bristle_rate, the constrained solver's states): the
// transverse friction is the bristles', its loss less what they store.
#include <cmath>

#include "driver_element.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/model/element_section.hpp"
#include "transverse_slip.hpp"

namespace leadscrew::model::drive {

const ElementKind& transverse_slip_kind();

namespace {

// Its channels (the declaration's, in this order).
enum Channel { kTransverseVelocity, kTransverseFriction, kWorkTransverse };

void declare(const DriveModel& model, const friction::Law& law, Declaration& d) {
  (void)law;
  if (!has_transverse_slip(model.parameters())) return;
  d.states = {"transverse_work"};
  d.channels = transverse_slip_kind().catalog;
}

class TransverseSlipElement final : public DriveHybrid::Element {
 public:
  TransverseSlipElement(DriveHybrid& hybrid, const Excitation& w)
      : Element(hybrid), w_(w) {}

  int root_count() const override { return 1; }
  void roots(double t, double* g) const override { g[0] = w_(t); }
  void root_directions(int* directions) const override { directions[0] = 0; }
  // A zero of w: the slip vector turns across the cone's apex; the
  // integrator restarts there, nothing else changes.
  Event handle(double t, double* y, const int* root_info) override {
    (void)t, (void)y, (void)root_info;
    return {};
  }

  void rates(double t, const double* y, double* ydot, double* energy) const override {
    (void)t, (void)y;
    const double w = dynamics().transverse_slip();
    const double loss =
        -dynamics().transverse_friction(solve_current().normal_force, dynamics().slip_velocity()) *
        w;
    ydot[first_state()] = loss;  // the excitation's work on the transverse slip
    energy[kFrictionLoss] += loss;
  }

  void output(double t, const double* y, const ContactForces& forces,
              ChannelState& state) const override {
    (void)t;
    double* values = state.values.data() + first_channel();
    values[kTransverseVelocity] = dynamics().transverse_slip();
    values[kTransverseFriction] =
        dynamics().transverse_friction(forces.normal, dynamics().slip_velocity());
    values[kWorkTransverse] = y[first_state()];
  }

 private:
  const Excitation& w_;
};

}  // namespace

const ElementKind& transverse_slip_kind() {
  static const ElementKind kind{"transverse_slip",
                                {{"transverse_velocity", "m/s", Role::none},
                                 {"transverse_friction", "N", Role::none},
                                 {"work_transverse", "J", Role::work}},
                                &declare};
  return kind;
}

std::unique_ptr<DriveHybrid::Element> make_transverse_slip_element(DriveHybrid& hybrid,
                                                                   const DriveModel& model) {
  if (!has_transverse_slip(model.parameters())) return nullptr;
  return std::make_unique<TransverseSlipElement>(hybrid,
                                                 model.parameters().transverse_slip_velocity);
}

void write_transverse_channels(const StateLayout& layout, const DriveDynamics& dynamics,
                               double transverse_friction, const double* y,
                               ChannelState& state) {
  const int channel = layout.find_channel("transverse_velocity");
  if (channel < 0) return;
  state.values[channel + kTransverseVelocity] = dynamics.transverse_slip();
  state.values[channel + kTransverseFriction] = transverse_friction;
  state.values[channel + kWorkTransverse] = y[layout.find_state("transverse_work")];
}

namespace {

// Where the excitation is held at zero over an interval (a table's segment
// between two zero knots, or its zero end), or cannot be known (a
// callable): the event-driven cone would need the 1-D modes there.
std::string held_at_zero_reason(const Excitation& w, double t_end) {
  const Excitation::Definition d = w.definition();
  if (d.kind == "sine" || d.kind == "constant") return "";
  if (d.kind != "table")
    return "a " + d.kind + " excitation, whose intervals held at zero (where the cone's "
           "stick with mu_static applies) the event-driven scheme cannot know ahead";
  const std::vector<double>& times = d.times;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const bool zero = d.values[k] == 0.0;
    const bool held_before = k == 0 && zero && times[k] > 0.0;
    const bool held_after = k + 1 == times.size() && zero && times[k] < t_end;
    const bool held_between = k + 1 < times.size() && zero && d.values[k + 1] == 0.0 &&
                              times[k] < t_end && times[k + 1] > 0.0;
    if (held_before || held_after || held_between)
      return "a table held at zero from t = " + format_value(held_before ? 0.0 : times[k]) +
             " s (where the cone's stick with mu_static applies: not implemented on the "
             "drive's event-driven scheme)";
  }
  return "";
}

// Where the concept, the law and the integrator meet the cone: the
// set-valued laws on the rigid concept's two schemes and the flexible
// concepts' Moreau-Jean; LuGre's 2-D bristles (a smooth right-hand side:
// no apex to restart on) on the ODE methods and the event-driven scheme's,
// every concept. Empty: they fit.
std::string law_obstacle(const DriveModel& model, const std::string& integrator) {
  const DriveParameters& p = model.parameters();
  const friction::Resolution resolution = model.law().resolution();
  if (resolution == friction::Resolution::bristle) return "";
  if (resolution != friction::Resolution::set_valued)
    return "friction.law = \"" + p.friction + "\"";
  if (integrator != "event_driven" && integrator != "moreau")
    return "integrator = \"" + integrator + "\"";
  if (p.concept != Concept::rigid && integrator != "moreau")
    return "concept = \"" + concept_name(p.concept) + "\" and integrator = \"" + integrator +
           "\" (not implemented: the flexible drives' event-driven integrator is CVODE, which "
           "missed the friction block's cone creep by 37-110 % at its restarts at the cone's "
           "apex)";
  return "";
}

// What else the drive carries that the cone does not take yet (exact play
// but on Moreau-Jean, whose step takes the flank's impacts with the cone;
// the train's friction stages (an ideal gear is a transmission), a
// preloaded nut, the elements
// but a DC motor, a base excitation and a load spring, exact end stops, the
// Painleve regime; penalty end stops are force elements, smooth in the
// state). Penalty play is a smooth normal force (its friction none where
// the flank does not touch: DriveDynamics::transverse_friction,
// DriveMoreau::book_transverse). Empty: none.
std::string drive_obstacle(const DriveModel& model, const std::string& integrator) {
  const DriveParameters& p = model.parameters();
  if (p.backlash == BacklashContact::exact && integrator != "moreau")
    return "backlash.contact = \"exact\" and integrator = \"" + integrator +
           "\" (the flank's impacts with the cone: Moreau-Jean's step takes them)";
  // (Tried on Moreau-Jean: the rigid drive's rotor contact found no
  // consistent stick/slip state at the zeros of w, and the flexible drives'
  // creep has no reference with the stage's friction in the balance yet.)
  if (model.train_friction())
    return (p.gear == GearType::lossy || p.gear == GearType::worm
                ? "gear.type = \"" + gear_type_name(p.gear) + "\""
                : "motor.friction_torque = " + format_value(p.motor_friction_torque) + " N m") +
           " (the train's friction contact beside the cone is not implemented)";
  if (model.preloaded_nut()) return "a preloaded nut";
  // (A DC motor is the rotor's drive, a base excitation the housing's
  // inertial loads, a load spring a force on the load: given forces of the
  // mode and of the step, as a drive torque and an axial force are.)
  for (const std::shared_ptr<const Element>& element : model.elements().elements) {
    const std::string name = element->name();
    if (name != "dc_motor" && name != "base_excitation" && name != "load_spring")
      return "an element besides the thread, the concept's springs, a DC motor, a base "
             "excitation and a load spring (" + name + ")";
  }
  // Exact stops on Moreau-Jean (where the load is rigid in the thread the
  // stop's row holds the thread's slip: stop_holds takes the cone's
  // direction at the prescribed slip); the event-driven scheme's stop modes
  // are not written for the cone.
  if (!model.elements().exact_stops.empty() && integrator != "moreau")
    return "end_stops.contact = \"exact\" and integrator = \"" + integrator + "\"";
  // (LuGre on Moreau-Jean where the stop's row holds the slip takes the
  // 1-D bristles' balance, moreau_held_bristles.cpp: not the cone's.)
  if (!model.elements().exact_stops.empty() &&
      model.law().resolution() == friction::Resolution::bristle)
    return "end_stops.contact = \"exact\" and friction.law = \"lugre\" (the held stop's "
           "rows take the 1-D bristles only)";
  if (DriveDynamics(model).painleve_possible()) return "the thread in the Painleve regime";
  return "";
}

}  // namespace

void check_transverse_slip(const DriveModel& model, const std::string& integrator,
                           const std::string& smooth_integrator, double t_end) {
  const DriveParameters& p = model.parameters();
  if (!has_transverse_slip(p)) return;
  const std::string key =
      "loads.transverse_slip_velocity = " + p.transverse_slip_velocity.describe();
  const std::string supported =
      "the flank's 2-D friction cone is implemented without play and with penalty play "
      "(backlash.contact = \"none\", \"bistop\" or \"cubic\"; \"exact\" on "
      "integrator = \"moreau\"), with a drive torque, a DC motor or a prescribed rotor "
      "speed, an ideal gear, a base excitation, a load spring and penalty end stops (exact "
      "ones on integrator = \"moreau\", not with LuGre; no lossy or worm gear stage, "
      "motor friction or "
      "preloaded nut), friction.law = "
      "\"coulomb\" (mu, "
      "mu_static) or \"stribeck\" (its curve on the 2-D slip speed, the viscous term along "
      "the slip), on concept = \"rigid\" with integrator = "
      "\"event_driven\" or \"moreau\" and on the flexible concepts with integrator = "
      "\"moreau\"; friction.law = \"lugre\" (2-D bristles) on every concept with "
      "integrator = \"event_driven\", an ODE method such as \"cvode_bdf\" or \"moreau\" "
      "(docs/physics/transverse_slip.md)";
  std::string obstacle = law_obstacle(model, integrator);
  if (obstacle.empty()) obstacle = drive_obstacle(model, integrator);
  if (!obstacle.empty())
    throw InvalidArgument(key + " is invalid with " + obstacle + ": " + supported);
  // (LuGre's bristles have no stick: a w held at zero is a slip like any.)
  if (integrator == "event_driven" &&
      model.law().resolution() == friction::Resolution::set_valued) {
    if (smooth_integrator.rfind("cvode", 0) == 0)
      throw InvalidArgument(key + " is invalid with smooth_integrator = \"" +
                            smooth_integrator + "\": the set-valued cone jumps at its apex, "
                            "where CVODE's restarts missed the friction block's creep by "
                            "37-110 %; leave smooth_integrator out (the Verner pair runs) or "
                            "name an explicit pair (\"rk_verner6\", \"rk_dopri5\", "
                            "\"verner6\", \"dopri5\")");
    const std::string held = held_at_zero_reason(p.transverse_slip_velocity, t_end);
    if (!held.empty())
      throw InvalidArgument(key + " is invalid on integrator = \"event_driven\" with " + held +
                            "; use integrator = \"moreau\", whose step takes the 1-D "
                            "Coulomb step where w is zero");
  }
}

}  // namespace leadscrew::model::drive
