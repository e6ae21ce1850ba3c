#include "leadscrew/model/drive.hpp"

#include <algorithm>
#include <cmath>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/model/drive_geometry.hpp"

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
      LEADSCREW_FIELD(rotor_angle),
      LEADSCREW_FIELD(rotor_speed),
      LEADSCREW_FIELD(play_position),
  };
#undef LEADSCREW_FIELD
  return fields;
}

namespace {

// Coordinates of the screw's and the nut's contact bodies: an index into q, or
// -1 where the support fixes that motion.
struct ContactCoordinates {
  int screw_u = -1, screw_phi = -1, nut_u = -1, nut_phi = -1;
};

void add_gradient(Eigen::VectorXd& gradient, int index, double value) {
  if (index >= 0) gradient[index] += value;
}

}  // namespace

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

std::string concept_name(Concept c) { return concept_names()[static_cast<int>(c)]; }
std::string drive_name(DrivenPart d) { return drive_names()[static_cast<int>(d)]; }
std::string support_name(ScrewSupport s) { return support_names()[static_cast<int>(s)]; }
std::string backlash_contact_name(BacklashContact b) {
  return backlash_contact_names()[static_cast<int>(b)];
}

std::string initial_state_name(InitialState s) {
  return initial_state_names()[static_cast<int>(s)];
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

DriveModel::DriveModel(DriveParameters parameters) : p_(std::move(parameters)) {
  require_nonnegative("friction.mu", p_.mu);
  require_positive("friction.k_v", p_.k_v);
  {
    // The law: mu, k_v where it takes it, and its other parameters.
    const friction::LawType& type = friction::law_type(p_.friction);
    friction::LawValues values = {{"mu", p_.mu}};
    for (const friction::ParameterInfo& parameter : type.parameters)
      if (std::string(parameter.key) == "k_v") values.emplace_back("k_v", p_.k_v);
    values.insert(values.end(), p_.friction_values.begin(), p_.friction_values.end());
    law_ = friction::make_law(p_.friction, values);
  }
  require_positive("rotor.inertia", p_.rotor_inertia);
  require_nonnegative("load.mass", p_.load_mass);
  require_nonnegative("backlash.axial", p_.clearance);
  require_in_range("backlash.restitution", p_.restitution, 0.0, 1.0);
  require_finite("initial.rotor_angle", p_.rotor_angle);
  require_finite("initial.rotor_speed", p_.rotor_speed);
  require_finite("initial.play_position", p_.play_position);
  // Exact flank contacts with zero play touch both flanks at once: that is
  // the thread without play.
  if (p_.backlash == BacklashContact::exact && p_.clearance == 0.0)
    p_.backlash = BacklashContact::none;
  if (p_.backlash == BacklashContact::bistop || p_.backlash == BacklashContact::cubic) {
    require_positive("backlash.stiffness", p_.contact_stiffness);
    require_nonnegative("backlash.damping", p_.contact_damping);
    require_positive("backlash.penetration", p_.contact_penetration);
    require_in_range("backlash.exponent", p_.contact_exponent, 1.0, 10.0);
  }
  if (p_.backlash == BacklashContact::none) {
    p_.clearance = 0.0;
  }
  // A play below a picometre is below the resolution of the positions it is
  // the difference of (round-off of coordinates of up to a metre, 1e-16 m).
  if (p_.clearance > 0.0 && p_.clearance < kSmallestClearance)
    throw InvalidArgument("backlash.axial = " + format_value(p_.clearance) +
                          " is invalid: must be 0 (no play) or >= " +
                          format_value(kSmallestClearance) +
                          " m (a smaller play is below the resolution of the positions)");
  if (std::abs(p_.play_position) > 0.5 * p_.clearance)
    throw InvalidArgument("initial.play_position = " + format_value(p_.play_position) +
                          " is invalid: must be within +-backlash.axial / 2 = +-" +
                          format_value(0.5 * p_.clearance));
  if (p_.initial_state == InitialState::equilibrium) {
    // The equilibrium is at rest, under a torque (a speed-controlled motor
    // would make the thread's friction force statically indeterminate), with
    // the nut where the loads put it.
    const std::string with = " is invalid with initial.state = \"equilibrium\": ";
    if (p_.speed_controlled)
      throw InvalidArgument("initial.state = \"equilibrium\" is invalid with loads.drive_speed: "
                            "the static equilibrium needs a torque-controlled motor "
                            "(loads.drive_torque)");
    if (p_.rotor_speed != 0.0)
      throw InvalidArgument("initial.rotor_speed = " + format_value(p_.rotor_speed) + with +
                            "must be 0 (the drive starts at rest)");
    if (p_.play_position != 0.0)
      throw InvalidArgument("initial.play_position = " + format_value(p_.play_position) + with +
                            "must be 0 (the equilibrium puts the nut on the flank the loads "
                            "press it against)");
  }

  const bool nut_flexible = p_.concept != Concept::rigid;
  const bool screw_flexible = p_.concept == Concept::flexible;
  const bool screw_rotates = p_.drive == DrivenPart::screw;
  const bool rotating_flexible = screw_rotates ? screw_flexible : nut_flexible;
  const bool translating_flexible = screw_rotates ? nut_flexible : screw_flexible;
  const std::string rotating = screw_rotates ? "screw" : "nut";
  const std::string translating = screw_rotates ? "nut" : "screw";
  const double rotating_mass = screw_rotates ? p_.screw_mass : p_.nut_mass;
  const double rotating_inertia = screw_rotates ? p_.screw_inertia : p_.nut_inertia;
  const double translating_mass = screw_rotates ? p_.nut_mass : p_.screw_mass;
  const double translating_inertia = screw_rotates ? p_.nut_inertia : p_.screw_inertia;
  require_nonnegative(rotating + " mass", rotating_mass);
  require_nonnegative(rotating + " inertia", rotating_inertia);
  require_nonnegative(translating + " mass", translating_mass);
  require_nonnegative(translating + " inertia", translating_inertia);

  std::vector<double> masses;
  names_.push_back("phi_rotor");
  masses.push_back(p_.rotor_inertia + (rotating_flexible ? 0.0 : rotating_inertia));
  int rotating_u = -1, rotating_phi = 0, translating_u = -1, translating_phi = -1;
  // A flexible part is its own contact body: coordinates u_<part> and phi_<part>.
  auto add_contact_body = [&](const std::string& part, double mass, double inertia, int& u,
                              int& phi) {
    u = static_cast<int>(names_.size());
    names_.push_back("u_" + part);
    masses.push_back(require_positive(part + " mass", mass));
    phi = static_cast<int>(names_.size());
    names_.push_back("phi_" + part);
    masses.push_back(require_positive(part + " inertia", inertia));
  };
  if (rotating_flexible)
    add_contact_body(rotating, rotating_mass, rotating_inertia, rotating_u, rotating_phi);
  if (translating_flexible)
    add_contact_body(translating, translating_mass, translating_inertia, translating_u,
                     translating_phi);
  const int load_index = static_cast<int>(names_.size());
  names_.push_back("u_load");
  const double load_total = p_.load_mass + (translating_flexible ? 0.0 : translating_mass);
  if (!(load_total > 0.0))
    throw InvalidArgument("load.mass = " + format_value(p_.load_mass) +
                          " is invalid: must be > 0 when the " + translating +
                          " is flexible or massless");
  masses.push_back(load_total);
  if (!translating_flexible) translating_u = load_index;
  rotating_group_ = {0};
  if (rotating_flexible) rotating_group_.push_back(rotating_phi);
  translating_group_ = {load_index};
  if (translating_flexible) translating_group_.push_back(translating_u);
  mass_ = Eigen::Map<Eigen::VectorXd>(masses.data(), static_cast<Eigen::Index>(masses.size()));

  ContactCoordinates c;
  if (screw_rotates) {
    c = {rotating_u, rotating_phi, translating_u, translating_phi};
  } else {
    c = {translating_u, translating_phi, rotating_u, rotating_phi};
  }

  // Springs of the flexible parts (thesis eq. 4.16, 4.26).
  auto screw_law = [&](bool axial) {
    const double override_value = axial ? p_.screw_axial_stiffness : p_.screw_torsional_stiffness;
    return override_value > 0.0 ? Spring::Law::constant
                                : (axial ? Spring::Law::screw_axial : Spring::Law::screw_torsional);
  };
  auto add_spring = [&](const std::string& name, int first, int second, bool screw, bool axial) {
    Spring s;
    s.name = name;
    s.first = first;
    s.second = second;
    if (screw) {
      s.law = screw_law(axial);
      s.stiffness = axial ? p_.screw_axial_stiffness : p_.screw_torsional_stiffness;
      s.damping = axial ? p_.screw_axial_damping : p_.screw_torsional_damping;
    } else {
      s.law = Spring::Law::constant;
      s.stiffness = axial ? p_.nut_axial_stiffness : p_.nut_torsional_stiffness;
      s.damping = axial ? p_.nut_axial_damping : p_.nut_torsional_damping;
    }
    springs_.push_back(s);
  };
  if (rotating_flexible) {
    add_spring(rotating + " torsion", rotating_phi, 0, screw_rotates, false);
    add_spring(rotating + " axial", rotating_u, -1, screw_rotates, true);
  }
  if (translating_flexible) {
    add_spring(translating + " axial", translating_u, load_index, !screw_rotates, true);
    add_spring(translating + " torsion", translating_phi, -1, !screw_rotates, false);
  }

  const int n = coordinate_count();
  position_gradient_ = Eigen::VectorXd::Zero(n);
  add_gradient(position_gradient_, c.nut_u, 1.0);
  add_gradient(position_gradient_, c.screw_u, -1.0);

  // Screw stiffness data, checked at the initial nut position.
  if (screw_flexible) {
    if (p_.screw_axial_stiffness <= 0.0) require_positive("screw axial rigidity E A", p_.screw_axial_rigidity);
    if (p_.screw_torsional_stiffness <= 0.0)
      require_positive("screw torsional rigidity G I_p", p_.screw_torsional_rigidity);
  }
  // The whole nut on the screw, for every concept (a run ends where it leaves).
  require_positive("screw.length", p_.screw_length);
  require_positive("nut.position", p_.nut_position);
  if (!(p_.nut_position < p_.screw_length))
    throw InvalidArgument("nut.position = " + format_value(p_.nut_position) +
                          " is invalid: must be < screw.length = " +
                          format_value(p_.screw_length));
  require_positive("nut.length", p_.nut_length);
  require_nut_on_screw(p_.drive, p_.nut_position, p_.nut_length, p_.screw_length, false);
  require_nonnegative("overrides.damping_ratio", p_.damping_ratio);
  for (Spring& s : springs_) {
    double derivative = 0.0;
    const double k = spring_stiffness(s, p_.nut_position, &derivative);
    require_positive(s.name + " stiffness", k);
    if (s.damping < 0.0) {
      // The mode that matters on a spring is the heavier body's (the load
      // bouncing on the nut, the screw on its support): the reduced mass
      // would leave it nearly undamped.
      const double carried = s.second >= 0 ? std::max(mass_[s.first], mass_[s.second])
                                           : mass_[s.first];
      s.damping = 2.0 * p_.damping_ratio * std::sqrt(k * carried);
    }
    require_finite(s.name + " damping", s.damping);
  }

  const double h = p_.thread.hand_sign();
  const double lead_per_radian = p_.thread.lead_per_radian();
  const double r_m = p_.thread.mean_radius();
  const double alpha = p_.thread.lead_angle();
  play_gradient_ = Eigen::VectorXd::Zero(n);
  add_gradient(play_gradient_, c.screw_u, 1.0);
  add_gradient(play_gradient_, c.nut_u, -1.0);
  add_gradient(play_gradient_, c.screw_phi, -h * lead_per_radian);
  add_gradient(play_gradient_, c.nut_phi, h * lead_per_radian);
  normal_ = std::cos(alpha) * play_gradient_;
  tangent_ = Eigen::VectorXd::Zero(n);
  add_gradient(tangent_, c.screw_u, std::sin(alpha));
  add_gradient(tangent_, c.nut_u, -std::sin(alpha));
  add_gradient(tangent_, c.screw_phi, h * r_m * std::cos(alpha));
  add_gradient(tangent_, c.nut_phi, -h * r_m * std::cos(alpha));
  mu_eff_ = p_.thread.effective_mu(p_.mu);
  flank_factor_ = p_.mu > 0.0 ? mu_eff_ / p_.mu : p_.thread.effective_mu(1.0);

  // Without play the thread is a kinematic constraint e = 0: eliminate a
  // translational coordinate of the thread pair (the nut's, as the thesis
  // eliminates u_2 in eq. 4.9 and 4.13), keeping the rotor independent.
  if (bilateral_thread()) {
    for (int candidate : {c.nut_u, c.screw_u, c.nut_phi, c.screw_phi}) {
      if (candidate > 0 && play_gradient_[candidate] != 0.0) {
        eliminated_ = candidate;
        break;
      }
    }
    if (eliminated_ < 0) eliminated_ = 0;
  }
  for (int i = 0; i < n; ++i)
    if (i != eliminated_) independent_.push_back(i);
}

Eigen::VectorXd DriveModel::consistent_velocity(double rotor_speed) const {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(coordinate_count());
  for (int i : rotating_group_) v[i] = rotor_speed;
  // The translating parts move together so that e' = grad e . v = 0.
  double per_unit = 0.0;
  for (int i : translating_group_) per_unit += play_gradient_[i];
  const double speed = per_unit != 0.0 ? -play_gradient_.dot(v) / per_unit : 0.0;
  for (int i : translating_group_) v[i] = speed;
  return v;
}

double DriveModel::nut_position(const double* q) const {
  double a = p_.nut_position;
  for (int i = 0; i < coordinate_count(); ++i) a += position_gradient_[i] * q[i];
  return a;
}

double DriveModel::screw_end_margin(double nut_position) const noexcept {
  return model::screw_end_margin(nut_position, p_.nut_length, p_.screw_length);
}

std::string DriveModel::nut_off_screw(double nut_position) const {
  return "the nut reached the end of the screw (nut position " + format_value(nut_position) +
         " m on a screw of length " + format_value(p_.screw_length) + " m, nut length " +
         format_value(p_.nut_length) + " m)";
}

double DriveModel::spring_stiffness(const Spring& s, double a, double* derivative) const {
  *derivative = 0.0;
  switch (s.law) {
    case Spring::Law::constant:
      return s.stiffness;
    case Spring::Law::screw_torsional: {
      // Only the segment between the drive (or load) end and the nut carries
      // torque: a torsionally held far end would lock the drive. (Thesis eq.
      // 4.25 adds a second segment; see README.)
      const double k = p_.screw_torsional_rigidity / a;
      *derivative = -k / a;
      return k;
    }
    case Spring::Law::screw_axial:
    default: {
      // Eq. (4.24): segments to the supports in parallel.
      double k = p_.screw_axial_rigidity / a;
      *derivative = -k / a;
      if (p_.drive == DrivenPart::screw && p_.support == ScrewSupport::both_ends) {
        const double rest = p_.screw_length - a;
        const double k_far = p_.screw_axial_rigidity / rest;
        k += k_far;
        *derivative += k_far / rest;
      }
      return k;
    }
  }
}

}  // namespace leadscrew::model
