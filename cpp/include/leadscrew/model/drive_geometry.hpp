// A drive's quantities derived from its geometry and material, and the rules
// its inputs obey: the one place of both (the Python Scene converts its
// sections into a DriveGeometry, reports derive()'s values as
// Scene.derived() and feeds them into DriveParameters).
//
// Screw: a solid cylinder of radius r_S and length L; nut: a hollow cylinder
// of outer radius r_o on it (inner radius r_S) and length l_M. With
// G = E / (2 (1 + nu)):
//   masses          m_S = rho_S pi r_S^2 L,  m_M = rho_M pi (r_o^2 - r_S^2) l_M
//   polar inertias  J_S = m_S r_S^2 / 2,     J_M = m_M (r_o^2 + r_S^2) / 2
//   screw rigidity  E_S A_S (axial), G_S I_pS (torsion); its stiffness follows
//                   the nut's position a (eq. 4.24: E A / a + E A / (L - a))
//   nut stiffness   E_M A_M / l_M (axial, eq. 4.17), G_M I_pM / l_M (torsion,
//                   eq. 4.18 with the polar moment I_p = pi (r_o^4 - r_S^4) / 2)
// Each override replaces its quantity. With backlash, the flank contact's
// stiffness, damping and penetration of full damping (defaults below).
// derive() never throws: a quantity beyond the float range comes out as inf,
// 0 or NaN, and first_out_of_range() names it (the Scene then names the
// inputs that made it so).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "leadscrew/model/drive.hpp"

namespace leadscrew::model {

// The scene's inputs the derivation takes, named <section>_<key> after the
// scene's key paths (SI).
struct DriveGeometry {
  double thread_pitch = 1e-3;
  double thread_mean_diameter = 20e-3;
  int thread_starts = 1;
  double thread_flank_angle = 0.0;  // included angle beta [rad]
  double friction_mu = 0.3;
  DrivenPart drive = DrivenPart::screw;

  double screw_radius = 10e-3;
  double screw_length = 0.5;
  double screw_density = 7850.0;
  double screw_youngs_modulus = 210e9;
  double screw_poisson = 0.3;
  double nut_outer_radius = 12e-3;
  double nut_length = 20e-3;
  double nut_density = 1400.0;
  double nut_youngs_modulus = 2e9;
  double nut_poisson = 0.3;
  double load_mass = 1.0;

  // The backlash section: contact none where the scene has none.
  BacklashContact backlash_contact = BacklashContact::none;
  double backlash_axial = 0.0;
  double backlash_exponent = 1.5;
  std::optional<double> backlash_stiffness;
  std::optional<double> backlash_damping;
  std::optional<double> backlash_penetration;

  // The overrides section: each replaces its derived quantity.
  std::optional<double> overrides_screw_mass;
  std::optional<double> overrides_screw_inertia;
  std::optional<double> overrides_nut_mass;
  std::optional<double> overrides_nut_inertia;
  std::optional<double> overrides_screw_axial_stiffness;
  std::optional<double> overrides_screw_torsional_stiffness;
  std::optional<double> overrides_nut_axial_stiffness;
  std::optional<double> overrides_nut_torsional_stiffness;
};

// Every number a DriveGeometry gives the model.
struct DerivedQuantities {
  // The thread's: checked, not part of Scene.derived().
  double tan_lead_angle = 0.0;  // lead / (pi d_m)
  double effective_mu = 0.0;    // mu' = mu / cos(beta / 2)

  double screw_mass = 0.0;                  // kg
  double screw_inertia = 0.0;               // kg m^2
  double nut_mass = 0.0;                    // kg
  double nut_inertia = 0.0;                 // kg m^2
  double screw_axial_rigidity = 0.0;        // E A [N]
  double screw_torsional_rigidity = 0.0;    // G I_p [N m^2]
  double nut_axial_stiffness = 0.0;         // N/m
  double nut_torsional_stiffness = 0.0;     // N m/rad
  double screw_axial_stiffness = 0.0;       // N/m; 0: follows the nut (eq. 4.24)
  double screw_torsional_stiffness = 0.0;   // N m/rad; 0: follows the nut

  // With backlash only (has_contact).
  bool has_contact = false;
  double contact_stiffness = 0.0;    // N/m^exponent ('bistop'), N/m otherwise
  double contact_damping = 0.0;      // N s/m
  double contact_penetration = 0.0;  // m

  // Scene.derived(): (key, value) in the order of derived_quantities(),
  // without the thread's, the contact's only with backlash.
  std::vector<std::pair<std::string, double>> derived() const;
  // Every quantity with a range: the thread's first, then derived()'s.
  std::vector<std::pair<std::string, double>> quantities() const;

  // Feeds the masses, inertias, rigidities, stiffnesses and (with backlash)
  // the contact's values into the model's parameters.
  void apply_to(DriveParameters& parameters) const;
};

DerivedQuantities derive(const DriveGeometry& geometry);

// A derived quantity and the range it must lie in: its key, its text for
// messages (with the inputs it comes from), unit, range (low, open or not;
// high, closed) and the scene's key that replaces it (empty: none).
struct DerivedQuantity {
  const char* key;
  double DerivedQuantities::*member;
  const char* text;
  const char* unit;
  double low;
  bool low_open;
  double high;
  const char* override_key;
  // What the range says a value must be, or "" where `value` is in it:
  // "a finite number > 0", "a finite number >= 0" or "in [low, high]".
  std::string problem(double value) const;
};

// Every quantity, in the order of DerivedQuantities::quantities().
const std::vector<DerivedQuantity>& derived_quantities();
// The quantity named `key`, or nullptr.
const DerivedQuantity* find_derived_quantity(const std::string& key);
// The first quantity of `values` ((key, value) pairs of quantities(); keys
// not among them are skipped) out of its range, or nullptr.
const DerivedQuantity* first_out_of_range(
    const std::vector<std::pair<std::string, double>>& values);

// The rule that the whole nut stays on the screw, for either drive: its
// centre a (the point where the thread force enters the screw, eq. 4.24) in
// (l_M / 2, L - l_M / 2). screw_end_margin is how far the nut's nearer end
// is inside the screw's nearer end (> 0 on the screw; a run ends at 0).
double screw_end_margin(double nut_position, double nut_length, double screw_length) noexcept;
// Throws InvalidArgument naming nut.position, the range and why, where the
// margin is not > 0; `explain` adds what a is measured from for `drive`
// and the lengths (the scene's message).
void require_nut_on_screw(DrivenPart drive, double nut_position, double nut_length,
                          double screw_length, bool explain);

// The highest natural angular frequency of a part on its own spring
// [rad/s]: a part stiffer for its mass than this is rigid to any drive, and
// beyond what the integrators resolve (runs ended in a wrong message or NaN).
constexpr double kMaxNaturalFrequency = 1e12;
// What is wrong with a spring of `model`: its part's natural angular
// frequency sqrt(k / m) (m the part's mass or polar inertia, k the spring's
// stiffness at the start) not finite or above kMaxNaturalFrequency; "" where
// every spring is fine (none in the rigid concept).
std::string spring_frequency_problem(const DriveModel& model);

// The rigid drive's two dynamic jamming (Painleve) inequalities
// (docs/physics/rigid_drive.md section 7) for a friction factor kappa (mu'
// for exact Coulomb, the regularized law's factor otherwise), rotating
// inertia J and translating mass m:
//   m r^2 tan a (kappa - tan a) >= J (1 + kappa tan a)  a self-locking drive
//                                                       jams when driven
//   J cot a (kappa - cot a) >= m r^2 (1 + kappa cot a)  a drive no torque
//                                                       turns jams back-driven
struct JammingMargins {
  double lhs1, rhs1, lhs2, rhs2;  // kg m^2
  bool jams1, jams2;
  // The translating mass at which the first holds (inf where kappa <= tan
  // a) and the rotating inertia at which the second holds (inf where
  // kappa <= cot a).
  double mass1, inertia2;
};
JammingMargins rigid_jamming_margins(const Thread& thread, double kappa, double inertia,
                                     double mass);

// The scene's key paths of the model's enumerations and their names
// (drive.hpp's lists; backlash.contact without "none", which is the absent
// section): the Python Scene's choices.
std::vector<std::pair<std::string, std::vector<std::string>>> scene_choices();

}  // namespace leadscrew::model
