#include "leadscrew/model/drive.hpp"

#include <algorithm>
#include <cmath>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/model/drive_dynamics.hpp"
#include "leadscrew/model/drive_equilibrium.hpp"
#include "leadscrew/model/drive_geometry.hpp"
#include "leadscrew/model/drive_rigid.hpp"

namespace leadscrew::model {

const std::vector<ScalarField>& scalar_fields() {
#define LEADSCREW_FIELD(name) ScalarField{#name, &DriveParameters::name}
  static const std::vector<ScalarField> fields = {
      LEADSCREW_FIELD(mu),
      LEADSCREW_FIELD(k_v),
      LEADSCREW_FIELD(clearance),
      LEADSCREW_FIELD(restitution),
      LEADSCREW_FIELD(contact_stiffness),
      LEADSCREW_FIELD(contact_exponent),
      LEADSCREW_FIELD(contact_damping),
      LEADSCREW_FIELD(contact_penetration),
      LEADSCREW_FIELD(rotor_inertia),
      LEADSCREW_FIELD(load_mass),
      LEADSCREW_FIELD(screw_mass),
      LEADSCREW_FIELD(screw_inertia),
      LEADSCREW_FIELD(nut_mass),
      LEADSCREW_FIELD(nut_inertia),
      LEADSCREW_FIELD(screw_axial_rigidity),
      LEADSCREW_FIELD(screw_torsional_rigidity),
      LEADSCREW_FIELD(screw_length),
      LEADSCREW_FIELD(nut_position),
      LEADSCREW_FIELD(nut_length),
      LEADSCREW_FIELD(screw_axial_stiffness),
      LEADSCREW_FIELD(screw_torsional_stiffness),
      LEADSCREW_FIELD(nut_axial_stiffness),
      LEADSCREW_FIELD(nut_torsional_stiffness),
      LEADSCREW_FIELD(damping_ratio),
      LEADSCREW_FIELD(screw_axial_damping),
      LEADSCREW_FIELD(screw_torsional_damping),
      LEADSCREW_FIELD(nut_axial_damping),
      LEADSCREW_FIELD(nut_torsional_damping),
      LEADSCREW_FIELD(nut_preload),
      LEADSCREW_FIELD(nut_preload_stiffness),
      LEADSCREW_FIELD(rotor_angle),
      LEADSCREW_FIELD(rotor_speed),
      LEADSCREW_FIELD(play_position),
      LEADSCREW_FIELD(gear_ratio),
      LEADSCREW_FIELD(motor_friction_torque),
      LEADSCREW_FIELD(gear_efficiency),
      LEADSCREW_FIELD(gear_efficiency_backdrive),
      LEADSCREW_FIELD(gear_lead_angle),
      LEADSCREW_FIELD(gear_mu),
      LEADSCREW_FIELD(gear_mu_static),
      LEADSCREW_FIELD(gear_flank_angle),
  };
#undef LEADSCREW_FIELD
  return fields;
}

// One list per enumeration, in the order of its values: the names and the
// parser cannot drift apart.
const std::vector<std::string>& concept_names() {
  static const std::vector<std::string> names = {"rigid", "flexible_nut", "flexible"};
  return names;
}
const std::vector<std::string>& drive_names() {
  static const std::vector<std::string> names = {"screw", "nut"};
  return names;
}
const std::vector<std::string>& support_names() {
  static const std::vector<std::string> names = {"both_ends", "drive_end"};
  return names;
}
const std::vector<std::string>& backlash_contact_names() {
  static const std::vector<std::string> names = {"none", "exact", "bistop", "cubic"};
  return names;
}
const std::vector<std::string>& initial_state_names() {
  static const std::vector<std::string> names = {"relaxed", "equilibrium"};
  return names;
}

const std::vector<std::string>& gear_type_names() {
  static const std::vector<std::string> names = {"none", "ideal", "lossy", "worm"};
  return names;
}

bool has_transverse_slip(const DriveParameters& p) {
  // (zero at all times: a constant 0, or a sine of no amplitude and offset)
  const Excitation::Definition d = p.transverse_slip_velocity.definition();
  if (d.kind == "constant") return d.parameters.at(0) != 0.0;
  if (d.kind == "sine") return d.parameters.at(0) != 0.0 || d.parameters.at(3) != 0.0;
  return true;
}

std::string concept_name(Concept c) { return concept_names()[static_cast<int>(c)]; }
std::string drive_name(DrivenPart d) { return drive_names()[static_cast<int>(d)]; }
std::string support_name(ScrewSupport s) { return support_names()[static_cast<int>(s)]; }
std::string backlash_contact_name(BacklashContact b) {
  return backlash_contact_names()[static_cast<int>(b)];
}

std::string initial_state_name(InitialState s) {
  return initial_state_names()[static_cast<int>(s)];
}

std::string gear_type_name(GearType g) { return gear_type_names()[static_cast<int>(g)]; }

GearType parse_gear_type(const std::string& name) {
  return static_cast<GearType>(require_choice("gear.type", name, gear_type_names()));
}

Concept parse_concept(const std::string& name) {
  return static_cast<Concept>(require_choice("concept", name, concept_names()));
}

DrivenPart parse_drive(const std::string& name) {
  return static_cast<DrivenPart>(require_choice("drive", name, drive_names()));
}

ScrewSupport parse_support(const std::string& name) {
  return static_cast<ScrewSupport>(require_choice("screw.support", name, support_names()));
}

BacklashContact parse_backlash_contact(const std::string& name) {
  return static_cast<BacklashContact>(
      require_choice("backlash.contact", name, backlash_contact_names()));
}

InitialState parse_initial_state(const std::string& name) {
  return static_cast<InitialState>(require_choice("initial.state", name, initial_state_names()));
}

DriveModel::DriveModel(DriveParameters parameters)
    : p_(std::move(parameters)), e_(elements::build_drive_elements(p_)) {
  const int n = e_.coordinate_count();
  mass_ = Eigen::VectorXd::Zero(n);
  for (const elements::RigidBody& body : e_.bodies) body.add_mass(mass_);
  e_.forces.for_each([&](const auto& s) { springs_on_screw_ = springs_on_screw_ || s.on_screw; });
  for (int i = 0; i < n; ++i)
    if (i != eliminated()) independent_.push_back(i);
  // The event-driven scheme's obstacles to the train's stages that only the
  // built model tells (the thread's Painleve regime needs the masses): with
  // one, Moreau-Jean is the scene's default (drive::model_integrators).
  if (e_.train_friction && e_.train_friction->event_driven_obstacle.empty() &&
      !p_.speed_controlled && p_.concept == Concept::rigid &&
      p_.backlash == BacklashContact::none && p_.friction == "coulomb")
    e_.train_friction->event_driven_obstacle =
        RigidDriveModes::train_obstacle(*this, DriveDynamics(*this));
  place_stops_at_equilibrium();
}

// initial.state = equilibrium with end stops: the stops' faces are relative
// to the load's start, the equilibrium's u_load (docs/physics/end_stops.md,
// "The scene"). The load starts strictly between them (lower < 0 < upper),
// where they exert no force: the equilibrium is the drive's without them,
// solved once here (the model of the same parameters without the section)
// and the faces moved by its u_load.
void DriveModel::place_stops_at_equilibrium() {
  if (p_.initial_state != InitialState::equilibrium ||
      (e_.exact_stops.empty() && e_.end_stops().empty()))
    return;
  DriveParameters without = p_;
  without.sections.erase("end_stops");
  const DriveModel free(without);
  const double start = initial_state(free).q[free.load()];
  for (elements::ExactEndStop& stop : e_.exact_stops) stop.position += start;
  for (elements::EndStop& stop : e_.forces.of<elements::EndStop>()) stop.position += start;
}

Eigen::VectorXd DriveModel::consistent_velocity(double rotor_speed) const {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(coordinate_count());
  for (int i : e_.rotating_group) v[i] = gear().driven_speed(rotor_speed);
  // The translating parts move together so that e' = grad e . v = 0.
  double per_unit = 0.0;
  for (int i : e_.translating_group) per_unit += play_gradient()[i];
  const double speed = per_unit != 0.0 ? -play_gradient().dot(v) / per_unit : 0.0;
  for (int i : e_.translating_group) v[i] = speed;
  return v;
}

double DriveModel::screw_end_margin(double nut_position) const noexcept {
  return model::screw_end_margin(nut_position, p_.nut_length, p_.screw_length);
}

std::string DriveModel::nut_off_screw(double nut_position) const {
  return "the nut reached the end of the screw (nut position " + format_value(nut_position) +
         " m on a screw of length " + format_value(p_.screw_length) + " m, nut length " +
         format_value(p_.nut_length) + " m)";
}

}  // namespace leadscrew::model
