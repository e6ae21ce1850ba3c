#include "leadscrew/model/drive_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::model {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
// The lead angles the models resolve: 1e-6 <= tan(alpha) <= 1e6.
constexpr double kSmallestTanLeadAngle = 1e-6;
constexpr double kLargestTanLeadAngle = 1e6;

double or_else(const std::optional<double>& given, double derived) {
  return given ? *given : derived;
}

// sqrt(x), NaN (not an error) where x is negative: a quantity the checks
// then refuse, naming the inputs that made it so.
double root(double x) {
  return x >= 0.0 ? std::sqrt(x) : std::numeric_limits<double>::quiet_NaN();
}

std::string format_g(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace

// The arithmetic's order is the order of its terms in the comments above
// (with floating-point contraction off, CMakeLists.txt, the values are the
// same to the last bit on every platform).
DerivedQuantities derive(const DriveGeometry& g) {
  DerivedQuantities d;
  // Thread (thesis eq. 3.5-3.8): tan(alpha) = lead / (pi d_m), mu' = mu / cos(beta / 2).
  d.tan_lead_angle = g.thread_starts * g.thread_pitch / (kPi * g.thread_mean_diameter);
  d.effective_mu = g.friction_mu / std::cos(0.5 * g.thread_flank_angle);

  // Shear moduli G = E / (2 (1 + nu)); cross-sections: the screw's solid
  // circle, the nut's annulus on it; polar moments I_p.
  const double r_s = g.screw_radius, r_o = g.nut_outer_radius;
  const double g_s = g.screw_youngs_modulus / (2.0 * (1.0 + g.screw_poisson));
  const double g_n = g.nut_youngs_modulus / (2.0 * (1.0 + g.nut_poisson));
  const double r_s2 = r_s * r_s, r_o2 = r_o * r_o;
  const double area_s = kPi * r_s2;
  const double polar_s = kPi * r_s2 * r_s2 / 2.0;
  const double area_n = kPi * (r_o2 - r_s2);
  const double polar_n = kPi * (r_o2 * r_o2 - r_s2 * r_s2) / 2.0;

  // Masses (density * volume) and polar inertias of the cylinders.
  d.screw_mass = or_else(g.overrides_screw_mass, g.screw_density * area_s * g.screw_length);
  d.nut_mass = or_else(g.overrides_nut_mass, g.nut_density * area_n * g.nut_length);
  d.screw_inertia = or_else(g.overrides_screw_inertia, 0.5 * d.screw_mass * r_s2);
  d.nut_inertia = or_else(g.overrides_nut_inertia, 0.5 * d.nut_mass * (r_o2 + r_s2));

  // The screw's rigidities; its stiffness follows the nut's position (eq.
  // 4.24, DriveModel::spring_stiffness) unless an override fixes it (0: none).
  d.screw_axial_rigidity = g.screw_youngs_modulus * area_s;
  d.screw_torsional_rigidity = g_s * polar_s;
  d.screw_axial_stiffness = or_else(g.overrides_screw_axial_stiffness, 0.0);
  d.screw_torsional_stiffness = or_else(g.overrides_screw_torsional_stiffness, 0.0);
  // The nut as a bar of length l_M: E A / l (eq. 4.17), G I_p / l (eq. 4.18).
  d.nut_axial_stiffness =
      or_else(g.overrides_nut_axial_stiffness, g.nut_youngs_modulus * area_n / g.nut_length);
  d.nut_torsional_stiffness =
      or_else(g.overrides_nut_torsional_stiffness, g_n * polar_n / g.nut_length);

  if (g.backlash_contact != BacklashContact::none) {
    d.has_contact = true;
    // Penetration of full damping d_0: c_a / 100, at least 1e-7 m.
    const double depth =
        or_else(g.backlash_penetration, std::max(g.backlash_axial / 100.0, 1e-7));
    // The contact stiffness: the nut's axial one, k_nut; a 'bistop' one is
    // in N/m^exponent, matched to the nut's spring force k_nut d_0 at d_0.
    const double exponent =
        g.backlash_contact == BacklashContact::bistop ? g.backlash_exponent : 1.0;
    const double k =
        or_else(g.backlash_stiffness, d.nut_axial_stiffness * std::pow(depth, 1.0 - exponent));
    // Critical damping of the contact's linear-equivalent stiffness at d_0
    // with the translating mass (the load and the part that carries it).
    const double translating =
        g.load_mass + (g.drive == DrivenPart::screw ? d.nut_mass : d.screw_mass);
    const double equivalent = k * std::pow(depth, exponent - 1.0);
    d.contact_stiffness = k;
    d.contact_damping = or_else(g.backlash_damping, 2.0 * root(equivalent * translating));
    d.contact_penetration = depth;
  }
  return d;
}

const std::vector<DerivedQuantity>& derived_quantities() {
  using Q = DerivedQuantities;
  static const std::vector<DerivedQuantity> quantities = {
      {"tan_lead_angle", &Q::tan_lead_angle,
       "the tangent of the lead angle (thread.starts * thread.pitch / (pi "
       "thread.mean_diameter))",
       "", kSmallestTanLeadAngle, false, kLargestTanLeadAngle, ""},
      {"effective_mu", &Q::effective_mu,
       "the effective friction coefficient (friction.mu / cos(thread.flank_angle / 2))", "", 0.0,
       false, kInf, ""},
      {"screw_mass", &Q::screw_mass,
       "the screw's mass (screw.density * pi screw.radius^2 * screw.length)", "kg", 0.0, true,
       kInf, "overrides.screw_mass"},
      {"screw_inertia", &Q::screw_inertia,
       "the screw's polar inertia (screw mass * screw.radius^2 / 2)", "kg*m^2", 0.0, true, kInf,
       "overrides.screw_inertia"},
      {"nut_mass", &Q::nut_mass,
       "the nut's mass (nut.density * pi (nut.outer_radius^2 - screw.radius^2) * nut.length)",
       "kg", 0.0, true, kInf, "overrides.nut_mass"},
      {"nut_inertia", &Q::nut_inertia,
       "the nut's polar inertia (nut mass * (nut.outer_radius^2 + screw.radius^2) / 2)",
       "kg*m^2", 0.0, true, kInf, "overrides.nut_inertia"},
      {"screw_axial_rigidity", &Q::screw_axial_rigidity,
       "the screw's axial rigidity (screw.youngs_modulus * pi screw.radius^2)", "N", 0.0, true,
       kInf, "overrides.screw_axial_stiffness"},
      {"screw_torsional_rigidity", &Q::screw_torsional_rigidity,
       "the screw's torsional rigidity (G I_p = screw.youngs_modulus / (2 (1 + "
       "screw.poisson)) * pi screw.radius^4 / 2)",
       "N*m^2", 0.0, true, kInf, "overrides.screw_torsional_stiffness"},
      {"nut_axial_stiffness", &Q::nut_axial_stiffness,
       "the nut's axial stiffness (nut.youngs_modulus * pi (nut.outer_radius^2 - "
       "screw.radius^2) / nut.length)",
       "N/m", 0.0, true, kInf, "overrides.nut_axial_stiffness"},
      {"nut_torsional_stiffness", &Q::nut_torsional_stiffness,
       "the nut's torsional stiffness (G I_p / nut.length)", "N*m/rad", 0.0, true, kInf,
       "overrides.nut_torsional_stiffness"},
      {"screw_axial_stiffness", &Q::screw_axial_stiffness,
       "overrides.screw_axial_stiffness (0: it follows the nut's position)", "N/m", 0.0, false,
       kInf, ""},
      {"screw_torsional_stiffness", &Q::screw_torsional_stiffness,
       "overrides.screw_torsional_stiffness (0: it follows the nut's position)", "N*m/rad", 0.0,
       false, kInf, ""},
      {"contact_stiffness", &Q::contact_stiffness,
       "the flank contact stiffness (default: the nut's axial stiffness at "
       "backlash.penetration)",
       "N/m^exponent", 0.0, true, kInf, "backlash.stiffness"},
      {"contact_damping", &Q::contact_damping,
       "the flank contact damping (default: critical, of the contact stiffness and the "
       "translating mass)",
       "N*s/m", 0.0, false, kInf, "backlash.damping"},
      {"contact_penetration", &Q::contact_penetration,
       "the penetration of full contact damping (backlash.penetration, default "
       "backlash.axial / 100)",
       "m", 0.0, true, kInf, "backlash.penetration"},
  };
  return quantities;
}

namespace {
// The first two quantities are the thread's, the last three the contact's.
constexpr std::size_t kThreadQuantities = 2;
constexpr std::size_t kContactQuantities = 3;

std::vector<std::pair<std::string, double>> values_of(const DerivedQuantities& d,
                                                      std::size_t first) {
  const std::vector<DerivedQuantity>& all = derived_quantities();
  const std::size_t end = all.size() - (d.has_contact ? 0 : kContactQuantities);
  std::vector<std::pair<std::string, double>> out;
  out.reserve(end - first);
  for (std::size_t i = first; i < end; ++i) out.emplace_back(all[i].key, d.*(all[i].member));
  return out;
}
}  // namespace

std::vector<std::pair<std::string, double>> DerivedQuantities::derived() const {
  return values_of(*this, kThreadQuantities);
}

std::vector<std::pair<std::string, double>> DerivedQuantities::quantities() const {
  return values_of(*this, 0);
}

void DerivedQuantities::apply_to(DriveParameters& p) const {
  p.screw_mass = screw_mass;
  p.screw_inertia = screw_inertia;
  p.nut_mass = nut_mass;
  p.nut_inertia = nut_inertia;
  p.screw_axial_rigidity = screw_axial_rigidity;
  p.screw_torsional_rigidity = screw_torsional_rigidity;
  p.nut_axial_stiffness = nut_axial_stiffness;
  p.nut_torsional_stiffness = nut_torsional_stiffness;
  p.screw_axial_stiffness = screw_axial_stiffness;
  p.screw_torsional_stiffness = screw_torsional_stiffness;
  if (has_contact) {
    p.contact_stiffness = contact_stiffness;
    p.contact_damping = contact_damping;
    p.contact_penetration = contact_penetration;
  }
}

std::string DerivedQuantity::problem(double value) const {
  const bool above = low_open ? value > low : value >= low;
  if (std::isfinite(value) && above && value <= high) return "";
  if (high < kInf) return "in [" + format_g(low) + ", " + format_g(high) + "]";
  return std::string("a finite number ") + (low_open ? ">" : ">=") + " " + format_g(low);
}

const DerivedQuantity* find_derived_quantity(const std::string& key) {
  for (const DerivedQuantity& q : derived_quantities())
    if (key == q.key) return &q;
  return nullptr;
}

const DerivedQuantity* first_out_of_range(
    const std::vector<std::pair<std::string, double>>& values) {
  for (const DerivedQuantity& q : derived_quantities()) {
    for (const auto& [key, value] : values) {
      if (key == q.key && !q.problem(value).empty()) return &q;
    }
  }
  return nullptr;
}

double screw_end_margin(double nut_position, double nut_length, double screw_length) noexcept {
  const double half = 0.5 * nut_length;
  return std::min(nut_position - half, screw_length - half - nut_position);
}

void require_nut_on_screw(DrivenPart drive, double nut_position, double nut_length,
                          double screw_length, bool explain) {
  if (screw_end_margin(nut_position, nut_length, screw_length) > 0.0) return;
  const double half = 0.5 * nut_length;
  std::string why = ": the whole nut on the screw";
  if (explain) {
    const bool screw = drive == DrivenPart::screw;
    why = std::string(" (the distance of the nut's centre from the screw's ") +
          (screw ? "drive end" : "load end") + " for drive = '" + drive_name(drive) +
          "': the whole nut on the screw; nut.length = " + format_value(nut_length) +
          ", screw.length = " + format_value(screw_length) + ")";
  }
  throw InvalidArgument("nut.position = " + format_value(nut_position) +
                        " is invalid: must be in (nut.length / 2, screw.length - nut.length / "
                        "2) = (" + format_value(half) + ", " +
                        format_value(screw_length - half) + ")" + why);
}

std::string spring_frequency_problem(const DriveModel& model) {
  const DriveParameters& p = model.parameters();
  for (const Spring& s : model.springs()) {
    // "<part> axial" or "<part> torsion" (DriveModel's names).
    const std::string part = s.name.substr(0, s.name.find(' '));
    const std::string kind = s.name.substr(s.name.find(' ') + 1);
    const bool axial = kind == "axial";
    const bool screw = part == "screw";
    const double carried = axial ? (screw ? p.screw_mass : p.nut_mass)
                                 : (screw ? p.screw_inertia : p.nut_inertia);
    double derivative = 0.0;
    const double omega = root(model.spring_stiffness(s, p.nut_position, &derivative) / carried);
    if (!(omega <= kMaxNaturalFrequency)) {
      const std::string inertia = axial ? "mass" : "inertia";
      return "the " + part + "'s " + kind + " natural frequency sqrt(stiffness / " + part + " " +
             inertia + ") comes to " + format_value(omega) + " rad/s: must be at most " +
             format_g(kMaxNaturalFrequency) + " rad/s (a part this stiff for its " + inertia +
             " is rigid to any drive; a concept that takes it as rigid models it)";
    }
  }
  return "";
}

JammingMargins rigid_jamming_margins(const Thread& thread, double kappa, double inertia,
                                     double mass) {
  const double tan_a = std::tan(thread.lead_angle());
  const double cot_a = 1.0 / tan_a;
  const double r = thread.mean_radius();
  const double J = inertia, m = mass;
  JammingMargins out;
  out.lhs1 = m * r * r * tan_a * (kappa - tan_a);
  out.rhs1 = J * (1.0 + kappa * tan_a);
  out.lhs2 = J * cot_a * (kappa - cot_a);
  out.rhs2 = m * r * r * (1.0 + kappa * cot_a);
  out.jams1 = out.lhs1 >= out.rhs1;
  out.jams2 = out.lhs2 >= out.rhs2;
  out.mass1 = kappa > tan_a ? J * (1.0 + kappa * tan_a) / (r * r * tan_a * (kappa - tan_a)) : kInf;
  out.inertia2 =
      kappa > cot_a ? m * r * r * (1.0 + kappa * cot_a) / (cot_a * (kappa - cot_a)) : kInf;
  return out;
}

std::vector<std::pair<std::string, std::vector<std::string>>> scene_choices() {
  const std::vector<std::string>& contacts = backlash_contact_names();
  return {{"concept", concept_names()},
          {"drive", drive_names()},
          {"screw.support", support_names()},
          {"backlash.contact", {contacts.begin() + 1, contacts.end()}},
          {"initial.state", initial_state_names()}};
}

}  // namespace leadscrew::model
