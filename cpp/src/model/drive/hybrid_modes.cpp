// DriveHybrid (hybrid.hpp): the current mode's accelerations and forces (the
// consistent sign of the normal force), and the choice of stick or slip at
// zero slip by the flank LCP and the two-step stick test (mu_static).
#include "hybrid.hpp"

#include "leadscrew/core/errors.hpp"
#include "leadscrew/friction/flank_lcp.hpp"
#include "mode_solver.hpp"

namespace leadscrew::model::drive {

// Accelerations and forces in the current mode; for the thread without
// play the sign of the normal force is the one consistent with it (the
// thesis's y+/y- procedure, section 4.3, done exactly).
ModeSolution DriveHybrid::solve_current() {
  if (mode_.friction == FrictionMode::stick && mode_.half_b_edge != 0) half_b_edge_share();
  const bool friction_on_normal = mode_.friction == FrictionMode::slip ||
                                  mode_.friction == FrictionMode::regularized_velocity ||
                                  mode_.friction == FrictionMode::regularized_acceleration ||
                                  mode_.friction == FrictionMode::bristle;
  if (mode_.contact == ThreadContact::bilateral &&
      mode_.friction == FrictionMode::regularized_acceleration && dynamics_.painleve_possible()) {
    // Eq. (3.15): every consistent flank force at once (DriveDynamics::
    // solve_acceleration_law); there is always one, several are jamming.
    const ModeSolution s = dynamics_.solve(spec(sigma_guess_));
    if (!s.regular)
      throw SimulationError(dynamics_.time(), "the constraint equations of the drive are singular",
                            "check masses, inertias and the thread geometry");
    if (s.consistent_solutions != 1) jam_acceleration_law(s.consistent_solutions);
    if (s.normal_force != 0.0) sigma_guess_ = sign_of(s.normal_force);
    last_unique_time_ = std::max(last_unique_time_, dynamics_.time());
    return s;
  }
  // (The rotor's friction contact changes the rotor's inertia on the
  // thread, a self-locking stage's to a negative one: its own test.)
  const bool painleve = rotor_train_ ? rotor_painleve_possible() : dynamics_.painleve_possible();
  if (mode_.contact == ThreadContact::bilateral && friction_on_normal && !painleve) {
    // At most one sign can be consistent: try the last one first.
    for (int attempt = 0; attempt < 2; ++attempt) {
      const ModeSolution s = dynamics_.solve(spec(sigma_guess_));
      if (s.regular && sigma_guess_ * s.loaded_normal() >= 0.0) return s;
      sigma_guess_ = -sigma_guess_;
    }
    jam("no sign of the flank normal force is consistent");
  }
  if (mode_.contact == ThreadContact::bilateral && friction_on_normal) {
    const ModeSolution plus = dynamics_.solve(spec(1));
    const ModeSolution minus = dynamics_.solve(spec(-1));
    const bool plus_ok = plus.regular && plus.loaded_normal() >= 0.0;
    const bool minus_ok = minus.regular && minus.loaded_normal() <= 0.0;
    if (watch_fold()) {
      // The paradox of the regularized law is located by its roots (the
      // margin, the branch's denominator; approach_fold). Between them keep
      // the current sign's branch: where both are consistent it is the
      // continuous one, and where neither is (a trial state of the
      // integrator beyond the onset) its continuation, so that the step is
      // rejected, not the simulation ended at a state off the trajectory.
      const ModeSolution& current = sigma_guess_ > 0 ? plus : minus;
      const bool current_ok = sigma_guess_ > 0 ? plus_ok : minus_ok;
      const bool other_ok = sigma_guess_ > 0 ? minus_ok : plus_ok;
      if (current_ok || (!other_ok && current.regular)) return current;
      if (other_ok) {
        sigma_guess_ = -sigma_guess_;
        return sigma_guess_ > 0 ? plus : minus;
      }
      jam("the constraint equations of the thread are singular");
    }
    if (plus_ok && minus_ok) {
      if (plus.loaded_normal() == 0.0) return plus;
      if (minus.loaded_normal() == 0.0) return minus;
      jam("both signs of the flank normal force are consistent");
    }
    if (plus_ok) return plus;
    if (minus_ok) return minus;
    jam("no sign of the flank normal force is consistent");
  }
  const ModeSolution s = dynamics_.solve(spec(1));
  if (!s.regular)
    throw SimulationError(dynamics_.time(), "the constraint equations of the drive are singular",
                          "check masses, inertias and the thread geometry");
  return s;
}

// A closed flank's solve takes its friction on the flank's own side,
// -kappa flank N: the law's -kappa |N| while the flank pushes (flank N >=
// 0). Where it pulls, the mode is ending, and -kappa flank N turns the
// friction the wrong way (LuGre's bristle force against the bristles'
// deflection, Coulomb's slip friction along the slip). The rhs keeps that
// branch past the opening root: it is the mode's smooth continuation, which
// CVODE's steps over the root and its interpolation back to it need (with
// the |N| branch in the rhs too, its kink inside such steps, a stuck seat
// adjuster's play drifted 1.5e-10 m against its 1e-10 m and a DC motor's
// flexible drive closed its energy account to twice its 1e-7). A row is
// no trial state: at the flank's opening (its root, or a table's knot that
// jumps the normal force to the pulling sign at once; issue 31's fuzz
// cases 5638 and 7512) it reports the law, the other side's branch
// -kappa (-flank) N = -kappa |N|, solved whole (accelerations, motor
// torque) as the thread without play takes the consistent sign. Both
// branches agree at N = 0. Where that branch does not pull (a Painleve
// fold: no branch consistent) the flank's own is kept; the flank opens.
ModeSolution DriveHybrid::on_the_law(const ModeSolution& own) {
  const bool kinetic = mode_.friction == FrictionMode::slip ||
                       mode_.friction == FrictionMode::regularized_velocity ||
                       mode_.friction == FrictionMode::regularized_acceleration ||
                       mode_.friction == FrictionMode::bristle;
  if (mode_.contact != ThreadContact::closed || !kinetic || !own.regular ||
      !(mode_.flank * own.loaded_normal() < 0.0))
    return own;
  ModeSpec other = spec(1);
  other.sigma = -mode_.flank;
  const ModeSolution pulled = dynamics_.solve(other);
  return pulled.regular && mode_.flank * pulled.loaded_normal() <= 0.0 ? pulled : own;
}

// A flank closed by an impact (or a grazing touch) whose normal force would
// pull opens at once: the contact is unilateral, as a closed flank opens
// where its normal force falls through zero (the root g[1] cannot see a
// force that starts on the wrong side). Solves the current mode.
void DriveHybrid::open_if_pulling() {
  const ModeSolution s = solve_current();
  if (mode_.contact != ThreadContact::closed || mode_.flank * s.normal_force >= 0.0) return;
  mode_.contact = ThreadContact::open;
  mode_.friction = FrictionMode::none;
  mode_.slip_sign = 0;
}

// Stick or slip: from the slip velocity, or at zero slip by the flank LCP.
void DriveHybrid::decide_friction(double t, double* y, bool at_zero_slip, int hint) {
  (void)t;
  mode_.half_b_edge = 0;  // (stick_at_half_b_edge sets it)
  if (train_) {
    decide_train(t, y, at_zero_slip, hint);
    return;
  }
  const friction::Resolution resolution = dynamics_.law().resolution();
  // A transverse slip's cone (transverse_slip.cpp): the helix friction
  // mu' gamma / |(gamma, w)| is a smooth function of the slip, a velocity
  // law's factor (DriveDynamics::cone_coefficient); the event-driven scheme
  // takes w held at zero nowhere with it (check_transverse_slip). LuGre's
  // bristles stay the bristle mode (2-D: DriveDynamics::bristle_rate).
  const bool regularized =
      resolution != friction::Resolution::set_valued || dynamics_.transverse();
  // A regularized law's friction on a penalty flank follows its penetration
  // (zero where it has none): no contact mode to track.
  // (A lift-off nut's half B bears on its flank in open play too: friction.)
  const elements::PreloadedNut* lift_off = model_.preloaded_nut();
  if (lift_off && !lift_off->lift_off) lift_off = nullptr;
  if (mode_.contact == ThreadContact::open || dynamics_.law().frictionless() ||
      (mode_.contact == ThreadContact::penalty && !touching_ && !regularized && !lift_off)) {
    // No contact (an open play, or a penalty flank not penetrated), or a
    // frictionless law (no coefficient, no viscous term): no stick, no
    // slip, no friction events.
    mode_.friction = FrictionMode::none;
    mode_.slip_sign = 0;
    open_if_pulling();
    return;
  }
  if (regularized) {
    // (A set-valued law's cone is the velocity law's factor; LuGre's
    // bristles stay bristles, 2-D on a transverse slip.)
    mode_.friction = resolution == friction::Resolution::velocity ||
                             resolution == friction::Resolution::set_valued
                         ? FrictionMode::regularized_velocity
                     : resolution == friction::Resolution::acceleration
                         ? FrictionMode::regularized_acceleration
                         : FrictionMode::bristle;
    open_if_pulling();
    return;
  }
  // A slip velocity at the level of its own round-off has no sign to take.
  if (!at_zero_slip && std::abs(dynamics_.slip_velocity()) > dynamics_.slip_noise()) {
    mode_.friction = FrictionMode::slip;
    mode_.slip_sign = sign_of(dynamics_.slip_velocity());
    open_if_pulling();  // raises JammingError if no normal-force sign is consistent
    return;
  }
  decide_at_zero_slip(t, y, hint, lift_off);
}

// Stick or slip at zero slip (a set-valued law on a bearing flank): a stop
// holding the rigid drive, the motor's prescribed slip, or the flank LCP at
// the velocities projected onto exactly zero slip.
void DriveHybrid::decide_at_zero_slip(double t, double* y, int hint,
                                      const elements::PreloadedNut* lift_off) {
  ModeSpec base = spec(1);
  base.friction = FrictionMode::none;
  if (held_load_ >= 0 && (mode_.contact == ThreadContact::bilateral ||
                          mode_.contact == ThreadContact::closed) &&
      2 + model_.motor().constraint_count() >= model_.coordinate_count()) {
    // A closed exact stop holds the rigid drive (its row and the thread's
    // fix every velocity): stuck, the stop carrying the loads and the
    // friction nothing (DriveDynamics::solve; end_stops.md, "The rigid
    // drive at a closed stop"). Its opening decides the thread anew.
    mode_.friction = FrictionMode::stick;
    mode_.slip_sign = 0;
    return;
  }
  if (slip_prescribed_now()) {
    decide_prescribed_slip(base);
    return;
  }
  // Zero slip: project the velocities onto exactly zero slip (the root is
  // located to round-off), then let the LCP decide.
  dynamics_.project_zero_slip(base, v_);
  layout_.compress(q_, v_, y);
  set(t, y);
  ModeSolution without = dynamics_.solve(base);
  base.given_tangential = 1.0;
  ModeSolution unit = dynamics_.solve(base);
  if (!without.regular || !unit.regular)
    throw SimulationError(t, "the constraint equations of the drive are singular",
                          "check masses, inertias and the thread geometry");
  // The slip acceleration c + d lambda_T and the normal force
  // beta + alpha lambda_T, affine in the tangential force.
  ZeroSlipLcp lcp;
  lcp.c = without.slip_acceleration;
  lcp.d = unit.slip_acceleration - lcp.c;
  lcp.beta = dynamics_.penalty_normal_force();
  // The normal-force signs to try: the penalty force's, the closed flank's, or both.
  if (mode_.contact == ThreadContact::penalty) {
    lcp.sigmas[0] = lcp.beta >= 0.0 ? 1 : -1;
    lcp.sigma_count = 1;
  } else {
    lcp.beta = without.normal_force;
    lcp.alpha = unit.normal_force - lcp.beta;
    if (mode_.contact == ThreadContact::closed) {
      lcp.sigmas[0] = mode_.flank;
      lcp.sigma_count = 1;
    }
  }
  // One coefficient: the thesis's LCP decides stick and slip at once. A
  // static coefficient above the kinetic one: stick wherever the force
  // that sticks lies in mu_static''s cone (its normal force on the
  // flank's side); otherwise the LCP at the slip's coefficient at zero
  // speed, mu(0+)', gives the slip's direction (no stick: it is not
  // admissible even with the larger coefficient).
  if (const elements::PreloadedNut* nut = model_.preloaded_nut())
    decide_preloaded_nut(*nut, lcp, hint, lift_off);
  else
    decide_flank_lcp(lcp, hint);
}

// The motor prescribes every velocity: its slip acceleration decides (no
// projection: the velocities are the motor's).
void DriveHybrid::decide_prescribed_slip(const ModeSpec& base) {
  const friction::FlankLcpResult r = dynamics_.prescribed_slip_decision(
      base, mode_.contact == ThreadContact::closed ? mode_.flank : 0);
  ++lcp_solves_;
  if (!r.consistent && mode_.contact == ThreadContact::closed) {
    mode_.contact = ThreadContact::open;  // the flank cannot push: it opens
    mode_.friction = FrictionMode::none;
    mode_.slip_sign = 0;
    return;
  }
  if (!r.consistent)
    jam("the prescribed motion needs a flank normal force of neither sign");
  mode_.friction = r.slip_acceleration == 0.0 ? FrictionMode::stick : FrictionMode::slip;
  mode_.slip_sign = sign_of(r.slip_acceleration);
}

// The preloaded nut: the LCP's decision by its three cases (its bound
// depends on the slip's direction; preloaded_nut.hpp). Lift-off: half A's
// normal force is the penalty flanks' (given), the edges constants. With
// mu_static above mu: stick where the element at mu_static' sticks (the
// two-step test), else the slip's direction at mu'.
void DriveHybrid::decide_preloaded_nut(const elements::PreloadedNut& nut, const ZeroSlipLcp& lcp,
                                       int hint, const elements::PreloadedNut* lift_off) {
  auto decide = [&](const elements::PreloadedNut& at) {
    return lift_off ? at.decide_split(lcp.c, lcp.d, dynamics_.penalty_normal_force(),
                                      dynamics_.preload_spring_force())
                    : at.decide(lcp.c, lcp.d, lcp.alpha, lcp.beta);
  };
  if (nut.two_coefficients() && hint == 0) {
    const friction::FlankLcpResult rest = decide(nut.sticking());
    ++lcp_solves_;
    if (rest.consistent && rest.slip_acceleration == 0.0) {
      mode_.friction = FrictionMode::stick;
      mode_.slip_sign = 0;
      return;
    }
  }
  // (The slip's direction at the law's coefficient at the slip's start:
  // mu' for Coulomb, Stribeck's mu(0+)'.)
  const friction::FlankLcpResult r =
      dynamics_.plain_coulomb() || dynamics_.law().slip_mu(0.0) == dynamics_.law().mu()
          ? decide(nut)
          : decide(nut.with_mu(dynamics_.law().slip_mu(0.0) * model_.flank_factor()));
  ++lcp_solves_;
  if (!r.consistent)
    jam(lift_off ? "the preloaded nut's friction has no slip acceleration to decide by"
                 : "the preloaded nut's friction has no unique edge (Painleve regime)");
  const int direction = sign_of(r.slip_acceleration);
  mode_.friction = direction == 0 && hint == 0 ? FrictionMode::stick : FrictionMode::slip;
  mode_.slip_sign = mode_.friction == FrictionMode::stick ? 0 : direction != 0 ? direction : hint;
  if (lift_off && mode_.friction == FrictionMode::slip) stick_at_half_b_edge();
}

// A lift-off nut leaving stick at the edge of slip s (decide_split: half B
// at its spring's force, side S / cos(a) W_N, its friction in the stick
// force) may find that slip, half B at its slip state N_B^s W_N + T_B^s W_T,
// slowing at once: half B's friction's axial part presses half A's flank
// harder. The event-driven scheme then chattered stick <-> slip s at one
// instant (drive-train fuzz cases 794, 7173, 7812 at f59bc15: 2,000 events
// within 1e-11 s). Stick leaves the split of its force between the halves
// indeterminate; Moreau-Jean (moreau_lift_off.cpp) takes half B at the
// edge where its spring's force does not stick. Here half B goes toward
// that edge by the share that holds the stick force at the cone's edge
// (half_b_edge_share): the limit of Moreau-Jean's steps alternating between
// the two, continuous in time. The stick ends at share 1 (slip s is
// consistent there, g0) or 0 (half B at its spring's force sticks, g1).
void DriveHybrid::stick_at_half_b_edge() {
  const int s = mode_.slip_sign;
  if (s * dynamics_.solve(spec(1)).slip_acceleration > 0.0) return;  // the slip is consistent
  mode_.friction = FrictionMode::stick;
  mode_.slip_sign = 0;
  mode_.half_b_edge = s;
  ++lcp_solves_;
  if (half_b_edge_share() >= 0.0) return;  // (its stick force at the edge state in the cone)
  mode_.friction = FrictionMode::slip;  // (no stick at the edge either: the slip, whose
  mode_.slip_sign = s;                  // check of half B's loss may fail)
  mode_.half_b_edge = 0;
}

// The share of the stick with half B toward slip s's edge (ModeSpec::
// half_b_share) at which its stick force, affine in the share, lies on the
// cone's edge s, E = -s b_s (half A's normal force and the spring's are the
// state's): (E - T_0) / (T_1 - T_0), between T_0 (half B at its spring's
// force) beyond the edge and T_1 (at its slip state) inside. Its roots
// without that quotient (which has a pole where the spring's force and
// half A's vanish): g0 = b_s + s T_1 (T_1 reaches the edge: slip s is
// consistent there) and g1 = -s T_0 - b_s (T_0 back inside). Stored in
// half_b_edge_ (the share unclamped); returns g0.
double DriveHybrid::half_b_edge_share() {
  const int s = mode_.half_b_edge;
  ModeSpec at = spec(1);
  at.half_b_share = 0.0;
  const double spring = dynamics_.solve(at).friction_force;
  at.half_b_share = 1.0;
  const double edge_state = dynamics_.solve(at).friction_force;
  const double bound = model_.preloaded_nut()->sticking().split_bound(
      s, dynamics_.penalty_normal_force(), dynamics_.preload_spring_force());
  half_b_edge_.share =
      edge_state != spring ? (-s * bound - spring) / (edge_state - spring) : 1.0;
  half_b_edge_.edge_margin = bound + s * edge_state;
  half_b_edge_.spring_margin = -s * spring - bound;
  return half_b_edge_.edge_margin;
}

// The thread's flank LCP at zero slip for each normal-force sign to try:
// the one consistent mode, else stick where it is admissible, the flank
// opening, or a jam.
void DriveHybrid::decide_flank_lcp(const ZeroSlipLcp& lcp, int hint) {
  const double c = lcp.c, d = lcp.d, alpha = lcp.alpha, beta = lcp.beta;
  const friction::Law& law = dynamics_.law();
  double lcp_mu = model_.effective_mu();
  const int stick_side = mode_.contact == ThreadContact::closed ? mode_.flank
                         : mode_.contact == ThreadContact::penalty ? lcp.sigmas[0]
                                                                   : 0;
  const bool stick_admissible =
      hint == 0 && friction::flank_stick(c, d, alpha, beta, stick_mu(), stick_side).consistent;
  if (!dynamics_.plain_coulomb()) {
    if (stick_admissible) {
      mode_.friction = FrictionMode::stick;
      mode_.slip_sign = 0;
      return;
    }
    lcp_mu = law.slip_mu(0.0) * model_.flank_factor();
  }
  int found = 0;
  bool ambiguous = false;
  Mode chosen = mode_;
  for (int k = 0; k < lcp.sigma_count; ++k) {
    const friction::FlankLcpResult r =
        solve_flank_lcp_scaled(c, d, alpha, beta, lcp_mu, lcp.sigmas[k], lcp_workspace_,
                               lcp_options_);
    ++lcp_solves_;
    if (!r.consistent) continue;
    Mode candidate = mode_;
    const int direction = sign_of(r.slip_acceleration);
    if (direction == 0 && hint == 0) {
      candidate.friction = FrictionMode::stick;
      candidate.slip_sign = 0;
    } else {
      candidate.friction = FrictionMode::slip;
      candidate.slip_sign = direction != 0 ? direction : hint;
    }
    if (found > 0 && !(candidate == chosen)) ambiguous = true;
    chosen = candidate;
    ++found;
  }
  if (found == 0 && mode_.contact == ThreadContact::closed && !stick_admissible) {
    // No friction mode keeps the normal force on this flank's side: the
    // flank opens (the contact is unilateral). (In the Painleve regime the
    // LCP of the flank's sign can miss a stick that holds it: a rigid
    // drive at rest on its loaded flank opened and jammed at its first
    // impact, 2.6e-11 s later.)
    mode_.contact = ThreadContact::open;
    mode_.friction = FrictionMode::none;
    mode_.slip_sign = 0;
    return;
  }
  if (found == 0 || ambiguous) {
    // In the Painleve regime (mu' |G_NT| >= G_NN) the LCP of one normal-force
    // sign may have no solution or admit a spurious slip start. At zero slip
    // the drive keeps sticking whenever stick is admissible
    // (docs/physics/rigid_drive.md, "uniqueness"); otherwise it jams.
    if (stick_admissible) {
      chosen = mode_;
      chosen.friction = FrictionMode::stick;
      chosen.slip_sign = 0;
    } else {
      jam(found == 0 ? "no flank-contact mode is consistent"
                     : "two flank-contact modes are consistent");
    }
  }
  mode_ = chosen;
}

// The bilateral thread's normal force at the start of a mode (the state is
// set): its sign is the flank in contact; exactly zero leaves it open.
void DriveHybrid::start_normal_side() {
  normal_side_ = 0;
  stage_side_ = 0;
  if (train_) {
    if (mode_.friction != FrictionMode::slip) return;
    normal_side_ = sign_of(solver_->forces(dynamics_.time(), nullptr).normal_force);
    if (train_->has_stage()) stage_side_ = sign_of(train_->stage_torque());
    return;
  }
  if (mode_.contact == ThreadContact::bilateral && mode_.friction != FrictionMode::stick &&
      mode_.friction != FrictionMode::none)
    normal_side_ = sign_of(solve_current().loaded_normal());
}

// Root function of a flank change of the thread without play: the normal
// force on the side it pushes, falling through zero. A normal force that is
// exactly zero at the start of a mode (a flexible drive whose springs are
// relaxed at t = 0 transmits no load yet) has no side: until it leaves zero
// the root is |N|, which cannot change sign, and the side it leaves to
// becomes the flank (|N| = side N there, so the root stays continuous).
// Leaving zero is not a flank change; passing through it is.
double DriveHybrid::flank_change_root(double normal_force) {
  if (normal_side_ == 0) normal_side_ = sign_of(normal_force);
  return normal_side_ != 0 ? normal_side_ * normal_force : 0.0;
}

// The train's friction stages (mode_solver.hpp, TrainSolver): every contact
// slips with the one speed, so the mode is the train's. At zero slip (the
// velocity projected onto exactly zero) the breakaway test decides.
void DriveHybrid::decide_train(double t, double* y, bool at_zero_slip, int hint) {
  mode_.contact = ThreadContact::bilateral;
  if (!at_zero_slip && std::abs(dynamics_.slip_velocity()) > dynamics_.slip_noise()) {
    mode_.friction = FrictionMode::slip;
    mode_.slip_sign = sign_of(dynamics_.slip_velocity());
    return;
  }
  ModeSpec base = spec(1);
  base.friction = FrictionMode::none;
  dynamics_.project_zero_slip(base, v_);
  layout_.compress(q_, v_, y);
  set(t, y);
  const int direction = train_->breakaway(hint);
  mode_.friction = direction == 0 ? FrictionMode::stick : FrictionMode::slip;
  mode_.slip_sign = direction;
}

// As flank_change_root, for the stage's torque on the driven part.
double DriveHybrid::stage_reversal_root(double stage_torque) {
  if (stage_side_ == 0) stage_side_ = sign_of(stage_torque);
  return stage_side_ != 0 ? stage_side_ * stage_torque : 0.0;
}

}  // namespace leadscrew::model::drive
