// DriveHybrid::ConstrainedSolver (mode_solver.hpp): any drive model; y
// expanded by StateLayout, the current mode solved by DriveDynamics'
// constrained solve (DriveHybrid::solve_current), LuGre's bristle states and
// their stored energy (their declaration, lugre_bristles_kind), the
// elements' with events rates and output values (driver_element.hpp).
#include <algorithm>
#include <cmath>

#include "driver_element.hpp"
#include "mode_solver.hpp"

namespace leadscrew::model::drive {

const ElementKind& lugre_bristles_kind();

namespace {

// LuGre's bristles (the friction law's, friction/laws/lugre.cpp): the
// deflection z and its stored energy, states of their own; the deflection a
// channel (their energy is the elastic channel's).
// On a transverse slip's 2-D cone (transverse_slip.cpp) the deflection is
// a vector: its transverse component a state and a channel besides.
void declare_bristles(const DriveModel& model, const friction::Law& law, Declaration& d) {
  d.states = law.state_names();  // (the law's own: LuGre's bristles)
  if (d.states.empty()) return;
  const std::vector<ChannelSpec>& catalog = lugre_bristles_kind().catalog;
  d.channels = {catalog[0]};
  if (!has_transverse_slip(model.parameters())) return;
  d.states.push_back("bristle_share_transverse");
  d.channels.push_back(catalog[1]);
}

}  // namespace

const ElementKind& lugre_bristles_kind() {
  static const ElementKind kind{
      "lugre_bristles",
      {{"bristle_deflection", "m", Role::none}, {"bristle_deflection_transverse", "m", Role::none}},
      &declare_bristles};
  return kind;
}

DriveHybrid::ConstrainedSolver::ConstrainedSolver(DriveHybrid& hybrid)
    : ModeSolver(hybrid),
      bristle_state_(hybrid.layout_.find_state("bristle_share")),
      bristle_channel_(hybrid.layout_.find_channel("bristle_deflection")),
      speed_train_(hybrid.model_.motor().speed_controlled ? hybrid.model_.train_friction()
                                                          : nullptr),
      motor_friction_state_(hybrid.layout_.find_state("motor_friction_loss")),
      gear_state_(hybrid.layout_.find_state("gear_loss")),
      motor_friction_channel_(hybrid.layout_.find_channel("motor_friction_loss")),
      gear_channel_(hybrid.layout_.find_channel("gear_loss")) {}

// The motor's torque on the rotor's coordinate in the solution s (at the
// state set): the speed constraint's multiplier Lambda, and behind a
// prescribed speed with the train's stages the frictions ahead of the
// stage's output besides: the rotor's reflected inertia R takes R w' of
// Lambda, the stage passes tau_b = Lambda - R w' on (docs/physics/gear.md,
// "A prescribed rotor speed"; Moreau-Jean's step the same per impulse,
// moreau_speed_train.cpp).
double DriveHybrid::ConstrainedSolver::speed_train_torque(const ModeSolution& s) const {
  if (!speed_train_) return s.motor_torque;
  const int r = h_.model_.rotor();
  const double transmitted = s.motor_torque - speed_train_->rotor_inertia * s.acceleration[r];
  return s.motor_torque + speed_train_->friction_torque_at_speed(transmitted, h_.v_[r]);
}

double DriveHybrid::ConstrainedSolver::slip_velocity(const double* y) const {
  (void)y;
  return h_.dynamics_.slip_velocity();
}

ThreadForces DriveHybrid::ConstrainedSolver::forces(double t, const double* y) {
  (void)t;
  (void)y;
  const ModeSolution s = h_.solve_current();
  return {s.normal_force, s.friction_force, s.preload_normal};
}

void DriveHybrid::ConstrainedSolver::bristle_rates(const ModeSolution& s, double* ydot,
                                                    double* energy) const {
  const DriveDynamics& dynamics = h_.dynamics_;
  const DriveModel& model = h_.model_;
  const int bristle = bristle_state_;
  // LuGre's bristles: z' of the law. Of the friction's power, the part
  // |N|' sigma0 z z' is stored in the bristles, not lost; it is
  // integrated (the state after z) rather than taken as |N|' sigma0 z^2
  // / 2, which would miss the work of a changing normal force on a
  // deflected bristle. What remains, |N|' (sigma0^2 |gamma| z^2 / mu(|gamma|)
  // + sigma1 z' gamma) + viscous gamma^2, is the loss (sigma1 z' gamma can be
  // negative: LuGre is passive only for small sigma1).
  // (A transverse slip: the vector's components relax at |(gamma, w)|,
  // both store; the transverse one's state follows the energy's.)
  const double rate = dynamics.bristle_rate();
  // (A preloaded nut: both halves' flanks carry bristles of the one
  // deflection z, both slipping at gamma_T: |N_A| + |N_B| in place of |N|.)
  const double flank_normal =
      model.preloaded_nut()
          ? std::abs(s.normal_force - s.preload_normal) + std::abs(s.preload_normal)
          : std::abs(s.normal_force);
  const double stored = flank_normal * model.flank_factor() * dynamics.bristle_storing_power();
  ydot[bristle] = rate / h_.bristle_range_;
  ydot[bristle + 1] = stored;
  if (dynamics.transverse())
    ydot[bristle + 2] = dynamics.transverse_bristle_rate() / h_.bristle_range_;
  energy[kFrictionLoss] -= stored;
}

void DriveHybrid::ConstrainedSolver::rhs(double t, const double* y, double* ydot) {
  h_.set(t, y);
  const ModeSolution s = h_.solve_current();
  const StateLayout& layout = h_.layout_;
  const DriveDynamics& dynamics = h_.dynamics_;
  const DriveModel& model = h_.model_;
  const CoordinateVector& v = h_.v_;
  const int np = static_cast<int>(layout.positions().size());
  for (int k = 0; k < np; ++k) ydot[k] = v[layout.positions()[k]];
  for (std::size_t k = 0; k < layout.velocities().size(); ++k)
    ydot[np + k] = s.acceleration[layout.velocities()[k]];
  double* energy = ydot + layout.energy_offset();
  energy[kWorkDrive] = model.motor().power(speed_train_torque(s), v);
  energy[kWorkAxial] = model.axial_load().power(dynamics.axial_force(), v);
  energy[kFrictionLoss] =
      h_.mode_.friction == FrictionMode::stick ? 0.0 : -s.friction_force * dynamics.slip_velocity();
  if (bristle_state_ >= 0) bristle_rates(s, ydot, energy);
  // A lift-off nut's half B slipping on its own flank: its friction works on
  // its slip gamma_T - sin(a) e', not on gamma_T (preloaded_nut.hpp).
  if (const elements::PreloadedNut* nut = model.preloaded_nut();
      nut && nut->lift_off && h_.mode_.contact == ThreadContact::penalty) {
    if (dynamics.preload_at_kappa(h_.spec(1)))  // (a smooth law's, Stribeck's: the solve's)
      energy[kFrictionLoss] += nut->sin_lead * s.preload_friction * dynamics.play_rate();
    else if (const int edge = h_.mode_.friction == FrictionMode::slip ? h_.mode_.slip_sign
                                                                      : h_.mode_.half_b_edge)
      // (in slip, and in stick with half B toward its slip's edge: its
      // share of T_B^s on its own slip -sin(a) e')
      energy[kFrictionLoss] +=
          (h_.mode_.friction == FrictionMode::slip ? 1.0 : h_.spec(1).half_b_share) *
          nut->sin_lead * nut->split_friction(edge, dynamics.preload_spring_force()) *
          dynamics.play_rate();
  }
  energy[kDampingLoss] = dynamics.damping_power();
  energy[kContactLoss] = dynamics.contact_loss_power();
  if (speed_train_) {  // the stages' losses (each >= 0), the motor's work beside
    const int r = model.rotor();
    const double transmitted = s.motor_torque - speed_train_->rotor_inertia * s.acceleration[r];
    if (motor_friction_state_ >= 0)
      ydot[motor_friction_state_] = speed_train_->motor_friction_bound() * std::abs(v[r]);
    if (gear_state_ >= 0) ydot[gear_state_] = speed_train_->stage_loss(transmitted * v[r]);
  }
  if (const elements::TrainFriction* train = h_.rotor_train_) {
    // The rotor's friction contact (hybrid_rotor_contact.cpp): in slip the
    // motor's friction B |w| and the stage's (k - 1) tau_b w (>= 0: flow s
    // tau_b >= 0), Q w in all; in stick nothing moves.
    const int r = model.rotor();
    const moreau_contacts::RotorMode& mode = h_.rotor_mode_;
    const bool slip = mode.slip != 0;
    if (motor_friction_state_ >= 0)
      ydot[motor_friction_state_] = slip ? train->motor_friction_bound() * std::abs(v[r]) : 0.0;
    if (gear_state_ >= 0)
      ydot[gear_state_] = slip ? (train->torque_ratio(mode.flow, mode.breakaway) - 1.0) *
                                     h_.rotor_stage_torque(s) * v[r]
                               : 0.0;
  }
  for (const std::unique_ptr<Element>& element : h_.elements_) element->rates(t, y, ydot, energy);
}

ChannelState DriveHybrid::ConstrainedSolver::output(double t, const double* y,
                                                    ContactForces& forces) {
  h_.set(t, y);
  if (h_.model_.thread_pair().exact_play() && h_.mode_.contact == ThreadContact::open)
    h_.check_flight(t);
  // A closed flank that pulls (the row at its opening): the law's branch.
  const ModeSolution s = h_.on_the_law(h_.solve_current());
  forces.normal = s.normal_force;
  forces.friction = s.friction_force;
  forces.preload_normal = s.preload_normal;
  forces.motor_torque = h_.model_.gear().rotor_torque(speed_train_torque(s));
  ChannelState state = channel_state(h_.dynamics_);
  if (motor_friction_state_ >= 0 && motor_friction_channel_ >= 0)
    state.values[motor_friction_channel_] = y[motor_friction_state_];
  if (gear_state_ >= 0) state.values[gear_channel_] = y[gear_state_];
  const int bristle = bristle_state_;
  if (bristle >= 0) {
    state.values[bristle_channel_] = h_.dynamics_.bristle();  // z (set)
    if (h_.dynamics_.transverse())
      state.values[bristle_channel_ + 1] = h_.dynamics_.transverse_bristle();
    state.elastic += y[bristle + 1];  // the bristles' stored energy
  }
  // Stick holds the slip velocity at zero; the state carries the integrator's
  // error in this linear invariant (CVODE's Newton tolerance, ~1e-15 m/s).
  if (forces.stick) state.slip_velocity = 0.0;
  for (const std::unique_ptr<Element>& element : h_.elements_)
    element->output(t, y, forces, state);
  return state;
}

double DriveHybrid::ConstrainedSolver::slip_resolution() const {
  return h_.model_.tangent_direction().cwiseAbs().sum() * h_.integrator_options_.atol;
}

// A stuck contact's state onto its held constraints (DriveHybrid::project):
// held on the acceleration level alone, they drift with the integrator's
// Newton error (a stuck seat adjuster's closed flank: 4.3e-6 m beyond its
// flank after 2 s at rtol 1e-8, the load creeping into its stop). The
// change is the least one in the kinetic metric, of the size of that
// error, and its energy with it: the constraint forces' work on the drift,
// which the account never booked, is taken back with it. Only in stick:
// in a slip or a free flight the projection's corrections, which enter
// CVODE's history as part of its steps' and bend its dense output within a
// step, failed runs that passed before (a speed-controlled motor's impacts
// at rtol 1e-11 past a million steps against 531k; a preloaded nut's
// lift-off at the smallest step size); a slip's drift ends at its next
// event.
bool DriveHybrid::ConstrainedSolver::project(double t, const double* y, double* correction) {
  const StateLayout& layout = h_.layout_;
  std::fill(correction, correction + layout.size(), 0.0);
  const DriveDynamics::HeldContact held = h_.held_contact();
  if (!held.stick && !held.rotor) return false;
  CoordinateVector q, v;
  layout.expand(t, y, q, v);
  // Left alone: a drive at rest (every speed within atol; corrections of
  // round-off moved one at rest in its equilibrium by 2.6e-12 rad, which
  // stays exactly still without them, and its drift is bounded by atol per
  // second), and a violation within kHeldResolution of the error weights
  // rtol |y_i| + atol (round-off is no drift). Held back to the full
  // weights, the violation ramped into the history and the projected steps
  // failed their error test down to the smallest step; at 1e-2 of them
  // (then in every mode) a correction's bump in the dense output put a stuck
  // clamp's friction 2e-7 N outside its cone.
  const double rtol = h_.integrator_options_.rtol, atol = h_.integrator_options_.atol;
  if (!(v.cwiseAbs().maxCoeff() > atol)) return false;
  CoordinateVector dq = q, dv = v;
  if (!h_.dynamics_.project_held(held, dq, dv)) return false;
  bool beyond = false;
  for (int i = 0; i < q.size(); ++i) {
    const double q_weight = rtol * std::abs(q[i]) + atol, v_weight = rtol * std::abs(v[i]) + atol;
    beyond = beyond || std::abs(dq[i] - q[i]) > kHeldResolution * q_weight ||
             std::abs(dv[i] - v[i]) > kHeldResolution * v_weight;
  }
  if (!beyond) return false;
  dq -= q;
  dv -= v;
  layout.compress(dq, dv, correction);
  return true;
}

// By the constrained solve with a unit drive torque (on the rotor: n on its
// coordinate behind a gear) and a unit axial force.
RigidModeCoefficients DriveHybrid::ConstrainedSolver::coefficients(int sigma) {
  const DriveModel& model = h_.model_;
  const int n = model.coordinate_count();
  CoordinateVector unit_torque = CoordinateVector::Zero(n), unit_force = unit_torque;
  unit_torque[model.rotor()] = model.gear().driven_torque(1.0);
  unit_force[model.load()] = 1.0;
  const ModeSolution torque = h_.dynamics_.solve_with_forces(h_.spec(sigma), unit_torque);
  const ModeSolution force = h_.dynamics_.solve_with_forces(h_.spec(sigma), unit_force);
  RigidModeCoefficients c;
  if (!torque.regular || !force.regular) return c;
  c.normal_force = {torque.normal_force, force.normal_force};
  c.friction_force = {torque.friction_force, force.friction_force};
  return c;
}

}  // namespace leadscrew::model::drive
