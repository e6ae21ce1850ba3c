// DriveHybrid (hybrid.hpp): the root functions of the events (friction,
// flanks, the screw's end; then the elements' with events, driver_element.hpp)
// and their directions, the initial mode, and the change of mode at an event.
#include "hybrid.hpp"

#include <algorithm>
#include <cmath>

#include "driver_element.hpp"
#include "mode_solver.hpp"
#include "screw_end.hpp"

namespace leadscrew::model::drive {

// The root that ends a stick (>= 0 while it holds; roots' g0).
double DriveHybrid::stick_root(const double* y, const ThreadForces& s) {
  // The motor holds the slip at zero (the friction force stays in the cone
  // by construction): the stick ends where the prescribed slip leaves zero,
  // either way.
  if (slip_prescribed_now()) return std::abs(solver_->slip_velocity(y));
  const elements::PreloadedNut* nut = model_.preloaded_nut();
  if (nut && nut->lift_off)
    return nut->sticking().split_stick_margin(dynamics_.penalty_normal_force(),
                                              dynamics_.preload_spring_force(), s.friction_force);
  double margin;
  if (train_) {
    margin = train_->stick_margin();  // the static stick test
  } else if (nut) {
    margin = nut->sticking().stick_margin(s.normal_force, s.friction_force);
  } else {
    const double mu = stick_mu();
    margin = (mu * s.normal_force - s.friction_force) * (mu * s.normal_force + s.friction_force);
  }
  if (margin > 0.0) stick_from_zero_ = false;  // the margin left zero into the cone
  return margin;
}

void DriveHybrid::roots(double t, const double* y, double* g) {
  g[0] = g[1] = g[2] = g[3] = g[4] = 1.0;
  solver_->expand(t, y);
  g[4] = model_.screw_end_margin(model_.nut_position(q_.data()));
  const bool active = mode_.contact != ThreadContact::open;
  const elements::PreloadedNut* closing = closing_nut();
  // A closed flank is watched for its normal force falling through zero
  // whatever the friction (a frictionless one too: it must open), and so is
  // half A of a preloaded nut closing exact play.
  if (active && (mode_.friction != FrictionMode::none || mode_.contact == ThreadContact::closed ||
                 closing)) {
    if (mode_.friction == FrictionMode::slip) g[0] = solver_->slip_velocity(y) - slip_offset_;
    const bool need_forces = mode_.friction == FrictionMode::stick ||
                             mode_.contact == ThreadContact::closed ||
                             mode_.contact == ThreadContact::bilateral;
    if (need_forces) {
      const ThreadForces s = solver_->forces(t, y);
      if (mode_.friction == FrictionMode::stick) g[0] = stick_root(y, s);
      if (mode_.friction == FrictionMode::stick && mode_.half_b_edge != 0) {
        g[0] = half_b_edge_.edge_margin;  // (set by forces: solve_current)
        g[1] = half_b_edge_.spring_margin;
      }
      if (mode_.contact == ThreadContact::bilateral && mode_.friction != FrictionMode::stick)
        g[1] = flank_change_root(s.normal_force - s.preload_normal);
      // Half A lifting off into the closed exact play: an error at its root.
      if (closing) g[1] = half_a_bearing(s.normal_force, s.preload_normal);
      if (train_ && train_->has_stage() && mode_.friction == FrictionMode::slip)
        g[2] = stage_reversal_root(train_->stage_torque());
      if (watch_fold()) {
        // The regularized law's paradox: the margin min over sigma of
        // G_NN - sigma kappa G_NT, and the current branch's denominator
        // approaching zero (see approach_fold).
        g[2] = fold_margin();
        g[3] = dynamics_.thread_denominator(sigma_guess_, current_kappa()) /
                   dynamics_.delassus_normal() -
               kFoldWatch;
      }
      if (mode_.contact == ThreadContact::closed) g[1] = mode_.flank * s.normal_force;
      if (load_root_ >= 0) g[load_root_] = load_root_value(t);
    }
  }
  for (const std::unique_ptr<Element>& element : elements_)
    element->roots(t, g + element->first_root());
  if (mode_.contact == ThreadContact::open || mode_.contact == ThreadContact::penalty) {
    g[2] = dynamics_.play() - 0.5 * p_.clearance;
    g[3] = dynamics_.play() + 0.5 * p_.clearance;
  }
  // After a bounce the flight's apex (the play rate through zero) is an
  // event: a weak bounce leaves the flank and comes back within one step,
  // and the gap alone would show no sign change at the step ends.
  if (mode_.contact == ThreadContact::open && bounced_from_ != 0) {
    g[1] = dynamics_.play_rate();
    // Until the apex the play moves away from the flank it bounced off, so
    // gap + tau * gap rate stays strictly on the open side (it starts at
    // tau * rate, not at zero, which would mislead the root finder) and
    // equals the gap at the apex: continuous where the ordinary gap takes over.
    constexpr double tau = 1e-3;  // [s]; any positive time works
    if (bounced_from_ > 0)
      g[3] += tau * dynamics_.play_rate();
    else
      g[2] += tau * dynamics_.play_rate();
  }
}

void DriveHybrid::root_directions(int* directions) const {
  // g0: slip s ends when s gamma falls through 0; stick when the cone margin falls.
  directions[0] = mode_.friction == FrictionMode::slip ? -mode_.slip_sign
                  : slip_prescribed_now()                ? 1
                                                         : -1;
  // g1: a closed flank opens when its normal force falls; the bilateral
  // thread changes flank when the normal force falls through zero on its
  // side (see flank_change_root).
  directions[1] = mode_.contact == ThreadContact::closed ||
                          mode_.contact == ThreadContact::bilateral
                      ? -1
                      : 0;
  if (mode_.contact == ThreadContact::open && bounced_from_ != 0)
    directions[1] = bounced_from_ > 0 ? -1 : 1;  // leaving the lower flank: e' falls at the apex
  if (mode_.friction == FrictionMode::stick && mode_.half_b_edge != 0)
    directions[1] = -1;  // half B at its spring's force sticks again
  // g2, g3: an open thread hits the upper flank rising, the lower falling;
  // a penalty contact restarts at both crossings.
  // A penalty flank is entered rising (upper) or falling (lower) and left
  // the other way: a root that starts at exactly 0 (a nut placed on the
  // flank) must see which crossing comes (RootGuard; with either direction
  // it saw neither entering, and the flank carried no friction).
  const bool open = mode_.contact == ThreadContact::open;
  const bool penalty = mode_.contact == ThreadContact::penalty;
  const bool upper = penalty && touching_ && dynamics_.play() > 0.0;
  const bool lower = penalty && touching_ && dynamics_.play() < 0.0;
  directions[2] = open || (penalty && !upper) ? 1 : (penalty ? -1 : 0);
  directions[3] = open || (penalty && !lower) ? -1 : (penalty ? 1 : 0);
  directions[4] = -1;  // the nut reaches an end of the screw
  for (const std::unique_ptr<Element>& element : elements_)
    element->root_directions(directions + element->first_root());
  if (watch_fold()) directions[2] = directions[3] = -1;  // both fall towards jamming
  if (train_) directions[2] = -1;  // the stage's torque falls through zero on its side
}

void DriveHybrid::select_initial_mode(double t, double* y) {
  set(t, y);
  kinetic0_ = dynamics_.kinetic_energy();
  stored0_ = dynamics_.elastic_energy() + dynamics_.contact_energy() +
            dynamics_.element_energy_terms();
  // The thread pair's kind of play: none (a constraint), exact flanks or
  // penalty flanks.
  const elements::ThreadPair& thread = model_.thread_pair();
  if (thread.bilateral()) {
    mode_.contact = ThreadContact::bilateral;
  } else if (thread.exact_play()) {
    const double half = 0.5 * p_.clearance;
    if (dynamics_.play() >= half) {
      mode_.contact = ThreadContact::closed;
      mode_.flank = -1;
    } else if (dynamics_.play() <= -half) {
      mode_.contact = ThreadContact::closed;
      mode_.flank = 1;
    } else {
      mode_.contact = ThreadContact::open;
    }
  } else {
    mode_.contact = ThreadContact::penalty;
    touching_ = std::abs(dynamics_.play()) > 0.5 * p_.clearance;
  }
  decide_friction(t, y, std::abs(dynamics_.slip_velocity()) <= dynamics_.slip_noise(), 0);
  if (mode_.contact == ThreadContact::closed) {
    const ModeSolution s = solve_current();
    if (mode_.flank * s.normal_force < 0.0) {
      mode_.contact = ThreadContact::open;
      mode_.friction = FrictionMode::none;
    }
  }
  if (rotor_train_) decide_rotor(t, y, false, false);  // (with the thread's decision at each mode)
  note_flight_start(t, y);
  start_normal_side();
  for (const std::unique_ptr<Element>& element : elements_) element->start(t, y);
  if (watch_fold()) {
    set(t, y);
    // A start inside the regularized law's Painleve regime (kappa |G_NT| >=
    // G_NN at the initial slip velocity: both signs of the flank normal
    // force consistent, or neither) jams where it starts, as exact
    // Coulomb's does; its roots only see the regime being entered.
    if (fold_margin() <= 0.0)
      jam_regularized("the drive starts inside the regime where both signs of the flank "
                      "normal force are consistent, or neither");
    solve_current();
    if (dynamics_.thread_denominator(sigma_guess_, current_kappa()) <
        kFoldWatch * dynamics_.delassus_normal())
      approach_fold(t, y);
  }
  start_mode(t, y);
}

std::string DriveHybrid::handle_event(double t, double* y, const std::vector<int>& root_info) {
  if (load_scan_horizon(t, root_info)) return std::string();
  if (root_info[4] != 0) {
    set(t, y);
    nut_left_the_screw(model_, t, model_.nut_position(q_.data()));
  }
  const bool from_zero = stick_from_zero_ && mode_.friction == FrictionMode::stick &&
                         root_info[0] != 0;
  // The elements whose roots fired, in the list's order: their state
  // changes (y may: an end stop's impact, a current snapped onto its limit).
  // Where a force jumps (an end stop's onset, impact or closing), the
  // friction mode is decided anew (change_mode) as at a penalty flank; where
  // only elements fired and none asks for that (a current limit's hold),
  // the event is theirs alone.
  bool decide = std::any_of(root_info.begin(), root_info.begin() + kThreadRoots,
                            [](int info) { return info != 0; });
  bool quiet = false;
  std::string elements_kind, quiet_kind;
  for (const std::unique_ptr<Element>& element : elements_) {
    const int* info = root_info.data() + element->first_root();
    if (std::none_of(info, info + element->root_count(), [](int i) { return i != 0; })) continue;
    const Element::Event event = element->handle(t, y, info);
    std::string& into = event.decide_mode ? elements_kind : quiet_kind;
    if (!event.kind.empty()) into = into.empty() ? event.kind : into + ", " + event.kind;
    (event.decide_mode ? decide : quiet) = true;
  }
  if (quiet && !decide) return quiet_kind;
  std::string kind = change_mode(t, y, root_info);
  if (!elements_kind.empty()) kind = kind.empty() ? elements_kind : elements_kind + ", " + kind;
  for (const std::unique_ptr<Element>& element : elements_) element->after_mode_change(t, y);
  if (rotor_train_) settle_rotor(t, y);  // the thread's new mode may end the rotor's
  note_flight_start(t, y);
  start_mode(t, y);
  // A stick whose cone margin never left zero was no stick phase: the thread
  // carried no force (a flexible drive's relaxed springs at t = 0) and the
  // forces, once they grow, leave the cone at once. The slip that follows is
  // the drive's motion from the start, not an event.
  return from_zero ? std::string() : kind;
}

// After the mode is chosen (at the start and at every event).
void DriveHybrid::start_mode(double t, const double* y) {
  plan_load_roots(t);
  // A slip mode starts at zero slip (projected to round-off) or with the
  // slip velocity's sign. Where the projection's round-off leaves the slip
  // velocity on the other side of zero than the mode's sign (-2.4e-38 m/s
  // with slip+), the root g0 would start beyond its own zero and never
  // fall through it: the drive slipped the other way for the rest of the
  // run with friction pushing it. The root is measured from that
  // round-off instead, so it starts at exactly 0 (on its uncrossed side,
  // RootGuard) and any slip against the mode's sign ends the mode.
  //
  // Where an event of g0 kept the same slip mode (the flank LCP at zero
  // slip chose the same direction again), the slip velocity crossed zero
  // only by the integrator's noise: forces of 1e-15 N at the start of a
  // flexible drive, whose slip acceleration of 1e-11 m/s^2 no step resolves,
  // restarted CVODE at every crossing of its noise, a million steps within
  // 7 ns. Then the root waits for the slip to pass the integrator's
  // resolution against the mode's sign (slip_resolution), which any real
  // reversal does; friction may do positive work within that band only,
  // at most mu' |N| times it (the result's checks allow for it).
  slip_offset_ = 0.0;
  if (mode_.friction == FrictionMode::slip) {
    solver_->expand(t, y);
    const double slip = solver_->slip_velocity(y);
    if (mode_.slip_sign * slip < 0.0) slip_offset_ = slip;
    if (slip_noise_event_) slip_offset_ = -mode_.slip_sign * solver_->slip_resolution();
  }
  slip_noise_event_ = false;
  stick_from_zero_ = false;
  if (mode_.friction == FrictionMode::stick) {
    solver_->expand(t, y);
    stick_position_ = model_.tangent_direction().dot(q_);  // held from here (held_contact)
  }
  if (mode_.friction == FrictionMode::stick && train_) {
    solver_->expand(t, y);
    const ThreadForces s = solver_->forces(t, y);
    stick_from_zero_ = s.normal_force == 0.0 && s.friction_force == 0.0;
  } else if (mode_.friction == FrictionMode::stick) {
    const ModeSolution s = solve_current();
    stick_from_zero_ = s.normal_force == 0.0 && s.friction_force == 0.0;
  }
  // A mode of a preloaded nut closing exact play that starts with half A
  // pulling on its flank (half B's force changes with the mode): it lifts
  // off here.
  if (closing_nut()) {
    const ModeSolution s = solve_current();
    if (half_a_bearing(s.normal_force, s.preload_normal) < 0.0) half_a_lifts_off(t);
  }
}

// A stick's slip position (the stick's start's, start_mode) and a closed
// flank's play held on the position and velocity level, besides their rows
// of the acceleration solve (project: in stick only). The thread without
// play holds e = 0 through the layout's eliminated coordinate: its row keeps
// that coordinate out of the stick's correction.
DriveDynamics::HeldContact DriveHybrid::held_contact() const {
  DriveDynamics::HeldContact held;
  held.rotor = rotor_train_ && rotor_mode_.slip == 0;  // a stuck rotor holds phi_r' = 0
  held.stick = mode_.friction == FrictionMode::stick && !slip_prescribed_now();
  if (!held.stick) return held;
  held.slip_position = stick_position_;
  if (mode_.contact == ThreadContact::closed) {
    held.normal = true;
    held.play = -0.5 * mode_.flank * p_.clearance;  // the lower flank (+1) at e = -c/2
  } else if (mode_.contact == ThreadContact::bilateral) {
    held.normal = true;
    held.play = model_.thread_pair().play(CoordinateVector::Zero(model_.coordinate_count()));
  }
  return held;
}

bool DriveHybrid::has_projection() const {
  // Only a set-valued law sticks (a regularized one slips at every speed,
  // and its contacts are held by no constraint between events): elsewhere
  // CVODE's projection call at every step costs a flexible drive with a
  // smooth law 5 % of its run for nothing (benchmarks/before_after).
  return dynamics_.law().resolution() == friction::Resolution::set_valued &&
         dynamic_cast<const ConstrainedSolver*>(solver_.get()) != nullptr;
}

void DriveHybrid::project(double t, const double* y, double* correction) {
  solver_->project(t, y, correction);
}

// The free flight reaches the flank `flank` (+1 lower, -1 upper): an impact,
// or a touch below resolution (the play reaches the flank without
// approaching it, or so slowly against a free flight that pulls it back
// that it would go less than kPlasticHeight of the clearance beyond,
// rate^2 / (2 |e''|)), whose state is saved for undo_touch. Returns true
// where the play bounces off the flank (still open: the event is over).
bool DriveHybrid::end_flight(double t, double* y, int flank, bool& touch, bool& zero_slip,
                             std::string& kind) {
  const double rate = dynamics_.play_rate();
  touch = flank * rate >= 0.0;
  if (!touch) {
    const double acceleration = free_flight_play_acceleration();
    touch = flank * acceleration > 0.0 &&
            rate * rate <= 2.0 * flank * acceleration * kPlasticHeight * p_.clearance;
  }
  if (touch) {
    std::copy(y, y + size(), saved_state_.begin());
    saved_impact_loss_ = impact_loss_;
    saved_rotor_mode_ = rotor_mode_;
  }
  zero_slip = flank_impact(t, y, flank);
  kind = "impact on the " + std::string(flank > 0 ? "lower" : "upper") + " flank";
  if (mode_.contact == ThreadContact::open) {
    bounced_from_ = flank;
    layout_.compress(q_, v_, y);
    return true;
  }
  bounced_from_ = 0;
  return false;
}

// A touch below resolution of a flank that cannot push: no contact,
// nothing changes (y is left as it was). This is the integrator's noise
// at the flank just left: a flank opens when its normal force falls
// through zero, so the play leaves it at third order in time, and a
// multistep method's first steps after the restart (CVODE) can show it
// a round-off beyond the flank, even approaching it at a round-off rate.
// That round-off goes back inside (put_back_inside): left beyond the
// flank, it would start the flight on the crossed side of its root.
void DriveHybrid::undo_touch(double t, double* y, const Mode& before, int bounced_before) {
  mode_ = before;
  bounced_from_ = bounced_before;
  std::copy(saved_state_.begin(), saved_state_.end(), y);
  impact_loss_ = saved_impact_loss_;
  rotor_mode_ = saved_rotor_mode_;
  put_back_inside(t, y);
}

// handle_event without the planning of the next mode's load-driven roots.
std::string DriveHybrid::change_mode(double t, double* y, const std::vector<int>& root_info) {
  set(t, y);
  const Mode before = mode_;
  if (closing_nut() && root_info[1] != 0) half_a_lifts_off(t);
  if (watch_fold() && root_info[2] != 0) {
    solve_current();
    // The other sign's denominator passes through zero (the current branch
    // stays regular): beyond, that sign is consistent too.
    jam_regularized("from here both signs of the flank normal force are consistent (the "
                    "regularized friction factor reached the Painleve bound)");
  }
  if (watch_fold() && root_info[3] != 0) {
    approach_fold(t, y);
    return "";  // the branch recovers: no event
  }
  bool zero_slip = false;
  int hint = 0;
  std::string kind;
  bool touch = false;
  const int bounced_before = bounced_from_;
  if (mode_.contact == ThreadContact::open && (root_info[2] > 0 || root_info[3] < 0)) {
    const int flank = root_info[2] > 0 ? -1 : 1;
    if (end_flight(t, y, flank, touch, zero_slip, kind)) return kind;
  } else if (mode_.contact == ThreadContact::open && root_info[1] != 0) {
    bounced_from_ = 0;  // the apex: the flight now only comes back
    layout_.compress(q_, v_, y);
    return "";
  } else if (mode_.contact == ThreadContact::closed && root_info[1] < 0) {
    mode_.contact = ThreadContact::open;
    mode_.friction = FrictionMode::none;
  } else if (root_info[0] != 0) {
    zero_slip = true;
    if (mode_.friction == FrictionMode::stick) {
      // Leaving the friction cone: slip starts against the friction force
      // that stick needed.
      hint = train_ ? train_->exit_direction() : -sign_of(solve_current().friction_force);
    }
  } else if (mode_.half_b_edge != 0 && root_info[1] != 0) {
    zero_slip = true;  // the stick with half B at its spring's force admissible again
  } else if (mode_.contact == ThreadContact::bilateral && root_info[1] != 0) {
    normal_side_ = -normal_side_;
    layout_.compress(q_, v_, y);
    return "flank change";
  } else if (train_ && root_info[2] != 0) {
    stage_side_ = -stage_side_;
    layout_.compress(q_, v_, y);
    return "gear stage power flow reversal";
  } else if (mode_.contact == ThreadContact::penalty && (root_info[2] != 0 || root_info[3] != 0)) {
    // A penalty flank is entered (upper rising, lower falling) or left.
    touching_ = root_info[2] > 0 || root_info[3] < 0;
    kind = touching_ ? "flank contact" : "flank separation";
    // A lift-off nut stuck keeps its friction across the crossing (half B's):
    // stick or slip from exactly zero slip, not from the slip's round-off.
    if (mode_.friction == FrictionMode::stick && model_.preloaded_nut() &&
        model_.preloaded_nut()->lift_off)
      zero_slip = true;
  }
  if (mode_.contact != ThreadContact::open) decide_friction(t, y, zero_slip, hint);
  slip_noise_event_ = root_info[0] != 0 && before.friction == FrictionMode::slip &&
                      mode_ == before;
  if (touch && mode_.contact == ThreadContact::open) {
    undo_touch(t, y, before, bounced_before);
    return "";
  }
  layout_.compress(q_, v_, y);
  start_normal_side();
  if (mode_ == before) return kind;
  const std::string change = describe(before, backlash_) + "->" + describe(mode_, backlash_);
  return kind.empty() ? change : kind + ", " + change;
}

}  // namespace leadscrew::model::drive
