// DriveMoreau (moreau.hpp): the Moreau-Jean step of a drive, its flank LCP
// on the velocity level, the restitution that creates no energy, and the
// check that a step resolves the drive's stiffness.
#include "moreau.hpp"
#include "transverse_slip.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/flank_lcp.hpp"
#include "leadscrew/friction/law.hpp"
#include "screw_end.hpp"

namespace leadscrew::model::drive {

DriveMoreau::DriveMoreau(const DriveModel& model)
    : model_(model), p_(model.parameters()), dynamics_(model),
      layout_(model, model.law()),
      names_(drive_channel_names(layout_)), element_slots_(layout_.element_slots()),
      stop_channel_(layout_.find_channel("stop_force")),
      motor_friction_state_(layout_.find_state("motor_friction_loss")),
      gear_state_(layout_.find_state("gear_loss")),
      motor_friction_channel_(layout_.find_channel("motor_friction_loss")),
      gear_channel_(layout_.find_channel("gear_loss")) {
  const int n = model.coordinate_count();
  q_.setZero(n);
  v_.setZero(n);
  dynamics_.set_element_slots(element_slots_);
  element_channels_.assign(element_slots_.size(), -1);
  for (const Declaration& d : layout_.declarations())
    if (d.element >= 0) element_channels_[static_cast<std::size_t>(d.element)] = d.first_channel;
  modes_at_start_.assign(element_slots_.size(), ElementMode{});
  step_modes_ = modes_at_start_;
  iteration_.directions(model.play_gradient(), model.tangent_direction());
  bristle_state_ = layout_.find_state("bristle_share");
  bristle_channel_ = layout_.find_channel("bristle_deflection");
  preload_channel_ = layout_.find_channel("preload_force");
  lift_off_ = model.preloaded_nut() != nullptr && model.preloaded_nut()->lift_off;
  bristle_range_ = model.law().bristle_range();
  transverse_state_ = layout_.find_state("transverse_work");
}

void DriveMoreau::initialize(double t, const double* y) {
  layout_.expand(t, y, q_, v_);
  dynamics_.set_element_states(y);
  dynamics_.set_state(t, q_, v_);
  const std::vector<std::shared_ptr<const Element>>& elements = model_.elements().elements;
  for (std::size_t k = 0; k < elements.size(); ++k)
    elements[k]->step_start(dynamics_.element_state(k), dynamics_.element_mode(k));
  kinetic0_ = dynamics_.kinetic_energy();
  stored0_ = dynamics_.elastic_energy() + dynamics_.contact_energy() +
            dynamics_.element_energy_terms();
}

void DriveMoreau::step(double t, double h, double theta, const double* y, double* y_next) {
  const double excess = friction_excess_, play_rate = play_rate_;
  for (std::size_t k = 0; k < modes_at_start_.size(); ++k)
    modes_at_start_[k] = dynamics_.element_mode(k);
  if (bristle_state_ >= 0) bristle_z0_ = y[bristle_state_] * bristle_range_;
  if (bristle_state_ >= 0 && transverse_state_ >= 0)  // (lugre_bristles_kind's third state)
    bristle_w0_ = y[bristle_state_ + 2] * bristle_range_;
  stop_share_ = 1.0;
  if (!take_step(t, h, theta, y, y_next, p_.restitution)) {
    if (stop_restituting_) limit_stop_restitution(t, h, theta, y, y_next, excess, play_rate);
    return;
  }
  // A step that closes a flank with Newton's restitution e > 0: with
  // Coulomb friction it can create energy (Kane and Levinson's paradox, as
  // at the event-driven scheme's impacts: a rigid nut's closing step at
  // e = 1 created 0.3 of the run's energy, at every dt). The step takes the
  // largest restitution up to e that creates no more than its plastic
  // version (e = 0, whose impulses solve the LCP of maximal dissipation),
  // found by bisection; the step is rare, its 40 solves cheap.
  const StepAccount first = energy_created(t, h, y, y_next);
  auto retake = [&](double e) {
    friction_excess_ = excess;
    play_rate_ = play_rate;
    take_step(t, h, theta, y, y_next, e);
    return energy_created(t, h, y, y_next);
  };
  const StepAccount plastic = retake(0.0);
  const double allowed =
      std::max(plastic.created, 0.0) + std::max(first.round_off, plastic.round_off);
  if (first.created <= allowed) {
    retake(p_.restitution);
    return;
  }
  double low = 0.0, high = p_.restitution;
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double middle = 0.5 * (low + high);
    (retake(middle).created <= allowed ? low : high) = middle;
  }
  retake(low);
}

// One step at restitution e; true where it closes a flank with e > 0. It
// is taken first in its elements' first modes (Element::step_first), then
// again while an element's step left its mode's domain (Element::step_mode:
// a DC motor's current beyond its driver's limit, held there, then beyond
// its supply, saturated; docs/physics/dc_motor.md), at most kMaxStepRetakes
// times. The modes it ends in are the run's.
bool DriveMoreau::take_step(double t, double h, double theta, const double* y, double* y_next,
                            double restitution) {
  const double excess = friction_excess_, play_rate = play_rate_;
  const std::vector<std::shared_ptr<const Element>>& elements = model_.elements().elements;
  for (std::size_t k = 0; k < elements.size(); ++k)
    step_modes_[k] = elements[k]->step_first(modes_at_start_[k]);
  bool restituting = take_step_held(t, h, theta, y, y_next, restitution);
  for (int retake = 0; retake < kMaxStepRetakes && !elements.empty(); ++retake) {
    layout_.expand(t, y, q_, v_);
    const CoordinateVector q0 = q_, v0 = v_;
    bool again = false;
    for (std::size_t k = 0; k < elements.size(); ++k) {
      ElementMode next;
      if (elements[k]->step_mode(element_step(k, t, h, theta, y, q0, v0), step_modes_[k], next)) {
        step_modes_[k] = next;
        again = true;
      }
    }
    if (!again) break;
    friction_excess_ = excess;  // (the step is taken again)
    play_rate_ = play_rate;
    restituting = take_step_held(t, h, theta, y, y_next, restitution);
  }
  for (std::size_t k = 0; k < elements.size(); ++k) dynamics_.element_mode(k) = step_modes_[k];
  return restituting;
}

ElementStep DriveMoreau::element_step(std::size_t k, double t, double h, double theta,
                                      const double* y, const CoordinateVector& q0,
                                      const CoordinateVector& v0) const {
  const int first = element_slots_[k].first;
  return {{t + theta * h, q0.data(), v0.data(), first >= 0 ? y + first : y}, h, theta};
}

bool DriveMoreau::take_step_held(double t, double h, double theta, const double* y,
                                 double* y_next, double restitution) {
  StepState s;
  s.t = t, s.h = h, s.theta = theta, s.y = y;
  begin_step(s);
  plan_contacts(s, restitution);
  plan_stops(s);
  solve_step(s);
  finish_velocities(s);
  book_step(s, y_next);
  report_step(s);
  return s.restituting;
}


// The step's impulses with the rotor's friction contact: the thread's
// contact solved (solve_thread) for each mode of the rotor's contact in
// turn, stick first (with the static efficiencies), then the slips (with
// the slip's, then, breaking away, the static ones), until one is
// consistent (RotorBalance::consistent). A mode whose thread problem has no
// consistent impulse is not the step's; where no mode is consistent the
// first mode's failure, or a JammingError, is raised.
DriveMoreau::Impulses DriveMoreau::solve_train(double t, double h, double theta,
                                               const CoordinateVector& v0, double normal_target,
                                               double rotor_target, int sigma_fixed,
                                               const moreau_contacts::RotorBalance& balance,
                                               bool contact_at_start, bool& contact, bool& stick,
                                               moreau_contacts::RotorMode& mode) {
  if (p_.speed_controlled)  // (the motion is prescribed: the frictions follow it)
    return solve_speed_train(t, h, theta, v0, normal_target, rotor_target, sigma_fixed,
                             contact_at_start, contact, stick, mode);
  const elements::TrainFriction& train = *model_.train_friction();
  const int r = model_.rotor();
  std::string failure;
  if (contact_at_start && stops_fix_every_velocity()) {
    // The stop holds the rigid drive: the rotor's contact, as the thread's,
    // carries nothing (the rule, stop_holds); its stick mode.
    rotor_row_ = false;
    contact = true;
    Impulses impulses =
        solve_thread(t, h, theta, v0, normal_target, rotor_target, sigma_fixed, contact, stick);
    impulses.train = 0.0;
    mode = moreau_contacts::kRotorModes[0];
    return impulses;
  }
  for (const moreau_contacts::RotorMode& candidate : moreau_contacts::kRotorModes) {
    if (!train.stage && candidate.flow < 0) continue;  // (one slip per sign without a stage)
    rotor_row_ = true;
    rotor_ = balance.row(train, candidate);
    Impulses impulses;
    try {
      contact = contact_at_start;
      stick = false;
      if (contact)
        impulses = solve_thread(t, h, theta, v0, normal_target, rotor_target, sigma_fixed,
                                contact, stick);
      if (!contact) impulses = solve(false, 0.0, rotor_target, 0.0);
    } catch (const SimulationError& e) {  // (JammingError too)
      if (failure.empty()) failure = e.what();
      continue;
    }
    const double other = std::abs(impulses.normal * model_.normal_direction()[r]) +
                         std::abs(impulses.friction * model_.tangent_direction()[r]);
    if (balance.consistent(train, candidate, impulses.velocity[r], impulses.train, other)) {
      mode = candidate;
      rotor_row_ = false;
      return impulses;
    }
  }
  rotor_row_ = false;
  // (No combination of stick and slip of the rotor's friction, the stage's
  // power flow and the thread's contact is consistent over the step.)
  throw JammingError(t, "the motor's friction and the gear stage admit no consistent "
                        "stick/slip state with the thread's friction over the step of " +
                            format_value(h) +
                            " s: the step is too long to resolve the stall or breakaway" +
                            (failure.empty() ? std::string() : "; " + failure),
                     "shorten dt (or reduce the friction)");
}

// The end stops' active sets from the step's result (impulses, at free_):
// an engaged penalty stop whose force over the step would pull is released
// (for the rest of the step), a free one the step carries into its face
// engaged; an active exact stop whose impulse would pull is released.
// True where a set changed.
bool DriveMoreau::update_stops(double h, double theta, const CoordinateVector& v0,
                               const Impulses& impulses, bool* released) {
  const int load = model_.load();
  const double u0 = q_[load];
  const double du_theta = (1.0 - theta) * v0[load] + theta * impulses.velocity[load];
  bool changed = false;
  const std::vector<elements::EndStop>& stops = model_.elements().end_stops();
  for (std::size_t k = 0; k < stops.size(); ++k) {
    const elements::EndStop& stop = stops[k];
    const double d0 = stop.penetration(u0), rate = stop.side * du_theta;
    const double force = moreau_contacts::penalty_stop_force(stop, u0, du_theta, h, theta);
    if (engaged_[k] && !(force > 0.0)) {
      engaged_[k] = false;
      released[k] = true;
      changed = true;
    } else if (!engaged_[k] && !released[k] && d0 + h * rate > 0.0 && force > 0.0) {
      engaged_[k] = true;
      changed = true;
    }
  }
  const std::vector<elements::ExactEndStop>& exact = model_.elements().exact_stops;
  for (std::size_t k = 0; k < exact.size(); ++k)
    if (stop_active_[k] && impulses.stop[k] < 0.0) {
      stop_active_[k] = false;
      changed = true;
    }
  return changed;
}

// The thread's contact and friction impulses of the step at free_ (the flank
// LCP on the velocity level, two-step stick, implicit viscous term).
DriveMoreau::Impulses DriveMoreau::solve_thread(double t, double h, double theta,
                                                const CoordinateVector& v0, double normal_target,
                                                double rotor_target, int sigma_fixed,
                                                bool& contact, bool& stick) {
  stick = false;
  // A preloaded nut that lifts off: its halves' modes (moreau_lift_off.cpp).
  if (lift_off_) {
    contact = true;
    return solve_lift_off_thread(t, h, theta, v0, normal_target, rotor_target, stick);
  }
  // (A penalty flank: no constraint row, its normal impulse the force's.)
  const bool row = !model_.thread_pair().penalty();
  const Impulses without = solve(row, normal_target, rotor_target, 0.0);
  // An exact stop's row and the thread's fix every velocity (the rigid
  // drive at its stop): the stop's impulse and the thread's friction
  // impulse are one unknown too many. The rule (end_stops.md, "The rigid
  // drive at a closed stop"): the stop carries what it can, the friction
  // nothing; where the stop's impulse pulls, stop_changes releases it and
  // the thread's LCP decides the step again without it.
  const Impulses unit = solve(row, normal_target, rotor_target, 1.0);
  if (row && p_.speed_controlled && stops_fix_every_velocity() &&
      2 >= model_.coordinate_count())
    throw SimulationError(t, "the rotor's prescribed speed drives the load, rigid in the "
                             "thread, into its exact end stop: the speed and the rigid stop "
                             "both fix the drive's one degree of freedom, an infinite impulse",
                          "use a drive torque or a DC motor, end_stops.contact = \"penalty\" "
                          "(its stiffness bounds the force), or a flexible concept");
  // A transverse slip's w at the step's end and its cone's coefficient at
  // the step's start slip speed (the stop's hold and the smooth step take them).
  if (transverse_state_ >= 0) {
    transverse_next_ = p_.transverse_slip_velocity(t + h);
    transverse_mu_ = dynamics_.cone_mu(std::hypot(model_.tangent_direction().dot(v0),
                                                  p_.transverse_slip_velocity(t)));
  }
  if (row && stops_fix_every_velocity()) {
    if (dynamics_.law().resolution() != friction::Resolution::bristle)
      return stop_holds(without, unit, normal_target, rotor_target, stick);
    return bristles_at_held_stop(t, h, theta, v0, normal_target, rotor_target, sigma_fixed,
                                 without, unit, contact, stick);
  }
  const double c = lane_dot(model_.tangent_direction(), without.velocity);
  const double d = lane_dot(model_.tangent_direction(), unit.velocity) - c;
  const double beta = row ? without.normal : flank_impulse(h, theta, v0, without.velocity);
  const double alpha = (row ? unit.normal : flank_impulse(h, theta, v0, unit.velocity)) - beta;
  const friction::Law& law = dynamics_.law();
  // A transverse slip's cone: where w+ != 0 the helix friction is smooth
  // in the slip (no stick), the exact cone's root (moreau_smooth_friction.cpp);
  // where w+ = 0 the 1-D Coulomb step below.
  if (law.resolution() != friction::Resolution::set_valued ||
      (transverse_state_ >= 0 && transverse_next_ != 0.0))  // (no stick: a smooth law)
    return solve_smooth_thread(t, h, theta, v0, normal_target, rotor_target, sigma_fixed, c, d,
                               alpha, beta, contact);
  return solve_coulomb_thread(t, h, theta, v0, normal_target, rotor_target, sigma_fixed, row,
                              without, unit, {c, d, alpha, beta}, contact, stick);
}

// The set-valued (Coulomb) step of the thread: the implicit viscous term's
// scaling of the flank LCP, the slip a constraint prescribes, a preloaded
// nut's halves, else the flank's friction impulse (coulomb_flank_impulse)
// and the step's impulses at it (coulomb_step_impulses).
DriveMoreau::Impulses DriveMoreau::solve_coulomb_thread(
    double t, double h, double theta, const CoordinateVector& v0, double normal_target,
    double rotor_target, int sigma_fixed, bool row, const Impulses& without,
    const Impulses& unit, FlankMaps maps, bool& contact, bool& stick) {
  double& c = maps.c;
  double& d = maps.d;
  double& alpha = maps.alpha;
  double& beta = maps.beta;
  const friction::Law& law = dynamics_.law();
  // The law's viscous term, implicit: P_T = P_C - h viscous gamma+ with
  // P_C in the cone. With gamma+ = c + d P_T and the normal impulse
  // beta + alpha P_T, P_C solves the flank LCP of c, d, beta, alpha
  // scaled by s = 1 / (1 + h viscous d) (beta less alpha h viscous c s);
  // a stuck step (gamma+ = 0) has no viscous impulse.
  const double viscous_step = law.viscous() * h;
  const double viscous_scale = 1.0 / (1.0 + viscous_step * d);
  const double viscous_c = c;
  if (viscous_step > 0.0) {
    beta -= alpha * viscous_step * c * viscous_scale;
    c *= viscous_scale;
    d *= viscous_scale;
    alpha *= viscous_scale;
  }
  // The normal impulse with the cone's part of the friction zero (and the
  // viscous impulse on): a penalty flank pushes where sigma beta > 0 here.
  // (Taken before the viscous shift, a flank entered within the step, beta
  // of 1e-10 N s, counted as pushing where the shift had made it pull, and
  // the step was refused at every dt.)
  const double pushing = beta;
  if (model_.effective_max_mu() * std::abs(alpha) >= 1.0 && !dynamics_.painleve_possible())
    throw SimulationError(t,
                          "dt = " + format_value(h) + " s is too long for the stiffness of "
                          "this drive here: " + step_too_long(theta, alpha),
                          "use dt < " + format_value(resolving_step(h, theta)) + " s");
  const SlipPrescription slip = slip_prescription(row, without, unit);
  // A preloaded nut (without lift-off: the thread's row): its halves' cone
  // (moreau_preload.cpp).
  // (Stribeck's curve: the halves slip at the law's coefficient at the
  // step's start speed, as the plain thread's; the viscous impulse on top.)
  if (const elements::PreloadedNut* nut = model_.preloaded_nut(); nut && row) {
    const bool curve = law.slip_mu(0.0) != law.mu() || law.slip_mu(1.0) != law.mu();
    const elements::PreloadedNut slipping =
        curve ? nut->with_mu(law.slip_mu(std::abs(model_.tangent_direction().dot(v0))) *
                             model_.flank_factor())
              : *nut;
    return solve_preloaded_thread(slipping, t, h, c, d, alpha, beta, slip.prescribed,
                                  std::abs(c) <= slip.noise, slip.motor0, slip.motor1,
                                  normal_target, rotor_target,
                                  {viscous_step, viscous_c, viscous_scale}, stick);
  }
  friction::FlankLcpResult chosen;
  int found = coulomb_flank_impulse(v0, maps, sigma_fixed, row, slip, chosen);
  // The viscous impulse on top of the cone's (zero where stuck).
  if (viscous_step > 0.0 && found > 0)
    chosen.friction_force = (chosen.friction_force - viscous_step * viscous_c) * viscous_scale;
  return coulomb_step_impulses(t, h, theta, v0, normal_target, rotor_target, sigma_fixed, row,
                               found, chosen, pushing, contact, stick);
}

// The motor (DriveDynamics::slip_prescribed) or the rotor's stuck
// contact (below) prescribes every velocity: the step's slip velocity c
// decides, friction cannot change it.
// The rotor's friction row where it fixes the rotor's speed (a stuck
// rotor; a stage of eta_b = 0 back-driven) may, with the thread's and the
// stops' rows, fix every velocity (the rigid drive without play): the
// slip is prescribed then, as by a speed-controlled motor, and of the
// friction impulses the thread's cone admits the one is taken that leaves
// the rotor's contact the least |Q| (the split between serial friction
// contacts that stick together is statically indeterminate).
DriveMoreau::SlipPrescription DriveMoreau::slip_prescription(bool row, const Impulses& without,
                                                             const Impulses& unit) const {
  SlipPrescription slip;
  int fixed = (row ? 1 : 0) + (p_.speed_controlled ? 1 : 0) +
              (rotor_row_ && rotor_.fixes_speed() ? 1 : 0);
  for (int k = 0; k < kMaxStops; ++k) fixed += stop_active_[k] ? 1 : 0;
  slip.rotor_prescribes = rotor_row_ && rotor_.fixes_speed() &&
                          fixed >= model_.coordinate_count();
  // (A penalty flank is no constraint: it prescribes no slip.)
  slip.prescribed = (row && dynamics_.slip_prescribed()) || slip.rotor_prescribes;
  // (c's round-off: of the velocities, and where the rotor's contact holds
  // a drive at rest, of the loads' velocity increments h f / m, free_.)
  slip.noise =
      64.0 * std::numeric_limits<double>::epsilon() *
      (lane_abs_dot(model_.tangent_direction(), without.velocity) +
       (slip.rotor_prescribes ? lane_abs_dot(model_.tangent_direction(), free_) : 0.0));
  slip.motor0 = slip.rotor_prescribes ? without.train : without.rotor;
  slip.motor1 =
      slip.rotor_prescribes ? unit.train - without.train : unit.rotor - without.rotor;
  return slip;
}

// The flank's friction impulse of a Coulomb step (the cone's part; chosen)
// and how many are consistent (found; 0: none). One coefficient: the LCP
// decides stick and slip. A static one above the kinetic one: stick where
// the impulse that sticks lies in mu_static''s cone, else the LCP at the
// slip's coefficient at the step's start speed (Stribeck's curve, explicit
// in the speed). (In the Painleve regime the LCP may find no impulse where
// the stick holds: a stick that is admissible is taken then too.)
int DriveMoreau::coulomb_flank_impulse(const CoordinateVector& v0, const FlankMaps& maps,
                                       int sigma_fixed, bool row, const SlipPrescription& slip,
                                       friction::FlankLcpResult& chosen) {
  const double c = maps.c, d = maps.d, alpha = maps.alpha, beta = maps.beta;
  const friction::Law& law = dynamics_.law();
  // The flank's sign, or both (no allocation: this runs every step).
  const int sigmas[2] = {sigma_fixed != 0 ? sigma_fixed : 1, -1};
  const int sigma_count = sigma_fixed != 0 ? 1 : 2;
  int found = 0;
  double lcp_mu = model_.effective_mu();
  const friction::FlankLcpResult stick_step =
      slip.prescribed
          ? friction::FlankLcpResult{}
          : friction::flank_stick(c, d, alpha, beta, model_.effective_mu_static(), sigma_fixed);
  bool stuck = false;
  if (!dynamics_.plain_coulomb()) {
    if (stick_step.consistent) {
      chosen = stick_step;
      stuck = true;
      found = 1;
    }
    lcp_mu = law.slip_mu(std::abs(model_.tangent_direction().dot(v0))) * model_.flank_factor();
  }
  for (int k = 0; k < sigma_count && !stuck; ++k) {
    const friction::FlankLcpResult r =
        slip.prescribed
            ? friction::solve_flank_prescribed_slip(
                  c, std::abs(c) <= slip.noise, alpha, beta,
                  // (held by the rotor's stuck contact at zero slip: the
                  // static cone, as the train's static test)
                  slip.rotor_prescribes && std::abs(c) <= slip.noise
                      ? model_.effective_mu_static()
                      : lcp_mu,
                  sigmas[k], slip.motor0, slip.motor1)
            : solve_flank_lcp_scaled(c, d, alpha, beta, lcp_mu, sigmas[k], lcp_workspace_,
                                     lcp_options_);
    ++lcp_solves_;
    if (!r.consistent) continue;
    if (found == 0) chosen = r;
    ++found;
  }
  if (found == 0 && stick_step.consistent) {
    chosen = stick_step;
    found = 1;
  }
  // A penalty flank's slip at the cone's edge (docs/physics/drive_models.md,
  // "Moreau-Jean on penalty flanks"): where the LCP has none, and in place
  // of the LCP's, whose values carry its tolerance relative to |c / d| (a
  // flank force of round-off size, 7e-18 N s against 26 N s, slipped with
  // its friction outside the cone and along the slip).
  if (!row && !slip.prescribed && (found == 0 || chosen.slip_acceleration != 0.0)) {
    const friction::FlankLcpResult edge =
        moreau_contacts::penalty_flank_slip(c, d, alpha, beta, lcp_mu, sigma_fixed);
    if (edge.consistent) chosen = edge, found = std::max(found, 1);
  }
  return found;
}

// The step's impulses at the flank's friction impulse chosen (found of
// them consistent): the flank separates, the drive jams, a pushing penalty
// flank without a consistent friction impulse is refused, or the step's
// impulses with the friction impulse given.
DriveMoreau::Impulses DriveMoreau::coulomb_step_impulses(
    double t, double h, double theta, const CoordinateVector& v0, double normal_target,
    double rotor_target, int sigma_fixed, bool row, int found,
    const friction::FlankLcpResult& chosen, double pushing, bool& contact, bool& stick) {
  Impulses impulses;
  if (found == 0 && !row && sigma_fixed * pushing >= 0.0 && pushing != 0.0) {
    // (A penalty flank whose force pushes carries its friction: no
    // consistent impulse is no separation. With the viscous term the
    // scaled c, d, alpha, beta are the flank LCP's again (s > 0), so the
    // slip above finds one wherever sigma beta > 0 and d > 0; reached where
    // the rotor's stuck contact prescribes the slip, whose rotor mode is
    // then not the step's: solve_train tries the next.)
    throw SimulationError(t, "no friction impulse of the Moreau-Jean step is consistent with "
                             "the penalty flank's normal impulse " + format_value(pushing) +
                             " N s (dt = " + format_value(h) + " s)",
                          "shorten dt");
  } else if (found == 0 && sigma_fixed != 0) {
    contact = false;  // the flank separates (a penalty flank: its force pulls, released)
  } else if (found == 0) {
    throw JammingError(t, "dynamic jamming: no consistent flank impulse in the "
                          "Moreau-Jean step; " + dynamics_.jamming_report(),
                       "reduce the friction or change the inertia ratio");
  } else {
    impulses = solve(row, normal_target, rotor_target, chosen.friction_force);
    if (!row) impulses.normal = flank_impulse(h, theta, v0, impulses.velocity);
    impulses.friction = chosen.friction_force;
    stick = chosen.slip_acceleration == 0.0;
  }
  return impulses;
}

// The energy a step from y to y_next creates (StepAccount).
DriveMoreau::StepAccount DriveMoreau::energy_created(double t, double h, const double* y,
                                                      const double* y_next) {
  double largest = 0.0;
  const std::vector<std::shared_ptr<const Element>>& elements = model_.elements().elements;
  auto account = [&](double time, const double* state) {
    layout_.expand(time, state, q_, v_);
    dynamics_.set_element_states(state);
    dynamics_.set_state(time, q_, v_);
    const double* energy = state + layout_.energy_offset();
    double stored =
        dynamics_.kinetic_energy() + dynamics_.elastic_energy() + dynamics_.contact_energy();
    // (an element's stored energy, and its losses among the losses: a DC
    // motor's magnetic energy and copper loss)
    for (std::size_t k = 0; k < elements.size(); ++k)
      stored += elements[k]->energy_terms(dynamics_.element_state(k));
    for (const int k : {motor_friction_state_, gear_state_})
      if (k >= 0) stored += state[k];  // (the train's losses, with the losses)
    if (bristle_state_ >= 0) stored += state[bristle_state_ + 1];  // (LuGre's bristles)
    if (transverse_state_ >= 0) stored -= state[transverse_state_];  // (the cone's work)
    double balance = stored;
    largest = std::max(largest, std::abs(stored));
    for (int e = 0; e < kEnergyCount; ++e) {
      balance += (e == kWorkDrive || e == kWorkAxial) ? -energy[e] : energy[e];
      largest = std::max(largest, std::abs(energy[e]));
    }
    return balance;
  };
  const double before = account(t, y);
  const double after = account(t + h, y_next);
  return {after - before, 64.0 * std::numeric_limits<double>::epsilon() * largest};
}

void DriveMoreau::channels(double t, const double* y, double* out) {
  layout_.expand(t, y, q_, v_);
  dynamics_.set_element_states(y);
  dynamics_.set_state(t, q_, v_);
  const double* energy = y + layout_.energy_offset();
  // The Moreau-Jean scheme's numerical dissipation (and impacts) closes the
  // account: what the work and the named losses leave over.
  ChannelState state = channel_state(dynamics_);
  if (last_.stick) state.slip_velocity = 0.0;  // the step's stick: zero slip (as above)
  // LuGre's: the slip of the step's friction and bristles (bristle_slip)
  if (!std::isnan(last_law_slip_)) state.slip_velocity = last_law_slip_;
  // The exact stops' force over the last step (the penalty stops' is added
  // from the row's coordinates: hybrid_end_stops.cpp's declaration).
  if (stop_channel_ >= 0) state.values[stop_channel_] = last_stop_force_;
  if (motor_friction_state_ >= 0) state.values[motor_friction_channel_] = y[motor_friction_state_];
  if (gear_state_ >= 0) state.values[gear_channel_] = y[gear_state_];
  if (bristle_state_ >= 0) {  // LuGre's deflection and the energy its bristles store
    state.values[bristle_channel_] = y[bristle_state_] * bristle_range_;
    state.elastic += y[bristle_state_ + 1];
    if (transverse_state_ >= 0)
      state.values[bristle_channel_ + 1] = y[bristle_state_ + 2] * bristle_range_;
  }
  if (preload_channel_ >= 0) {  // (a preloaded nut: a smooth law or lift-off, the last step's)
    const elements::PreloadedNut& nut = *model_.preloaded_nut();
    const double normal_a = last_.normal - last_.preload_normal;
    state.values[preload_channel_] = lift_off_ ? dynamics_.preload_spring_force() : nut.preload;
    state.values[preload_channel_ + 1] = normal_a;
    // (stuck with lift-off: half B at the edge the friction heads for, at
    // mu_static', as the event-driven scheme's)
    state.values[preload_channel_ + 2] =
        lift_off_ && last_.stick
            ? nut.sticking().split_flank_normal(normal_a, half_b_spring_, last_.friction)
        : last_.stick ? nut.sticking().flank_normal(last_.normal, last_.friction)
                      : std::abs(normal_a) + std::abs(last_.preload_normal);
  }
  if (transverse_state_ >= 0)
    write_transverse_channels(layout_, dynamics_, last_transverse_, y, state);
  double applied = dynamics_.applied_torque();
  // The elements' channels, of the last step (a DC motor's armature), and
  // their torque on the rotor (Element::step_output, step_drive_torque).
  const std::vector<std::shared_ptr<const Element>>& elements = model_.elements().elements;
  if (!elements.empty()) {
    double element_torque = 0.0;
    for (std::size_t k = 0; k < elements.size(); ++k) {
      const ElementState s = dynamics_.element_state(k);
      const ElementMode& mode = dynamics_.element_mode(k);
      if (element_channels_[k] >= 0)
        elements[k]->step_output(s, mode, state.values.data() + element_channels_[k]);
      element_torque += elements[k]->step_drive_torque(s, mode);
    }
    applied = model_.motor().applied_torque(t) + element_torque;
  }
  // drive_torque, the rotor's: a torque-driven rotor's prescribed torque
  // and a DC motor's k_t i of the row's current, as the event-driven scheme
  // reports them (issue 31: the step's impulse over h is not the motor's
  // torque; the step's work stays its impulse's, booked in step()).
  ContactForces forces = last_;
  if (!p_.speed_controlled) forces.motor_torque = model_.gear().rotor_torque(applied);
  write_drive_channels(layout_, state, forces, energy, 0.0, kinetic0_, stored0_, out);
}

// The iteration matrix W = M + theta h C + theta^2 h^2 K at the positions
// q_ (iteration_: factorized where it changed), and its stiffness and
// damping matrices.
void DriveMoreau::assemble(double h, double theta, Square& stiffness, Square& damping,
                           bool elements) {
  const int n = model_.coordinate_count();
  stiffness = Square::Zero(n, n);
  damping = Square::Zero(n, n);
  const double a = model_.nut_position(q_.data());
  model_.elements().forces.for_each([&](const auto& element) {
    element.add_stiffness(stiffness, a);
    element.add_damping(damping);
  });
  // The penalty stops this step engages (their k and c; zero otherwise).
  const std::vector<elements::EndStop>& stops = model_.elements().end_stops();
  for (std::size_t k = 0; k < stops.size(); ++k)
    if (engaged_[k]) {
      stiffness(stops[k].coordinate, stops[k].coordinate) += stops[k].stiffness;
      damping(stops[k].coordinate, stops[k].coordinate) += stops[k].damping;
    }
  // theta h C + theta^2 h^2 K + M entry by entry, as Eigen's expression
  // (theta * h * damping + theta * theta * h * h * stiffness, then the
  // diagonal) rounds it, without its runtime-sized evaluation.
  const double damping_factor = theta * h, stiffness_factor = theta * theta * h * h;
  Square iteration(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      iteration(i, j) = damping_factor * damping(i, j) + stiffness_factor * stiffness(i, j);
  const Eigen::VectorXd& mass = model_.mass();
  for (int i = 0; i < n; ++i) iteration(i, i) += mass[i];
  if (elements && !model_.elements().elements.empty()) iteration.diagonal() -= element_slope_;
  iteration_.set(iteration, flank_coefficient(h, theta));
}

// v+ = free + W^-1 (B lambda + tangential W_T) with the active velocity
// constraints: W_N v+ = normal_target (thread), e_rotor v+ = rotor_target.
DriveMoreau::Impulses DriveMoreau::solve(bool thread, double normal_target, double rotor_target,
                                         double tangential) {
  constexpr int kRows = 3 + kMaxStops;
  const int n = model_.coordinate_count();
  const std::vector<elements::ExactEndStop>& exact = model_.elements().exact_stops;
  int nc = (thread ? 1 : 0) + (p_.speed_controlled ? 1 : 0) + (rotor_row_ ? 1 : 0);
  for (std::size_t k = 0; k < exact.size(); ++k) nc += stop_active_[k] ? 1 : 0;
  Impulses out;
  if (nc == 0) {  // (no constraint row: the free velocity and the friction impulse's part;
                  // a penalty flank's step, three times a pass)
    out.velocity = free_;
    if (tangential != 0.0) out.velocity += tangential * iteration_.tangent_solve();
    return out;
  }
  Columns B = Columns::Zero(n, nc);
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kRows, 1> r(nc);
  int row = 0;
  if (thread) {
    B.col(row) = model_.normal_direction();
    r[row++] = normal_target;
  }
  if (p_.speed_controlled) {
    B(model_.rotor(), row) = 1.0;
    r[row++] = rotor_target;
  }
  // An active exact stop: its impulse P pushes the load off the face
  // (-side along u), its row -side u'+ = its target.
  for (std::size_t k = 0; k < exact.size(); ++k)
    if (stop_active_[k]) {
      B(exact[k].coordinate, row) = -exact[k].side;
      r[row++] = stop_target_[k];
    }
  // The rotor's friction contact: Q on -e_rotor, its row a_w w+ + a_q Q = r
  // (moreau_contacts::RotorRow), the last.
  if (rotor_row_) {
    B(model_.rotor(), row) = -1.0;
    r[row++] = rotor_.r;
  }
  CoordinateVector base = free_;
  if (tangential != 0.0) {
    base += tangential * iteration_.tangent_solve();
  }
  const Columns weighted = iteration_.solve(B);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kRows, kRows> schur =
      B.transpose() * weighted;
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kRows, 1> residual = r - B.transpose() * base;
  if (rotor_row_) {  // (its row is a_w w+ + a_q Q = r, not -w+ = r)
    const int last = nc - 1;
    schur.row(last) *= -rotor_.a_w;
    schur(last, last) += rotor_.a_q;
    residual[last] = rotor_.r - rotor_.a_w * base[model_.rotor()];
  }
  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kRows, 1> lambda =
      schur.fullPivLu().solve(residual);
  out.velocity = base + weighted * lambda;
  row = 0;
  if (thread) out.normal = lambda[row++];
  if (p_.speed_controlled) out.rotor = lambda[row++];
  for (std::size_t k = 0; k < exact.size(); ++k)
    if (stop_active_[k]) out.stop[k] = lambda[row++];
  if (rotor_row_) out.train = lambda[row++];
  return out;
}

}  // namespace leadscrew::model::drive
