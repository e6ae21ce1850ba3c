// Forces and mode-wise accelerations of a DriveModel (Pinocchio's Data: the
// preallocated workspace of the algorithms on an immutable model).
//
// In every mode the accelerations follow from
//   M a = f + B lambda,    C a = r
// with f the spring, damper and load forces, and the multipliers lambda of
// the active constraints: the thread normal force (bilateral thread or a
// closed flank: row W_N, column W_N - sigma kappa W_T, where the friction
// force lambda_T = -kappa |lambda_N| = -kappa sigma lambda_N rides on the
// normal force), stick (row and column W_T), and a speed-controlled rotor
// (row and column e_rotor). M is diagonal, so a Schur complement of at most
// 3 x 3 gives lambda: no allocation, exact up to round-off.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "leadscrew/friction/flank_lcp.hpp"
#include "leadscrew/lcp/lcp.hpp"
#include "leadscrew/lcp/workspace.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/element.hpp"

namespace leadscrew::model {

constexpr int kMaxCoordinates = 6;
constexpr int kMaxConstraints = 4;  // normal, stick, a speed-controlled rotor, a held load
using CoordinateVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxCoordinates, 1>;

enum class ThreadContact { bilateral, open, closed, penalty };
// The flank's friction in a mode: none; stick or slip of a set-valued law;
// a velocity law's, an acceleration law's (eq. 3.15) or LuGre's bristles'
// friction factor (friction/law.hpp).
enum class FrictionMode {
  none,
  stick,
  slip,
  regularized_velocity,
  regularized_acceleration,
  bristle
};

struct ModeSpec {
  ThreadContact contact = ThreadContact::bilateral;
  int sigma = 1;  // sign of the normal force: assumed (bilateral) or the flank's (closed)
  FrictionMode friction = FrictionMode::none;
  int slip_sign = 0;              // FrictionMode::slip: sign of the slip velocity
  double given_tangential = 0.0;  // an extra tangential force (builds the friction LCP)
  // A lift-off nut in stick with half B toward slip s's edge state: its
  // normal force side S / cos(a) + share (N_B^s(S) - side S / cos(a)) along
  // W_N, its friction share T_B^s in the stick force (s = +-1; 0: its
  // spring's, side S / cos(a) W_N). DriveHybrid::half_b_edge_share.
  int half_b_edge = 0;
  double half_b_share = 1.0;
  // A closed exact end stop holds this coordinate (the load's) at rest: a
  // row of its own, its multiplier the stop's force (ModeSolution::
  // stop_force); -1: none (docs/physics/end_stops.md, "The rigid drive").
  int held_load = -1;
  // The rotor's friction contact (the train's stages with a torque or DC
  // motor on a drive TrainSolver does not take): a row a_w phi_r'' + a_q Q
  // = r on the rotor's coordinate, Q its torque along -e_rotor (the motor's
  // friction and the stage's loss; moreau_contacts::RotorBalance::row at
  // the rate level, docs/physics/gear.md). a_q = 0: the row fixes the
  // rotor's acceleration (stick, eta_b = 0), else Q is eliminated: the
  // rotor's inverse mass a_q / (a_q M_r - a_w) and force f_r - r / a_q.
  struct RotorRow {
    bool active = false;
    double a_w = 0.0, a_q = 0.0, r = 0.0;
    // Whether the row fixes the acceleration of the rotor's coordinate (of
    // inertia `mass`): a_q = 0, or a_q so small beside a_w that eliminating
    // Q would divide by it (a stage's eta_b = 2e-311 back-driven gave r /
    // a_q = inf: a NaN right-hand side; as eta_b = 0 to 1e-15).
    bool fixes(double mass) const noexcept {
      return active && std::abs(a_q) * mass <= 1e-15 * std::abs(a_w);
    }
  } rotor;
};

struct ModeSolution {
  bool regular = false;  // false: the constraint system is singular
  double normal_force = 0.0;
  double friction_force = 0.0;
  double motor_torque = 0.0;
  double slip_acceleration = 0.0;
  CoordinateVector acceleration;
  // Eq. (3.15) on the thread without play in the Painleve regime: how many
  // flank forces are consistent (DriveDynamics::solve); 1 everywhere else.
  int consistent_solutions = 1;
  // A preloaded nut (elements/preloaded_nut.hpp): its preload half's normal
  // force in the mode (part of normal_force, the net), 0 without one.
  double preload_normal = 0.0;
  // Its friction force where the half takes the law's coefficient kappa'
  // (DriveDynamics::preload_at_kappa; part of friction_force), else 0.
  double preload_friction = 0.0;
  // A closed exact stop's force on the load along +u (ModeSpec::held_load).
  double stop_force = 0.0;
  // The rotor's friction torque Q along -e_rotor (ModeSpec::rotor).
  double rotor_friction = 0.0;
  // The normal force of the half that carries the load (normal_force
  // without one): its sign is the bilateral thread's flank side.
  double loaded_normal() const noexcept { return normal_force - preload_normal; }
};

// A bracket [low, high] of a sign change narrowed by Illinois: regula falsi
// whose stale end has its value halved. Shared by first_negative and the
// eq. (3.15) slip-acceleration solve (DriveDynamics::solve).
struct IllinoisBracket {
  double low, high, f_low, f_high;
  int side = 0;  // the end moved last: -1 low, +1 high

  // The regula-falsi point, or the midpoint where it falls outside.
  double next() const {
    const double x = (low * f_high - high * f_low) / (f_high - f_low);
    return x > low && x < high ? x : 0.5 * (low + high);
  }
  // Moves the end on x's side (`low_side`: f(x) has f(low)'s sign).
  void update(double x, double fx, bool low_side) {
    if (low_side) {
      low = x;
      f_low = fx;
      if (side == -1) f_high *= 0.5;
      side = -1;
    } else {
      high = x;
      f_high = fx;
      if (side == 1) f_low *= 0.5;
      side = 1;
    }
  }
};

// Illinois on [low, high], where f(low) >= 0 > f(high): narrows the bracket
// to `width` or 200 iterations and returns its upper end, the first point
// known to be negative.
template <class Function>
double first_negative(Function f, double low, double high, double width) {
  IllinoisBracket bracket{low, high, f(low), f(high)};
  for (int iteration = 0; iteration < 200 && bracket.high - bracket.low > width; ++iteration) {
    const double x = bracket.next();
    const double fx = f(x);
    bracket.update(x, fx, fx >= 0.0);
  }
  return bracket.high;
}

// The flank LCP (friction::solve_flank_lcp) of the drive, solved at unit scale.
// The problem is homogeneous in (c, beta): scaling both by k scales the
// friction force, the normal force and the slip acceleration by k and leaves
// stick or slip unchanged. Lemke's pivot and tie tolerances are not
// scale-invariant, though: at the start of a flexible drive, whose relaxed
// springs carry forces of 1e-24 N just after t = 0, it reported no solution
// (ray termination) where one exists. So the problem is solved with (c, beta)
// scaled by a power of two to a force scale of 1 (exact in floating point) and
// the result scaled back.
friction::FlankLcpResult solve_flank_lcp_scaled(double c, double d, double alpha, double beta,
                                                double mu, int sigma, lcp::Workspace& workspace,
                                                const lcp::Options& options);

class DriveDynamics {
 public:
  // `law`: the friction law that runs (default: the model's; a set-valued
  // law's regularization where an ODE integrator runs it); it outlives this.
  explicit DriveDynamics(const DriveModel& model, const friction::Law* law = nullptr);

  const friction::Law& law() const noexcept { return *law_; }
  // law().plain_coulomb(), kept (the law is fixed; the test is eight
  // virtual calls, and the root functions and the slip's friction
  // coefficient asked it at every evaluation: callgrind, the rigid drive).
  bool plain_coulomb() const noexcept { return plain_coulomb_; }
  // LuGre's bristle deflection z at the state last set (its own state).
  void set_bristle(double z) noexcept { bristle_ = z; }
  double bristle() const noexcept { return bristle_; }
  // LuGre's bristles on the flank's 2-D cone (a transverse slip w): the
  // deflection is the vector (z, z_w) on the slip (gamma, w), relaxing at
  // the slip speed s = |(gamma, w)| (the friction block's
  // cone_bristle_block.cpp; docs/physics/transverse_slip.md):
  //   z' = gamma - sigma0 s z / mu(s),   z_w' = w - sigma0 s z_w / mu(s).
  // Without a transverse slip bristle_rate() is the law's 1-D rate.
  void set_transverse_bristle(double z) noexcept { transverse_bristle_ = z; }
  double transverse_bristle() const noexcept { return transverse_bristle_; }
  double bristle_rate() const;
  double transverse_bristle_rate() const {
    return planar_bristle_rate(transverse_slip_, transverse_bristle_);
  }
  // The power the bristles store per unit flank normal force [m/s],
  // sigma0 z . z' (the law's storing_power without a transverse slip).
  double bristle_storing_power() const;
  // The bristles' energy |N|' sigma0 z^2 / 2 at a flank normal force N.
  double bristle_energy(double normal_force) const noexcept {
    return 0.5 * std::abs(normal_force) * model_.flank_factor() * law_->bristle_stiffness() *
           bristle_ * bristle_;
  }

  // The model's elements (model/element.hpp, DriveElements::elements):
  // their states' slots in the run's y (each element's first state and
  // their count, {-1, 0}: none; set once per run by the driver), their states from y, set
  // before set_state (kept through set_state calls without it: a current
  // is continuous across impacts), their modes in the run, and each one's
  // state as it sees it at the state last set. Their forces are part of
  // forces(); a motor's torque on the rotor (Element::drives_rotor) part of
  // applied_torque() too.
  void set_element_slots(const std::vector<std::pair<int, int>>& slots);
  void set_element_states(const double* y) noexcept {
    for (std::size_t k = 0; k < element_slots_.size(); ++k)
      for (int i = 0; i < element_slots_[k].count; ++i)
        element_states_[element_slots_[k].offset + i] = y[element_slots_[k].first + i];
  }
  ElementMode& element_mode(std::size_t k) noexcept { return element_modes_[k]; }
  const ElementMode& element_mode(std::size_t k) const noexcept { return element_modes_[k]; }
  ElementState element_state(std::size_t k) const noexcept {
    return {t_, q_.data(), v_.data(), element_states_.data() + element_slots_[k].offset};
  }
  // The elements' torque on the rotor that drives it (a DC motor's k_t i).
  double element_drive_torque() const noexcept { return element_drive_torque_; }
  // Their energy terms at the state last set (Element::energy_terms): at a
  // run's start their stored energy (a DC motor's L i^2 / 2 of a current
  // that starts in equilibrium), which the energy account's residual takes
  // as its start (write_drive_channels' stored0).
  double element_energy_terms() const;

  const DriveModel& model() const noexcept { return model_; }

  // Full coordinates and velocities at time t. Throws SimulationError when
  // the nut leaves the screw.
  void set_state(double t, const CoordinateVector& q, const CoordinateVector& v);

  // Accelerations and forces in a mode at the state last set.
  ModeSolution solve(const ModeSpec& spec);
  // The same mode with the generalized forces replaced by `forces` (the state's
  // springs, dampers and loads ignored). For a mode whose friction factor is
  // constant the solution is linear in them: with unit loads this gives the
  // coefficients of RigidDriveModes.
  ModeSolution solve_with_forces(const ModeSpec& spec, const CoordinateVector& forces);

  // Smallest change of v (in the kinetic metric) that makes the slip velocity
  // zero while keeping the other active velocity constraints.
  void project_zero_slip(const ModeSpec& spec, CoordinateVector& v);

  // The constraints a mode holds on the acceleration level (the thread's
  // normal constraint: without play, or a closed flank; a stick's tangential
  // one), on the position and velocity level: the thread's play at `play`,
  // the slip position W_T . q at `slip_position` (where the stick began),
  // zero normal and slip velocity, a speed-controlled rotor kept.
  struct HeldContact {
    bool normal = false;
    double play = 0.0;           // e on the normal constraint [m]
    bool stick = false;
    double slip_position = 0.0;  // W_T . q [m]
    bool rotor = false;          // the rotor's stuck friction contact holds phi_r' = 0
  };
  // The least change of q and of v (each in the kinetic metric) that puts
  // them onto the held constraints (docs/physics/drive_models.md, "Held
  // constraints between events"). Returns false where the rows are dependent
  // (nothing changed).
  bool project_held(const HeldContact& held, CoordinateVector& q, CoordinateVector& v) const;

  // Velocity jump of an impact on a flank (sign sigma) with restitution:
  // Newton's law on the normal velocity, the rotor held if speed-controlled,
  // stick or slip of the impulses decided by the flank LCP. `sticks` is the
  // LCP's verdict (zero post-impact slip), taken from its basis: a sliding
  // impact has |P_T| = mu' |P_N| exactly, so comparing the impulses would let
  // round-off decide. `rotor` is the speed-controlled motor's impulse (its
  // work at the held speed is rotor times that speed). Returns false if no
  // consistent frictional impact exists. `rotor_contact`: the rotor's
  // friction contact's row on the impulse level (ModeSpec::RotorRow, a_w w+
  // + a_q Q = r with Q its impulse along -e_rotor: a_q = 0 fixes w+, else
  // Q is eliminated into the rotor's inverse mass); `rotor_friction` its Q.
  struct Impulses {
    double normal = 0.0, tangential = 0.0, rotor = 0.0, rotor_friction = 0.0;
    bool sticks = false;
  };
  bool impact(int sigma, double restitution, CoordinateVector& v, Impulses& impulses,
              lcp::Workspace& workspace, const lcp::Options& options,
              const ModeSpec::RotorRow& rotor_contact = {});

  double time() const noexcept { return t_; }
  const CoordinateVector& q() const noexcept { return q_; }
  const CoordinateVector& v() const noexcept { return v_; }
  double play() const noexcept { return play_; }             // e [m]
  double play_rate() const noexcept { return play_rate_; }   // e' [m/s]
  double slip_velocity() const noexcept { return slip_; }    // gamma_T [m/s]
  // The round-off of slip_velocity() at the state set: a slip velocity this
  // small has no reliable sign (64 ulp of the sum |W_T,i v_i| it cancels).
  double slip_noise() const noexcept { return slip_noise_; }
  double penalty_normal_force() const noexcept { return penalty_.normal_force; }
  // A preloaded nut's lift-off spring force S at the state last set [N]
  // (elements/preloaded_nut.hpp; 0 without one).
  double preload_spring_force() const noexcept { return preload_spring_; }
  double elastic_energy() const noexcept { return elastic_; }
  // Potential of the penalty flanks at the state last set: evaluated on request
  // (outputs and the energy account), not in every set_state of the right-hand side.
  double contact_energy() const noexcept;
  double damping_power() const noexcept { return damping_power_; }
  double contact_loss_power() const noexcept { return penalty_.loss_power; }
  double applied_torque() const noexcept { return applied_torque_; }
  // Spring, damper and load forces at the state last set (no thread forces).
  const CoordinateVector& forces() const noexcept { return forces_; }
  double axial_force() const noexcept { return axial_force_; }
  double kinetic_energy() const;
  double friction_factor(const ModeSpec& spec, double slip_acceleration) const;
  // A preloaded nut's half B at the law's coefficient (drive_dynamics_preload.cpp).
  bool preload_at_kappa(const ModeSpec& spec) const noexcept;
  double half_b_coefficient(const elements::PreloadedNut& nut, const ModeSpec& spec) const;
  double preloaded_acceleration_law(const ModeSpec& spec, bool multiplier,
                                    const std::function<double(double)>& slip_acceleration_at)
      const;

  // The flank's 2-D friction cone (a transverse slip w, issue 34;
  // docs/physics/transverse_slip.md): transverse() says the run has one
  // (loads.transverse_slip_velocity), transverse_slip() is w at the state
  // last set (set_state takes w(t)). In slip the friction is
  // (mu'(s) |N| + viscous s) (gamma, w) / s, s = |(gamma, w)|, mu'(s) the
  // law's coefficient at the slip speed (Stribeck's curve; exact Coulomb's
  // mu'): its helix coefficient mu'(s) gamma / s rides on the normal force
  // as a velocity law's kappa (FrictionMode::regularized_velocity), smooth in
  // gamma wherever w != 0; the viscous term is the mode's own.
  bool transverse() const noexcept { return transverse_ != nullptr; }
  double transverse_slip() const noexcept { return transverse_slip_; }
  double cone_mu(double speed) const { return law_->slip_mu(speed) * model_.flank_factor(); }
  // mu gamma / |(gamma, w)| at a coefficient mu (0 at the apex).
  static double cone_coefficient(double slip, double w, double mu) noexcept {
    const double speed = std::hypot(slip, w);
    return speed > 0.0 ? mu * (slip / speed) : 0.0;
  }
  // The transverse friction along +w (the friction channel's sign: against
  // the slip) at a flank normal force N and helix slip gamma [N].
  // With LuGre's bristles -(|N|' (sigma0 z_w + sigma1 z_w') + viscous w),
  // z_w' at the state's slip.
  // A penalty flank that does not touch carries none (its viscous term
  // neither: the helix's, mode_forces).
  double transverse_friction(double normal_force, double slip) const {
    if (model_.thread_pair().penalty() && penalty_.normal_force == 0.0) return 0.0;
    if (law_->resolution() == friction::Resolution::bristle)
      return -((law_->bristle_stiffness() * transverse_bristle_ +
                law_->bristle_damping() * transverse_bristle_rate()) *
                   model_.flank_factor() * std::abs(normal_force) +
               law_->viscous() * transverse_slip_);
    const double speed = std::hypot(slip, transverse_slip_);
    if (!(speed > 0.0)) return 0.0;
    return -(cone_mu(speed) * std::abs(normal_force) + law_->viscous() * speed) *
           (transverse_slip_ / speed);
  }

  // Painleve (dynamic jamming) report of a slip mode: the effective Delassus
  // terms G_NN, G_NT and whether mu' |G_NT| >= G_NN. With a regularized law
  // (regularized_factor >= 0: the friction factor kappa = (2/pi) mu' |atan(.)|
  // in effect) the condition that applies is kappa |G_NT| >= G_NN instead.
  std::string jamming_report(double regularized_factor = -1.0) const;
  // The Schur complement of the thread without play for a normal-force sign
  // sigma and friction factor kappa, G_NN - sigma kappa G_NT: the
  // mass-matrix-like denominator of the normal force (rigid drive: Delta / (m J)
  // times cos^2 a, docs/physics/rigid_drive.md section 7). A consistent branch
  // with it at zero is the onset of dynamic jamming.
  double thread_denominator(int sigma, double kappa) const noexcept {
    return delassus_nn_ - sigma * kappa * delassus_nt_;
  }
  double delassus_normal() const noexcept { return delassus_nn_; }
  // -G_NT / G_NN: the change of the flank normal force per unit friction
  // force with the masses alone (the speed-controlled rotor held).
  double coupling() const noexcept { return -delassus_nt_ / delassus_nn_; }
  // mu' |G_NT| >= G_NN: only then can both signs of the flank normal force be
  // consistent in slip. M and the thread directions are constant, so this is
  // a property of the model, computed once.
  bool painleve_possible() const noexcept { return painleve_possible_; }
  // True if the flank's constraint and the speed-controlled rotor fix every
  // velocity (the rigid drive's two coordinates): the slip is then
  // prescribed by the motor, and friction no longer changes it
  // (friction::solve_flank_prescribed_slip decides stick or slip). A
  // property of the model, computed once.
  bool slip_prescribed() const noexcept { return slip_prescribed_; }
  // True if the flank's constraint and the rotor's stuck friction contact
  // (its row fixing the rotor's speed: the train's stages with a torque or
  // DC motor) fix every velocity (the rigid concept with a closed flank):
  // the slip is prescribed as by a speed-controlled rotor, and in stick the
  // thread's friction force leaves the rotor's contact the least |Q|
  // (Moreau-Jean's "stuck together", docs/physics/gear_rotor_impacts.md).
  bool rotor_fixes_slip() const noexcept { return rotor_fixes_slip_; }
  // The flank's stick or slip at zero slip velocity where the slip is
  // prescribed (slip_prescribed), from the mode `base` without friction at
  // the state set: its slip acceleration decides, and in stick the friction
  // force leaves the motor the least torque. sigma: the closed flank's sign,
  // or 0 for the thread without play (either sign).
  friction::FlankLcpResult prescribed_slip_decision(const ModeSpec& base, int sigma);

 private:
  // impact()'s parts: the flank's line (the post-impact slip c + d P_T, the
  // normal impulse beta + alpha P_T; where the slip is prescribed, the held
  // row's impulse held0 + held1 P_T and the slip's round-off noise), its
  // friction impulse, and the rotor's inverse mass with its contact's row
  // eliminated (false: none finite).
  struct ImpactLine {
    double c = 0.0, d = 0.0, alpha = 0.0, beta = 0.0;
    bool prescribed = false;
    double noise = 0.0, held0 = 0.0, held1 = 0.0;
  };
  friction::FlankLcpResult impact_friction(const ImpactLine& line, double slip_before, int sigma,
                                           lcp::Workspace& workspace,
                                           const lcp::Options& options) const;
  bool eliminated_rotor_inverse_mass(const ModeSpec::RotorRow& rotor_contact,
                                     CoordinateVector& inverse_mass) const;
  // solve's parts (drive_dynamics_solve.cpp). A mode's rows and given forces
  // besides the multipliers: the law's viscous term and a preloaded nut's
  // half B (its coefficient half_b_kappa moves with eq. (3.15)).
  struct ModeForces {
    const elements::PreloadedNut* nut = nullptr;
    bool normal_multiplier = false, stick = false;
    bool kappa_half = false, preload_half = false, smooth_half = false;
    bool lift_off_half = false, lift_off_slip = false;
    double viscous = 0.0;
    double half_b_kappa = 0.0, lift_off_normal = 0.0, lift_off_friction = 0.0;
    // The rotor's friction contact (ModeSpec::rotor): a row of its own
    // where it fixes the rotor's acceleration, else eliminated into the
    // rotor's inverse mass and force; singular: the stage's Painleve case.
    bool rotor_fixed = false, rotor_eliminated = false, rotor_singular = false;
    // The inverse mass with the rotor's eliminated (set with
    // rotor_eliminated only: every other mode solves with inverse_mass_,
    // no copy of it per solve).
    CoordinateVector eliminated_inverse_mass;
  };
  ModeForces mode_forces(const ModeSpec& spec) const;
  void set_lift_off_forces(const ModeSpec& spec, ModeForces& m) const;
  CoordinateVector mode_applied_forces(const ModeSpec& spec, const ModeForces& m, double kappa,
                                       double given_tangential, double& normal_force) const;
  void evaluate_mode(const ModeSpec& spec, const ModeForces& m, double kappa,
                     double given_tangential, ModeSolution& out);
  void set_thread_forces(const ModeSpec& spec, const ModeForces& m, double kappa,
                         double given_tangential, double normal_force, double stick_force,
                         ModeSolution& out) const;
  ModeSolution solve_acceleration_by_newton(const ModeSpec& spec, const ModeForces& m);
  ModeSolution solve_acceleration_law(const ModeSpec& spec);
  // LuGre's friction where a closed exact stop holds the rigid drive
  // (drive_dynamics_solve.cpp); not regular where no sign of N agrees.
  ModeSolution solve_held_bristles(const ModeSpec& spec, const ModeForces& m);
  // The elements' forces at the state set: element_forces_ (their sum but
  // a motor's on the rotor) and element_drive_torque_.
  void add_element_forces(int rotor);

  const DriveModel& model_;
  const friction::Law* law_;
  bool plain_coulomb_;
  // The law's slip coefficient is mu at every slip speed (Coulomb, with or
  // without mu_static): a preloaded nut's half B in slip at the element's
  // mu' (PreloadedNut::normal); otherwise at the law's kappa' (normal_at).
  bool one_slip_mu_;
  double bristle_ = 0.0, transverse_bristle_ = 0.0;
  // A planar bristle component's rate at the state's slip speed |(gamma, w)|.
  double planar_bristle_rate(double slip_component, double z) const {
    const double speed = std::hypot(slip_, transverse_slip_);
    return slip_component - law_->bristle_stiffness() * speed * z / law_->slip_mu(speed);
  }
  const Excitation* transverse_ = nullptr;  // w(t) (nullptr: no transverse slip)
  double transverse_slip_ = 0.0;
  // The model's elements' data: their states (a copy of y's), slots, modes.
  struct ElementSlot {
    int first = 0, count = 0, offset = 0;  // in y; how many; in element_states_
  };
  std::array<double, kMaxElementStates> element_states_{};
  std::vector<ElementSlot> element_slots_;
  std::vector<ElementMode> element_modes_;
  CoordinateVector element_forces_;
  double element_drive_torque_ = 0.0;
  double t_ = 0.0;
  CoordinateVector q_, v_, forces_, inverse_mass_;
  double play_ = 0.0, play_rate_ = 0.0, slip_ = 0.0, slip_noise_ = 0.0;
  double elastic_ = 0.0;
  elements::ThreadPair::Penalty penalty_;  // the penalty flanks at the state set
  double preload_spring_ = 0.0;            // a lift-off nut's spring force S
  double damping_power_ = 0.0;
  double applied_torque_ = 0.0, axial_force_ = 0.0, rotor_acceleration_ = 0.0;
  double delassus_nn_ = 0.0, delassus_nt_ = 0.0;
  bool painleve_possible_ = false;
  bool slip_prescribed_ = false;
  bool rotor_fixes_slip_ = false;
};

}  // namespace leadscrew::model
