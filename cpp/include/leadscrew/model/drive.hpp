// Lead-screw drive models of thesis chapter 4, assembled from elements.
//
// Bodies and coordinates (displacements from the reference configuration:
// springs relaxed, the nut at initial.play_position in the play; the start
// of a relaxed run, drive_equilibrium.hpp for the other):
//   rotor          phi_rotor (always; prescribed when the motor is speed-controlled)
//   rotating part  the part the motor turns (screw for drive = screw, nut for
//                  drive = nut): rigid -> turns with the rotor, axially fixed;
//                  flexible -> own contact body (u, phi) tied to the rotor by
//                  a torsion spring and to the ground by an axial spring
//   translating part  the other part: rigid -> moves with the load, does not
//                  turn; flexible -> own contact body (u, phi) tied to the load
//                  by an axial spring and to the ground by a torsion spring
//   load           u_load
// concept rigid: both parts rigid (thesis 4.1.1); flexible_nut: the nut
// flexible (4.1.2); flexible: screw and nut flexible (4.1.3).
//
// Thread pair (unrolled at the mean radius, thesis Fig. 4.2): with
// du = u_screw - u_nut and dphi = phi_screw - phi_nut the axial play
// coordinate is e = du - h p dphi (h = +1 right hand, p = lead / 2 pi,
// eq. 4.1). The flank normal n = (-h sin a, cos a) and tangent
// t = (h cos a, sin a) in (arc, axial) coordinates give
//   normal velocity   g_N' = cos(a) e'                      (W_N = cos a grad e)
//   slip velocity     gamma_T = sin(a) du' + h r_m cos(a) dphi'
// A force lambda_N n + lambda_T t acts on the screw, its opposite on the nut.
// Without backlash e = 0 is a kinematic constraint (one coordinate is
// eliminated); with backlash |e| <= c_a / 2 (unilateral flanks or a penalty).
// Friction: |lambda_T| <= mu' |lambda_N|, mu' = mu / cos(beta / 2).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "leadscrew/excitation/excitation.hpp"
#include "leadscrew/friction/law.hpp"
#include "leadscrew/thread/thread.hpp"
#include "leadscrew/model/element_section.hpp"
#include "leadscrew/model/elements/drive_elements.hpp"

namespace leadscrew::model {

enum class Concept { rigid, flexible_nut, flexible };
enum class DrivenPart { screw, nut };
enum class ScrewSupport { both_ends, drive_end };
enum class BacklashContact { none, exact, bistop, cubic };
// The state at t = 0 (initial.state): `relaxed`, every spring relaxed, the
// nut at initial.play_position and every body turning with the thread at
// initial.rotor_speed; `equilibrium`, at rest in static equilibrium under the
// loads at t = 0 (drive_equilibrium.hpp).
enum class InitialState { relaxed, equilibrium };
// The gear stage between the rotor and the driven part (gear.type;
// elements/gear.hpp): none, an ideal kinematic ratio, or a stage with
// friction (elements/train_friction.hpp): Modelica's LossyGear with constant
// efficiencies, or a worm pair with exact Coulomb friction.
enum class GearType { none, ideal, lossy, worm };

// The smallest axial play a thread may have besides none [m].
constexpr double kSmallestClearance = 1e-12;

// Every number resolved (the Python Scene derives masses, inertias,
// stiffnesses and damping from geometry and material, or takes overrides).
struct DriveParameters {
  Concept concept = Concept::rigid;
  DrivenPart drive = DrivenPart::screw;
  Thread thread{1e-3, 20e-3};
  // The flank's friction law (friction::law_types()), its coefficient mu,
  // its gain k_v where it takes one (the arctan laws', Stribeck's
  // regularization), and its other parameters by key (mu_static, sigma0, ...).
  std::string friction = "coulomb";
  double mu = 0.3;
  double k_v = 1e4;
  friction::LawValues friction_values;

  BacklashContact backlash = BacklashContact::none;
  double clearance = 0.0;  // total axial play c_a [m]
  double restitution = 0.0;
  double contact_stiffness = 0.0;
  double contact_exponent = 1.5;
  double contact_damping = 0.0;
  double contact_penetration = 1e-7;

  double rotor_inertia = 1e-5;
  double load_mass = 1.0;
  double screw_mass = 0.0;
  double screw_inertia = 0.0;
  double nut_mass = 0.0;
  double nut_inertia = 0.0;

  // Screw stiffness from the segment between its supports and the nut
  // (eq. 4.24): axial rigidity E A, torsional rigidity G I_p, length, and the
  // nut's initial distance from the drive (or load) end.
  double screw_axial_rigidity = 0.0;
  double screw_torsional_rigidity = 0.0;
  double screw_length = 0.5;
  double nut_position = 0.1;
  // The nut's length: its centre a keeps the whole nut on the screw while
  // nut_length / 2 < a < screw_length - nut_length / 2 (screw_end_margin).
  double nut_length = 0.02;
  ScrewSupport support = ScrewSupport::both_ends;
  double screw_axial_stiffness = 0.0;      // > 0: constant override
  double screw_torsional_stiffness = 0.0;  // > 0: constant override
  double nut_axial_stiffness = 0.0;
  double nut_torsional_stiffness = 0.0;
  // Damping of each spring; < 0: c = 2 zeta sqrt(k m) with zeta =
  // damping_ratio, k at the initial nut position and m the larger mass or
  // inertia of the two bodies the spring connects.
  double damping_ratio = 0.05;
  double screw_axial_damping = -1.0;
  double screw_torsional_damping = -1.0;
  double nut_axial_damping = -1.0;
  double nut_torsional_damping = -1.0;

  Excitation drive_torque;
  bool speed_controlled = false;
  Excitation drive_speed;
  Excitation axial_force;
  // The housing's vibration (elements/base_excitation.hpp): its axial
  // acceleration [m/s^2] and its angular acceleration about the axis
  // [rad/s^2]; a constant 0 (the default) is none.
  Excitation base_acceleration;
  Excitation base_angular_acceleration;
  // The nut's transverse slip on the flank, across the helix (issue 34;
  // docs/physics/transverse_slip.md) [m/s]: the flank's friction is the
  // isotropic cone on the slip (gamma, w); a constant 0 (the default) is
  // none, and the 1-D thread runs unchanged.
  Excitation transverse_slip_velocity;
  // An element that drives the rotor instead of drive_torque or
  // drive_speed (a DC motor) has a section of its own in `sections`, its
  // input (the voltage) there (element_section.hpp: RotorDrive).
  // The motor's own Coulomb friction on the rotor (motor.friction_torque;
  // elements/train_friction.hpp) [N m]; 0: none. Torque-controlled or DC
  // motor on the rigid drive without play.
  double motor_friction_torque = 0.0;
  // A gear stage between the rotor and the driven part (elements/gear.hpp;
  // scene section `gear`): the rotor turns gear_ratio times per turn of the
  // driven part (< 0: a reversing stage). Without one (GearType::none) the
  // ratio must be 1.
  GearType gear = GearType::none;
  double gear_ratio = 1.0;
  // gear.type = "lossy": the efficiencies eta (rotor -> driven part) in
  // (0, 1] and eta_b (driven part -> rotor) <= 1 (<= 0: self-locking).
  double gear_efficiency = 1.0;
  double gear_efficiency_backdrive = 1.0;
  // gear.type = "worm": its lead angle gamma [rad] in (0, pi/2), its
  // coefficients mu >= 0 and mu_static (< 0: mu), its included flank
  // angle beta_w [rad] in [0, pi) (mu' = mu / cos(beta_w / 2), as the
  // thread's; 40 degrees: the standard 20 degree pressure angle).
  double gear_lead_angle = 0.0;
  double gear_mu = 0.0;
  double gear_mu_static = -1.0;
  double gear_flank_angle = 0.6981317007977318;  // 40 degrees
  // A preloaded split nut (elements/preloaded_nut.hpp; scene keys
  // nut.preload, nut.preload_stiffness): the halves' spring force P [N]
  // (0: none) and its rate [N/m] (0: not given).
  double nut_preload = 0.0;
  double nut_preload_stiffness = 0.0;

  // The elements' own sections by name (element_section.hpp: the end stops,
  // the DC motor, ...): present or not, and their values and inputs as given. Their builders read
  // them once, when the model is built.
  ElementSections sections;

  double rotor_angle = 0.0;
  double rotor_speed = 0.0;
  double play_position = 0.0;
  InitialState initial_state = InitialState::relaxed;
};

// Every field of DriveParameters that is one number, by name, in declaration
// order: the Python binding's attributes and DriveBatch's overrides both
// list them from here.
struct ScalarField {
  const char* name;
  double DriveParameters::*member;
};
const std::vector<ScalarField>& scalar_fields();

// A linear spring-damper between two coordinates (or one and the ground),
// optionally with the screw's position-dependent stiffness: an element
// (elements/spring_damper.hpp).
using Spring = elements::SpringDamper;

// The assembled model: immutable after construction (Pinocchio's Model), a
// list of elements over its coordinates (elements/drive_elements.hpp) built
// from the parameters by elements::build_drive_elements.
class DriveModel {
 public:
  explicit DriveModel(DriveParameters parameters);

  const DriveParameters& parameters() const noexcept { return p_; }
  const elements::DriveElements& elements() const noexcept { return e_; }
  const elements::ThreadPair& thread_pair() const noexcept { return *e_.thread; }
  const elements::Motor& motor() const noexcept { return e_.motor; }
  const elements::AxialLoad& axial_load() const noexcept { return e_.load; }
  // The gear stage between the rotor and the rotor's coordinate (ratio 1: none).
  const elements::Gear& gear() const noexcept { return e_.motor.gear; }
  // The train's friction stages besides the thread (nullptr: none): the
  // motor's Coulomb friction, a lossy or worm stage (train_friction.hpp).
  const elements::TrainFriction* train_friction() const noexcept {
    return e_.train_friction ? &*e_.train_friction : nullptr;
  }
  // The preloaded split nut on the thread (nullptr: none, the plain thread).
  const elements::PreloadedNut* preloaded_nut() const noexcept {
    return e_.preloaded_nut ? &*e_.preloaded_nut : nullptr;
  }
  int coordinate_count() const noexcept { return static_cast<int>(mass_.size()); }
  const std::vector<std::string>& coordinate_names() const noexcept { return e_.coordinates; }
  // The diagonal mass matrix: every body's inertia on its coordinate.
  const Eigen::VectorXd& mass() const noexcept { return mass_; }
  const std::vector<Spring>& springs() const noexcept { return e_.springs(); }
  // True if a force element needs the nut on the screw (the flexible screw's springs).
  bool springs_on_screw() const noexcept { return springs_on_screw_; }
  int rotor() const noexcept { return e_.motor.rotor; }
  int load() const noexcept { return e_.load.coordinate; }
  // Thread kinematics as gradients over the coordinates.
  const Eigen::VectorXd& play_gradient() const noexcept { return thread_pair().play_gradient(); }  // grad e
  const Eigen::VectorXd& normal_direction() const noexcept { return thread_pair().normal(); }  // W_N
  const Eigen::VectorXd& tangent_direction() const noexcept { return thread_pair().tangent(); }  // W_T
  const Eigen::VectorXd& nut_position_gradient() const noexcept {
    return thread_pair().nut_position_gradient();
  }
  // The flank's friction law, and its coefficients on the thread's normal
  // force: mu' = mu / cos(beta / 2) (the flank angle scales the flank's own
  // normal force), the static one, and the largest the law reaches.
  const friction::Law& law() const noexcept { return thread_pair().law(); }
  double flank_factor() const noexcept { return thread_pair().flank_factor(); }
  double effective_mu() const noexcept { return thread_pair().effective_mu(); }
  double effective_mu_static() const noexcept { return law().mu_static() * flank_factor(); }
  double effective_max_mu() const noexcept { return law().max_mu() * flank_factor(); }
  bool bilateral_thread() const noexcept { return thread_pair().bilateral(); }
  // Coordinate eliminated by the bilateral thread constraint (-1 with backlash).
  int eliminated() const noexcept { return thread_pair().eliminated(); }
  // Independent coordinates integrated by the ODE solvers.
  const std::vector<int>& independent() const noexcept { return independent_; }

  // Velocities of every coordinate when the rotor turns at rotor_speed and
  // the thread play does not change (springs relaxed, rigid-body motion;
  // behind a gear the rotor's coordinate turns at rotor_speed / n).
  Eigen::VectorXd consistent_velocity(double rotor_speed) const;

  // Stiffness of a spring at nut position a, and its derivative d k / d a.
  double spring_stiffness(const Spring& s, double nut_position, double* derivative) const {
    return s.stiffness_at(nut_position, derivative);
  }
  // How far the nut's nearer end is inside the screw's nearer end
  // [m] with its centre at nut_position: > 0 while the whole nut is on the
  // screw (the start must be; a run ends where it reaches 0).
  // (model::screw_end_margin, drive_geometry.hpp: the rule's one place.)
  double screw_end_margin(double nut_position) const noexcept;
  // What an error says where the nut leaves the screw (the end of a run, or a
  // trial state off the model's domain), and its hint.
  std::string nut_off_screw(double nut_position) const;
  static constexpr const char* kNutOffScrewHint =
      "shorten t_end, change the loads or place the nut elsewhere";
  double nut_position(const double* q) const { return thread_pair().nut_position(q); }

 private:
  void place_stops_at_equilibrium();

  DriveParameters p_;
  elements::DriveElements e_;
  Eigen::VectorXd mass_;
  bool springs_on_screw_ = false;
  std::vector<int> independent_;
};

// The names of the enumerations in scene files, each list in the order of
// its values (the Python Scene's choices come from here); parse_* raise
// InvalidArgument naming the key and the allowed names.
const std::vector<std::string>& concept_names();
const std::vector<std::string>& drive_names();
const std::vector<std::string>& support_names();
const std::vector<std::string>& backlash_contact_names();  // "none" first
const std::vector<std::string>& initial_state_names();
const std::vector<std::string>& gear_type_names();  // "none" first
std::string concept_name(Concept c);
std::string drive_name(DrivenPart d);
std::string support_name(ScrewSupport s);
std::string backlash_contact_name(BacklashContact b);
std::string initial_state_name(InitialState s);
std::string gear_type_name(GearType g);
Concept parse_concept(const std::string& name);
DrivenPart parse_drive(const std::string& name);
ScrewSupport parse_support(const std::string& name);
BacklashContact parse_backlash_contact(const std::string& name);  // "none" allowed
InitialState parse_initial_state(const std::string& name);
GearType parse_gear_type(const std::string& name);  // "none" allowed

// The scene gives the nut a transverse slip on the flank
// (loads.transverse_slip_velocity other than the constant 0): the flank's
// 2-D friction cone (docs/physics/transverse_slip.md).
bool has_transverse_slip(const DriveParameters& p);

}  // namespace leadscrew::model
