// DriveHybrid::TrainSolver (mode_solver.hpp): the rigid drive without play
// with the train's friction stages (elements/train_friction.hpp), one degree
// of freedom phi (the driven part's angle), y = [phi, omega, a DC motor's
// states, the stages' loss integrals, energy integrals]
// (docs/physics/gear.md, "Friction stages").
//
// In slip with s = sign phi', thread sign sigma and stage sign sigma_g
// (+1: the power flows from the rotor to the driven part), the equations
//   phi'' = A Q + B F                 (the thread with the whole inertia
//                                      J = R + J_driven, Q the torque on phi
//                                      besides the rotor's inertia)
//   Q = tau_b + R phi''               (the rotor's inertia R = n^2 J_rotor
//                                      sits before the stage)
//   k tau_b = U - R phi''             (the rotor: U = n T - |n| T_c s)
// give, with D = k - A R (k - 1),
//   phi'' = (A U + k B F) / D,   Q = (U + R (k - 1) B F) / D,
// and the thread's forces C Q + E F. Without a stage k = 1: Q = U.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "driver_element.hpp"
#include "leadscrew/core/validate.hpp"
#include "mode_solver.hpp"

namespace leadscrew::model::drive {

const ElementKind& train_friction_kind();

namespace {

// Its channels (the catalog's, in this order).
enum Channel { kMotorFrictionLoss, kGearLoss };

// The train's friction stages (elements/train_friction.hpp): each stage's
// loss an integral in y and a channel of its own, among the account's losses.
void declare_train_friction(const DriveModel& model, const friction::Law& law, Declaration& d) {
  (void)law;
  const elements::TrainFriction* train = model.train_friction();
  if (!train) return;
  const std::vector<ChannelSpec>& catalog = train_friction_kind().catalog;
  if (train->motor_friction_present()) {
    d.states.push_back("motor_friction_loss");
    d.channels.push_back(catalog[kMotorFrictionLoss]);
  }
  if (train->stage) {
    d.states.push_back("gear_loss");
    d.channels.push_back(catalog[kGearLoss]);
  }
}

// Two consistent combinations whose accelerations agree to this (a sign at
// its zero: both give the same motion) are one.
constexpr double kSameMotion = 1e-9;

}  // namespace

const ElementKind& train_friction_kind() {
  static const ElementKind kind{"train_friction",
                                {{"motor_friction_loss", "J", Role::loss},
                                 {"gear_loss", "J", Role::loss}},
                                &declare_train_friction};
  return kind;
}

DriveHybrid::TrainSolver::TrainSolver(DriveHybrid& hybrid)
    : RigidDofSolver(hybrid),
      train_(*hybrid.model_.train_friction()),
      motor_friction_state_(hybrid.layout_.find_state("motor_friction_loss")),
      gear_state_(hybrid.layout_.find_state("gear_loss")),
      motor_friction_channel_(hybrid.layout_.find_channel("motor_friction_loss")),
      gear_channel_(hybrid.layout_.find_channel("gear_loss")),
      stops_(hybrid.model_.elements().end_stops()),
      phi_per_slip_(rigid_.slip_per_speed() < 0.0 ? -1 : 1) {
  // RigidDriveModes' coefficients are per unit torque on the rotor (n on phi).
  const double n = train_.ratio;
  for (int s : {1, -1})
    for (int sigma : {1, -1}) {
      const RigidModeCoefficients& c = rigid_.coefficients(FrictionMode::slip, s, sigma);
      thread_[s > 0 ? 0 : 1][sigma > 0 ? 0 : 1] = {
          c.acceleration.per_torque / n,   c.acceleration.per_force,
          c.normal_force.per_torque / n,   c.normal_force.per_force,
          c.friction_force.per_torque / n, c.friction_force.per_force};
    }
  const RigidModeCoefficients& c = rigid_.coefficients(FrictionMode::stick, 0, 1);
  stick_.normal_force = {c.normal_force.per_torque / n, c.normal_force.per_force};
  stick_.friction_force = {c.friction_force.per_torque / n, c.friction_force.per_force};
}

// The motor's torque on phi at the state set: n T(t), or a DC motor's n k_t i
// (the elements' that drive the rotor, model/element.hpp).
double DriveHybrid::TrainSolver::coordinate_torque() const {
  const double t = h_.dynamics_.time();
  double torque = h_.model_.gear().driven_torque(h_.p_.drive_torque(t));
  if (!h_.model_.elements().elements.empty()) torque += h_.dynamics_.element_drive_torque();
  return torque;
}

// The penalty end stops push the load by a force of its state alone
// (elements/end_stop.hpp): one more axial force on the train, F = the
// scene's axial load + the stops' force. In stick the state is frozen, so
// the stops' force is constant there (docs/physics/gear.md, "End stops
// through the stages").
double DriveHybrid::TrainSolver::load_force() const {
  return h_.p_.axial_force(h_.dynamics_.time()) + stop_force();
}

double DriveHybrid::TrainSolver::stop_force() const {
  double force = 0.0;
  const int load = h_.model_.load();
  for (const elements::EndStop& stop : stops_)
    force += stop.force_on_load(h_.q_[load], h_.v_[load]);
  return force;
}

// The consistent combination of the signs in a slip s (breakaway: a start
// at rest, with the stages' static coefficients, accelerating in s); count
// 0: none, > 1: several with different motions.
DriveHybrid::TrainSolver::Solution DriveHybrid::TrainSolver::slip(int s, bool breakaway,
                                                                  double torque, double force) {
  const double R = train_.rotor_inertia;
  const int d = s * phi_per_slip_;  // the sign of phi'
  const double U = torque - train_.motor_friction_bound() * d;
  Solution best;
  const int sigma_first = h_.sigma_guess_, stage_first = train_.stage ? stage_guess_ : 1;
  for (int i = 0; i < 2; ++i) {
    const int sigma = i == 0 ? sigma_first : -sigma_first;
    const ThreadSlip& c = thread_[s > 0 ? 0 : 1][sigma > 0 ? 0 : 1];
    for (int j = 0; j < (train_.stage ? 2 : 1); ++j) {
      const int stage_sign = j == 0 ? stage_first : -stage_first;
      const double k = train_.torque_ratio(stage_sign, breakaway);
      const double D = k - c.a * R * (k - 1.0);
      if (D == 0.0) continue;
      Solution x;
      x.acceleration = (c.a * U + k * c.b * force) / D;
      const double Q = train_.stage ? (U + R * (k - 1.0) * c.b * force) / D : U;
      x.stage_torque = Q - R * x.acceleration;
      x.stage_loss = (k - 1.0) * x.stage_torque;
      x.normal_force = c.normal_q * Q + c.normal_f * force;
      x.friction_force = c.friction_q * Q + c.friction_f * force;
      if (sigma * x.normal_force < 0.0) continue;
      if (train_.stage && stage_sign * d * x.stage_torque < 0.0) continue;
      if (breakaway && !(d * x.acceleration > 0.0)) continue;  // no start in s
      if (best.count > 0 &&
          std::abs(x.acceleration - best.acceleration) >
              kSameMotion * (std::abs(x.acceleration) + std::abs(best.acceleration))) {
        ++best.count;  // another motion: ambiguous
        continue;
      }
      if (best.count == 0) {
        best = x;
        if (!breakaway) {
          h_.sigma_guess_ = sigma;
          stage_guess_ = stage_sign;
        }
      }
      best.count = std::max(best.count, 1);
    }
  }
  best.torque = torque / train_.ratio;
  best.axial_force = force;
  return best;
}

// The torques Q on phi the thread holds at rest under the axial force F:
// its stick cone |T| <= mu' |N| as an interval of Q (the edges T = +-mu' N;
// a single point, 0, without F).
void DriveHybrid::TrainSolver::thread_holds(double force, double& lo, double& hi) const {
  lo = hi = 0.0;
  if (force == 0.0) return;
  const double mu = h_.stick_mu();
  const LoadCoefficients& N = stick_.normal_force;
  const LoadCoefficients& T = stick_.friction_force;
  const double plus =
      -(T.per_force - mu * N.per_force) * force / (T.per_torque - mu * N.per_torque);
  const double minus =
      -(T.per_force + mu * N.per_force) * force / (T.per_torque + mu * N.per_torque);
  lo = std::min(plus, minus);
  hi = std::max(plus, minus);
}

// The static stick test (Coulomb's static solution, exact): the train holds
// at rest iff some split of the holding torque keeps every contact in its
// set: the thread's torque tau_b in [lo, hi] (thread_holds), the stage's
// rotor-side torque x between eta_b tau_b and tau_b / eta (its static
// efficiencies), and x within |n| T_c of the motor's torque U. Over tau_b in
// [lo, hi] the stage's x fill [m_lo, m_hi] (the segments' ends are concave
// and convex in tau_b: their extremes are at lo or hi), so the margins of
// both directions are m_hi - (U - |n| T_c) and (U + |n| T_c) - m_lo.
void DriveHybrid::TrainSolver::static_margins(double& up, double& down) const {
  const double torque = coordinate_torque();
  const double force = load_force();
  double lo, hi;
  thread_holds(force, lo, hi);
  const double k_forward = train_.torque_ratio(1, true), k_backward = train_.torque_ratio(-1, true);
  double m_lo = std::numeric_limits<double>::infinity(), m_hi = -m_lo;
  for (double tau : {lo, hi}) {
    const double a = k_backward * tau, b = k_forward * tau;
    m_lo = std::min(m_lo, std::min(a, b));
    m_hi = std::max(m_hi, std::max(a, b));
  }
  const double c = train_.motor_friction_bound();
  up = m_hi - (torque - c);
  down = (torque + c) - m_lo;
}

// Stick: the thread carries as much of the motor's torque as its cone
// allows; the stage and the motor's friction hold the rest (the split
// between serial friction contacts at rest is statically indeterminate).
DriveHybrid::TrainSolver::Solution DriveHybrid::TrainSolver::stick(double torque,
                                                                   double force) const {
  double lo, hi;
  thread_holds(force, lo, hi);
  const double held = std::clamp(torque, lo, hi);
  Solution x;
  x.torque = torque / train_.ratio;
  x.axial_force = force;
  x.normal_force = stick_.normal_force(held, force);
  x.friction_force = stick_.friction_force(held, force);
  x.stage_torque = held;
  x.count = 1;
  return x;
}

DriveHybrid::TrainSolver::Solution DriveHybrid::TrainSolver::solve() {
  const double torque = coordinate_torque();
  // (axial_force: the scene's axial load alone, whose work is work_axial;
  // the stops' work is their elastic energy and loss.)
  const double axial = h_.p_.axial_force(h_.dynamics_.time());
  const double force = axial + stop_force();
  if (h_.mode_.friction != FrictionMode::slip) {
    Solution x = stick(torque, force);
    x.axial_force = axial;
    return x;
  }
  Solution x = slip(h_.mode_.slip_sign, false, torque, force);
  x.axial_force = axial;
  if (x.count == 0) h_.jam("no combination of the signs of the thread's normal force and the "
                           "gear stage's power flow is consistent" + stage_regime(false));
  if (x.count > 1) h_.jam("two combinations of the signs of the thread's normal force and the "
                          "gear stage's power flow are consistent" + stage_regime(false));
  return x;
}

// Stick where the static test admits it (with hint 0: not at a stick's
// root); otherwise the direction whose slip starts consistently.
// The stage's own Painleve regime, for a jam's report: its backward
// combination's effective inertia eta_b + n^2 J_rotor a_d (a_d = A / (1 - A R),
// the driven side's response to a torque on it) is not positive for some
// slip state: a rotor too light behind a self-locking stage (eta_b <= 0).
std::string DriveHybrid::TrainSolver::stage_regime(bool breakaway) const {
  if (!train_.stage) return "";
  const double R = train_.rotor_inertia, eta_b = train_.torque_ratio(-1, breakaway);
  double margin = std::numeric_limits<double>::infinity();
  for (const auto& by_sigma : thread_)
    for (const ThreadSlip& c : by_sigma) margin = std::min(margin, eta_b + c.a * R / (1.0 - c.a * R));
  return "; the gear stage's Painleve margin eta_b + n^2 J_rotor a_driven = " +
         format_value(margin) + (margin <= 0.0 ? " (<= 0: a rotor too light behind a "
                                                 "self-locking stage)"
                                               : " (> 0)");
}

int DriveHybrid::TrainSolver::breakaway(int hint) {
  if (hint == 0 && stick_margin() >= 0.0) return 0;
  const double torque = coordinate_torque();
  const double force = load_force();
  bool starts[2];
  for (int s : {1, -1}) {
    const Solution x = slip(s, true, torque, force);
    if (x.count > 1)
      h_.jam("two combinations of the signs of the thread's normal force and the gear stage's "
             "power flow start a slip at rest where the train cannot stick" + stage_regime(true));
    starts[s > 0 ? 0 : 1] = x.count == 1;
  }
  if (starts[0] && starts[1])
    h_.jam("a slip starts consistently in both directions at rest" + stage_regime(true));
  if (starts[0]) return 1;
  if (starts[1]) return -1;
  // Neither start is consistent at the static test's edge (its round-off):
  // the direction the loads leave it in.
  return hint != 0 ? hint : exit_direction();
}

double DriveHybrid::TrainSolver::stick_margin() {
  double up, down;
  static_margins(up, down);
  return std::min(up, down);
}

int DriveHybrid::TrainSolver::exit_direction() {
  double up, down;
  static_margins(up, down);
  return (up <= down ? 1 : -1) * phi_per_slip_;  // (the margins' directions are phi's)
}

double DriveHybrid::TrainSolver::stage_torque() { return solve().stage_torque; }

ThreadForces DriveHybrid::TrainSolver::forces(double t, const double* y) {
  (void)t;
  (void)y;
  const Solution x = solve();
  return {x.normal_force, x.friction_force, 0.0};
}

void DriveHybrid::TrainSolver::rhs(double t, const double* y, double* ydot) {
  h_.set(t, y);
  const Solution x = solve();
  const bool slipping = h_.mode_.friction == FrictionMode::slip;
  const double omega = y[1];
  ydot[0] = omega;
  ydot[1] = slipping ? x.acceleration : 0.0;
  const StateLayout& layout = h_.layout_;
  double* energy = ydot + layout.energy_offset();
  energy[kWorkDrive] = h_.model_.gear().driven_torque(x.torque) * omega;
  energy[kWorkAxial] = x.axial_force * rigid_.load_per_angle() * omega;
  energy[kFrictionLoss] =
      slipping ? -x.friction_force * rigid_.slip_per_speed() * omega : 0.0;
  // The penalty stops' loss (the dynamics' damping power at the state set:
  // theirs alone on the rigid drive); their elastic energy is the output's.
  energy[kDampingLoss] = stops_.empty() ? 0.0 : h_.dynamics_.damping_power();
  energy[kContactLoss] = 0.0;
  if (motor_friction_state_ >= 0)
    ydot[motor_friction_state_] = slipping ? train_.motor_friction_bound() * std::abs(omega) : 0.0;
  if (gear_state_ >= 0) ydot[gear_state_] = slipping ? x.stage_loss * omega : 0.0;
  for (const std::unique_ptr<Element>& element : h_.elements_) element->rates(t, y, ydot, energy);
}

ChannelState DriveHybrid::TrainSolver::output(double t, const double* y, ContactForces& forces) {
  h_.set(t, y);
  const Solution x = solve();
  forces.normal = x.normal_force;
  forces.friction = x.friction_force;
  forces.motor_torque = x.torque;
  ChannelState state = channel_state(h_.dynamics_);
  if (forces.stick) state.slip_velocity = 0.0;
  if (motor_friction_state_ >= 0)
    state.values[motor_friction_channel_] = y[motor_friction_state_];
  if (gear_state_ >= 0) state.values[gear_channel_] = y[gear_state_];
  for (const std::unique_ptr<Element>& element : h_.elements_)
    element->output(t, y, forces, state);
  return state;
}

}  // namespace leadscrew::model::drive
