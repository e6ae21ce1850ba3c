// DriveMoreau's step (moreau.hpp): take_step_held's parts, in order: the
// step's start and the elements' impulses (begin_step), the thread's
// contact and the stops' active sets (plan_contacts, plan_stops), the
// passes of its solve (solve_step, assemble_step), its end velocities and
// state, its account and what its row reports (finish_velocities,
// book_step, book_losses, report_step).
#include <algorithm>
#include <cmath>
#include <limits>

#include "moreau.hpp"
#include "screw_end.hpp"

namespace leadscrew::model::drive {

// The step's start: the state at t, the forces at t + theta h; the
// elements' impulses over the step (a DC motor's mean current's torque in
// place of the start's, its slope an implicit damping of the rotor), and
// the rotor's share of them (the train's balance).
void DriveMoreau::begin_step(StepState& s) {
  layout_.expand(s.t, s.y, q_, v_);
  s.q0 = q_;
  s.v0 = v_;
  dynamics_.set_element_states(s.y);
  dynamics_.set_state(s.t + s.theta * s.h, q_, v_);
  s.play0 = dynamics_.play();
  s.play_rate0 = dynamics_.play_rate();
  const std::vector<std::shared_ptr<const Element>>& elements = model_.elements().elements;
  element_constant_.setZero(model_.coordinate_count());
  element_slope_.setZero(model_.coordinate_count());
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const ElementStep step = element_step(k, s.t, s.h, s.theta, s.y, s.q0, s.v0);
    elements[k]->step_impulse(step, step_modes_[k], element_constant_.data(),
                              element_slope_.data());
    s.rotor_impulse += elements[k]->step_rotor_impulse(step, step_modes_[k]);
  }
}

// Which thread contact is active in this step; a penalty flank's force over
// the step linearised at the predicted end of the play, then at the step's
// own (update_flank); the speed-controlled rotor's target.
void DriveMoreau::plan_contacts(StepState& s, double restitution) {
  if (model_.thread_pair().exact_play()) {
    const double half = 0.5 * p_.clearance;
    const double predicted = s.play0 + s.h * s.play_rate0;
    if (predicted <= -half) {
      s.sigma_fixed = 1;
    } else if (predicted >= half) {
      s.sigma_fixed = -1;
    } else {
      s.contact_at_start = false;
    }
    // Newton's restitution where this step closes the flank (the play
    // inside the clearance at its start); a flank already closed stays so
    // (target 0, or W_N v_theta = 0 where the start separates:
    // held_flank_target), as in the event-driven scheme an impact happens once:
    // restitution at every step of a persistent contact flipped its normal
    // velocity step after step, and with friction and the springs the
    // account created energy (up to 1e3 of the work).
    const bool closing = std::abs(s.play0) < half;
    s.normal_target = closing ? -restitution * model_.normal_direction().dot(s.v0)
                              : held_flank_target(s);
    s.restituting = s.contact_at_start && closing && restitution > 0.0;
  }
  const elements::ThreadPair& thread = model_.thread_pair();
  if (thread.penalty()) {
    flank_.start(thread, s.play0);
    flank_.linearise(thread, s.play0 + s.h * s.play_rate0);
  }
  if (lift_off_) {  // (half B's spring: moreau_lift_off.cpp)
    half_b_ = HalfBSpring{};
    half_b_.e0 = s.play0;
    half_b_.linearise(*model_.preloaded_nut(), s.play0 + s.h * s.play_rate0);
  }
  s.rotor_target = p_.speed_controlled ? model_.motor().prescribed_speed(s.t + s.h) : 0.0;
}

// The end stops' active sets at the step's start: a penalty stop engaged
// where it penetrates at the start or the start's velocity carries the
// load into it within the step; an exact stop active where the predicted
// position closes its gap, with Newton's target on the step that closes it
// (the gap open at the start), else 0 (a closed contact stays closed). The
// rotor's friction contact (the motor's friction, a lossy or worm stage:
// train_friction.hpp), a second friction contact of the step: its balance.
void DriveMoreau::plan_stops(StepState& s) {
  const int load = model_.load();
  const std::vector<elements::EndStop>& stops = model_.elements().end_stops();
  const std::vector<elements::ExactEndStop>& exact = model_.elements().exact_stops;
  s.u0 = s.q0[load], s.du0 = s.v0[load];
  const double u0 = s.u0, du0 = s.du0, h = s.h;
  for (std::size_t k = 0; k < stops.size(); ++k)
    engaged_[k] = stops[k].penetration(u0) > 0.0 || stops[k].penetration(u0 + h * du0) > 0.0;
  for (std::size_t k = 0; k < exact.size(); ++k) {
    stop_active_[k] = exact[k].gap(u0 + h * du0) <= 0.0;
    stop_closing_[k] = exact[k].gap(u0) > 0.0;
    stop_target_[k] = stop_closing_[k]
                          ? stop_share_ * exact[k].side * exact[k].restitution * du0
                          : held_stop_target(exact[k].side, du0, s.theta);
  }
  stop_restituting_ = restitution_through_thread();
  if (const elements::TrainFriction* train = model_.train_friction()) {
    s.balance.inertia = train->rotor_inertia;
    s.balance.w0 = s.v0[model_.rotor()];
    s.balance.h0 = h * model_.motor().applied_torque(s.t + s.theta * h) + s.rotor_impulse;
    s.balance.h1 = element_slope_[model_.rotor()];
    s.balance.friction = h * train->motor_friction_bound();
  }
}

// The passes of the step's solve: the iteration matrix, its stiffness and
// damping and the right-hand side without the penalty flank's force,
// assembled on the first pass and where the engaged penalty stops changed;
// the flank's part (its linearisation moves from pass to pass) is W's
// rank-one term. A pass ends where the stops' active sets and the flank's
// linearisation hold.
void DriveMoreau::solve_step(StepState& s) {
  const elements::ThreadPair& thread = model_.thread_pair();
  const bool penalty = thread.penalty();
  const double t = s.t, h = s.h, theta = s.theta;
  const CoordinateVector& v0 = s.v0;
  int stop_passes = 0;
  Square stiffness, damping;
  CoordinateVector rhs_base;
  bool assembled[kMaxStops] = {false, false};
  for (int pass = 0;; ++pass) {
    if (penalty) {  // (the flank's friction contact: where it pushes; half B's always)
      s.contact_at_start = flank_.active() || lift_off_;
      s.sigma_fixed = -flank_.side;
    }
    // Iteration matrix and free velocity.
    if (pass == 0 || !std::equal(engaged_, engaged_ + kMaxStops, assembled)) {
      std::copy(engaged_, engaged_ + kMaxStops, assembled);
      assemble_step(s, stiffness, damping, rhs_base);
    } else {
      iteration_.set_rank_one(flank_coefficient(h, theta));
    }
    CoordinateVector rhs = rhs_base;
    // A penalty flank's force over the step, its part at v+ in W (assemble).
    if (penalty && flank_.active()) {
      const double g0 = lane_dot(thread.play_gradient(), v0);
      rhs -= h *
             (flank_.secant + flank_.slope * (flank_.e0 + h * (1.0 - theta) * g0 - flank_.e1k) +
              flank_.damping * (1.0 - theta) * g0) *
             thread.play_gradient();
    }
    free_ = iteration_.solve(rhs);
    if (lift_off_) pass_rhs_ = rhs;
    if (model_.train_friction() != nullptr) {
      s.impulses = solve_train(t, h, theta, v0, s.normal_target, s.rotor_target, s.sigma_fixed,
                               s.balance, s.contact_at_start, s.contact, s.stick, s.rotor_mode);
    } else {
      s.contact = s.contact_at_start;
      if (s.contact)
        s.impulses = solve_thread(t, h, theta, v0, s.normal_target, s.rotor_target,
                                  s.sigma_fixed, s.contact, s.stick);
      if (!s.contact) s.impulses = solve(false, 0.0, s.rotor_target, 0.0);
    }
    // (An exact flank the pass ends beyond takes its contact first: the
    // stops' sets are decided on a pass with the thread's contact.)
    bool again = exact_flank_closes(s) ||
                 (stop_passes < 8 && update_stops(h, theta, v0, s.impulses, s.released));
    ++stop_passes;
    // (Newton on the flank's force: quadratic, a few passes; capped.)
    if (penalty && pass < 100 && update_flank(h, theta, v0, s.impulses)) again = true;
    if (lift_off_ && pass < 100 && update_half_b(h, theta, v0, s.impulses)) again = true;
    if (!again) break;
  }
}

// W and the right-hand side without the penalty flank's force: masses,
// springs, dampers, the elements' impulses; a penalty stop's force over
// the step: 0 where not engaged, else the linear Kelvin-Voigt force
// k (d0+ + theta dd) + c d'_theta (its increments through W), measured from
// the face or, engaging within the step, from the step's start.
void DriveMoreau::assemble_step(const StepState& s, Square& stiffness, Square& damping,
                                CoordinateVector& rhs_base) {
  const double h = s.h, theta = s.theta;
  const CoordinateVector& v0 = s.v0;
  assemble(h, theta, stiffness, damping, true);
  rhs_base = model_.mass().cwiseProduct(v0) + h * dynamics_.forces() -
             theta * (1.0 - theta) * h * h * (stiffness * v0) + theta * h * (damping * v0);
  if (!model_.elements().elements.empty()) rhs_base += element_constant_;
  const int load = model_.load();
  const std::vector<elements::EndStop>& stops = model_.elements().end_stops();
  for (std::size_t k = 0; k < stops.size(); ++k) {
    const elements::EndStop& stop = stops[k];
    rhs_base[load] += h * stop.side * stop.pushing_force(s.u0, s.du0);
    if (engaged_[k])
      rhs_base[load] -= h * stop.side *
                        (stop.stiffness * std::max(stop.penetration(s.u0), 0.0) +
                         stop.damping * stop.side * s.du0);
  }
}

// The step's end velocities. A speed-controlled rotor ends the step at its
// prescribed speed exactly, as the state carries it (StateLayout::expand):
// the solve's value, its round-off apart, turned a rotor held at 0 by
// 1e-20 rad and booked 1e-19 J of work of either sign.
void DriveMoreau::finish_velocities(StepState& s) {
  v_ = s.impulses.velocity;
  if (p_.speed_controlled) v_[model_.rotor()] = s.rotor_target;
  if (model_.thread_pair().exact_play() && !s.contact)
    s.impulses.normal = 0.0, s.impulses.friction = 0.0;
  if (model_.thread_pair().penalty()) {
    s.impulses.normal = flank_impulse(s.h, s.theta, s.v0, v_);
    if (lift_off_) s.impulses.normal += s.impulses.preload_normal;  // (half B's)
    if (!s.contact) s.impulses.friction = 0.0;
  }  check_half_a_bearing(s);  // (exact play closed by a preloaded nut)
}

// The state at the step's end: the positions of the independent
// coordinates (the layout fills the rest), the work, the elements' states
// at the step's end with their work and losses (a DC motor's armature over
// the step), the friction's loss.
void DriveMoreau::book_step(StepState& s, double* y_next) {
  const double t = s.t, h = s.h, theta = s.theta;
  const double* y = s.y;
  const CoordinateVector& q0 = s.q0;
  const CoordinateVector v_theta = (1.0 - theta) * s.v0 + theta * v_;
  q_ = q0 + h * v_theta;
  CoordinateVector q_positions = q_;
  layout_.compress(q_positions, v_, y_next);
  const int offset = layout_.energy_offset();
  for (int e = 0; e < kEnergyCount; ++e) y_next[offset + e] = y[offset + e];
  layout_.expand(t + h, y_next, q_, v_);
  // The event-driven scheme's root g4, for every concept: the run ends at
  // the end of the first step that takes the nut's end past the screw's
  // (checked at each step's end, so the last step's end is checked too; the
  // start is the model's checked initial position).
  const double nut_end = model_.nut_position(q_.data());
  if (!(model_.screw_end_margin(nut_end) > 0.0)) nut_left_the_screw(model_, t + h, nut_end);
  double* energy = y_next + offset;
  const double motor = p_.speed_controlled ? s.impulses.rotor * v_theta[model_.rotor()]
                                           : model_.motor().applied_torque(t + theta * h) *
                                                 (q_[model_.rotor()] - q0[model_.rotor()]);
  energy[kWorkDrive] += motor;
  const std::vector<std::shared_ptr<const Element>>& elements = model_.elements().elements;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const int first = element_slots_[k].first;
    elements[k]->step_end(element_step(k, t, h, theta, y, q0, s.v0), q_.data(), v_.data(),
                          step_modes_[k], first >= 0 ? y_next + first : y_next, energy);
  }
  energy[kWorkAxial] +=
      p_.axial_force(t + theta * h) * (q_[model_.load()] - q0[model_.load()]);
  const double slip = lane_dot(model_.tangent_direction(), v_);
  // A sticking step (the LCP's stick basis) ends at zero slip exactly; its
  // computed slip is the round-off of terms of h f / m (1e-17 m/s against
  // 4 m/s of a stuck drive's step), which would book a round-off loss of
  // either sign.
  if (!(s.contact && s.stick)) {
    energy[kFrictionLoss] += -s.impulses.friction * slip;
    // (ResultCheckSpec::step_friction_excess)
    const double slip0 = lane_dot(model_.tangent_direction(), s.v0);
    friction_excess_ += std::max(0.0, -(1.0 - theta) * s.impulses.friction * (slip - slip0));
    // A lift-off nut's half B slips on its own flank at gamma_T - sin(a) e'
    // (moreau_lift_off.cpp): its friction's loss on that slip.
    if (lift_off_)
      energy[kFrictionLoss] +=
          model_.preloaded_nut()->sin_lead * half_b_friction_ * model_.play_gradient().dot(v_);
  }
  if (bristle_state_ >= 0)
    // (A preloaded nut's halves: |P_N,A| + |P_N,B|, both flanks' bristles;
    // the slip of the law's friction, moreau_smooth_friction.cpp, "The
    // rows' slip".)
    book_bristles(h, y, y_next, bristle_slip(s, slip),
                  !s.contact ? 0.0
                             : std::abs(s.impulses.normal - s.impulses.preload_normal) +
                                   std::abs(s.impulses.preload_normal));
  if (transverse_state_ >= 0)
    book_transverse(h, y, y_next, s.contact, s.impulses.friction, s.impulses.normal, slip);
  play_rate_ = std::max({play_rate_, std::abs(s.play_rate0),
                         std::abs(lane_dot(model_.play_gradient(), v_))});
  book_losses(s, v_theta, y_next);
}

// The losses of dampers, stops, penalty flanks and the train's stages.
void DriveMoreau::book_losses(StepState& s, const CoordinateVector& v_theta, double* y_next) {
  const double h = s.h, theta = s.theta;
  const double* y = s.y;
  double* energy = y_next + layout_.energy_offset();
  double damping_power = 0.0;
  model_.elements().forces.for_each(
      [&](const auto& element) { damping_power += element.damping_power(v_theta); });
  energy[kDampingLoss] += h * damping_power;
  // The penalty stops' loss (as end_stop.hpp's power F d' - k d d'): an
  // engaged stop's damper, h c d'_theta^2 (its spring's part is the
  // scheme's numerical dissipation, as every spring's); a stop released
  // with d0 > 0 (no force over the step) loses the elastic energy it gives
  // up. The exact stops' impulses P dissipate -P g'_theta >= 0 (theta >= 1/2,
  // e <= 1), which the residual takes, as the flanks' impacts.
  const std::vector<elements::EndStop>& stops = model_.elements().end_stops();
  const int load = model_.load();
  for (std::size_t k = 0; k < stops.size(); ++k)
    energy[kDampingLoss] += moreau_contacts::penalty_stop_loss(stops[k], engaged_[k], s.u0,
                                                               q_[load], v_theta[load], h);
  // A penalty flank's: its damper's, or a released flank's elastic energy
  // (its spring's work is the potential's change: the discrete gradient).
  const elements::ThreadPair& thread = model_.thread_pair();
  if (thread.penalty())
    energy[kContactLoss] += flank_.loss(thread, thread.play(q_),
                                        lane_dot(thread.play_gradient(), v_theta), h);
  if (model_.train_friction() == nullptr) return;
  // The rotor's friction impulse Q = P_c + Lambda on -e_rotor: in a slip
  // the motor's friction P_c = s B and the stage's loss Lambda = Q - P_c
  // book their dissipation at the step's end speed (>= 0, as the
  // thread's -P_T gamma+); a stuck rotor ends at rest (no loss). The
  // booking's difference from the scheme's work -Q w_theta,
  // (1 - theta) Q (w+ - w0), joins the friction term the checks allow
  // (ResultCheckSpec::step_friction_excess).
  // (A speed-controlled rotor: at w_theta, where the motor's impulse works.)
  const double w1 = p_.speed_controlled ? v_theta[model_.rotor()] : v_[model_.rotor()];
  const double friction = s.rotor_mode.slip != 0 ? s.rotor_mode.slip * s.balance.friction : 0.0;
  const double stage = s.rotor_mode.slip != 0 ? s.impulses.train - friction : 0.0;
  if (const int k = motor_friction_state_; k >= 0) y_next[k] = y[k] + friction * w1;
  // (A flow within its round-off, a stage that transmits nothing, books
  // no loss of the other sign.)
  if (const int k = gear_state_; k >= 0) y_next[k] = y[k] + std::max(0.0, stage * w1);
  const double excess = (1.0 - theta) * s.impulses.train * (w1 - s.v0[model_.rotor()]);
  friction_excess_ += p_.speed_controlled ? 0.0 : std::max(0.0, excess);  // (at w_theta: none)
}

// What the row after the step reports: the exact stops' force, the thread's
// forces over the step; the speed-controlled rotor's torque is the step's
// impulse over h; a torque's or a DC motor's is the row's own (channels).
void DriveMoreau::report_step(const StepState& s) {
  const std::vector<elements::ExactEndStop>& exact = model_.elements().exact_stops;
  last_stop_force_ = 0.0;
  for (std::size_t k = 0; k < exact.size(); ++k)
    if (stop_active_[k]) last_stop_force_ -= exact[k].side * s.impulses.stop[k] / s.h;
  last_.normal = s.impulses.normal / s.h;
  last_.friction = s.impulses.friction / s.h;
  last_.preload_normal = s.impulses.preload_normal / s.h;
  last_.motor_torque =
      p_.speed_controlled ? model_.gear().rotor_torque(s.impulses.rotor / s.h) : 0.0;
  last_.stick = s.contact && s.stick;
  last_law_slip_ = bristle_slip(s, std::numeric_limits<double>::quiet_NaN());
}

// The slip LuGre's bristles take the step at: the law's (the slip of the
// step's friction), else the end state's (end_slip).
double DriveMoreau::bristle_slip(const StepState& s, double end_slip) const {
  return bristle_state_ >= 0 && s.contact && !std::isnan(s.impulses.law_slip)
             ? s.impulses.law_slip
             : end_slip;
}

}  // namespace leadscrew::model::drive
