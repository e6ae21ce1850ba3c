// The contacts of a Moreau-Jean step besides the thread's flank (whose flank
// LCP is friction/flank_lcp.hpp's), one small struct each: the rotor's
// friction contact (the motor's Coulomb friction and a lossy or worm stage,
// elements/train_friction.hpp; docs/physics/gear.md, "Moreau-Jean: the
// stages on every concept") and a penalty end stop's force over a step
// (elements/end_stop.hpp; docs/physics/end_stops.md, "Moreau-Jean") and a
// penalty flank's (bistop, cubic: elements/thread_pair.hpp;
// docs/physics/drive_models.md, "Moreau-Jean on penalty flanks"). An
// exact stop is a plain unilateral row of the step's constraint solve
// (DriveMoreau::solve). Internal to cpp/src/model; used by moreau.cpp and
// moreau_flanks.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/friction/flank_lcp.hpp"
#include "leadscrew/model/elements/end_stop.hpp"
#include "leadscrew/model/elements/thread_pair.hpp"
#include "leadscrew/model/elements/train_friction.hpp"

namespace leadscrew::model::drive::moreau_contacts {

// The rotor's friction contact in a step: stick, or slip with the sign
// `slip` and the stage's power flow `flow` (+1: from the rotor to the
// driven part), at the slip's or (breakaway) the static efficiencies.
struct RotorMode {
  int slip = 0, flow = 1;
  bool breakaway = false;
};

// The order the modes are tried in: stick (static sets), the slips, the
// slips at breakaway.
inline constexpr RotorMode kRotorModes[] = {
    {0, 1, true},  {1, 1, false}, {1, -1, false}, {-1, 1, false}, {-1, -1, false},
    {1, 1, true},  {1, -1, true}, {-1, 1, true},  {-1, -1, true}};

// A row of the step's constraint solve on the rotor's coordinate, its
// impulse Q along -e_rotor: a_w w+ + a_q Q = r.
struct RotorRow {
  double a_w = 0.0, a_q = 0.0, r = 0.0;
  // It fixes the rotor's speed (no Q in it).
  bool fixes_speed() const noexcept { return a_q == 0.0; }
};

// The rotor's momentum balance over the step without its frictions,
// Y(w) = R (w0 - w) + H0 + H1 w (w the rotor's speed at the step's end, H
// the motor's impulse, H1 a DC motor's implicit back-EMF term): the stage
// passes P_b = Y - Q to the driven part, Q = P_c + Lambda the motor's
// friction impulse and the stage's loss impulse. friction: B = h |n| T_c.
struct RotorBalance {
  double inertia = 0.0, w0 = 0.0, h0 = 0.0, h1 = 0.0, friction = 0.0;
  double at(double w) const noexcept { return inertia * (w0 - w) + h0 + h1 * w; }

  // The row of a mode, with k = x / tau_b the stage's torque ratio (1 / eta
  // forward, eta_b backward; 1 without a stage): stick w+ = 0; slip with
  // sign s, P_c = s B and the stage's X = k P_b with X = Y - P_c,
  // P_b = Y - Q, i.e. k Q - (k - 1) Y(w+) = s B.
  RotorRow row(const elements::TrainFriction& train, const RotorMode& mode) const noexcept {
    if (mode.slip == 0) return {1.0, 0.0, 0.0};
    const double k = train.torque_ratio(mode.flow, mode.breakaway);
    return {(k - 1.0) * (inertia - h1), k, mode.slip * friction + (k - 1.0) * (inertia * w0 + h0)};
  }

  // Whether the speed w and the impulse Q a step found fit the mode: a
  // slip's speed and the stage's power flow have its signs; a stick's Q
  // splits into the motor's friction in [-B, B] and a stage loss in the
  // stage's static set, Lambda between (eta_b,s - 1) P_b and
  // (1 / eta_s - 1) P_b. `other`: the other impulses' size on the rotor's
  // coordinate (the thread's), for the round-off: a flow's sign within it
  // is either (a thread in free flight transmits nothing).
  // (The event-driven scheme's rate form: w the rotor's acceleration, and
  // `moving` its speed where it is not at rest, whose sign a slip takes.)
  bool consistent(const elements::TrainFriction& train, const RotorMode& mode, double w, double q,
                  double other, double moving = 0.0) const noexcept {
    const double transmitted = at(mode.slip == 0 ? 0.0 : w) - q;  // P_b
    const double slack = 64.0 * std::numeric_limits<double>::epsilon() *
                         (std::abs(q) + std::abs(transmitted) + friction + std::abs(h0) +
                          std::abs(inertia * w0) + std::abs(inertia * w) + other);
    if (mode.slip != 0) {
      if (!(mode.slip * (moving != 0.0 ? moving : w) > 0.0)) return false;
      return !train.stage || mode.flow * mode.slip * transmitted >= -slack;
    }
    double low = 0.0, high = 0.0;
    static_set(train, transmitted, low, high);
    return q >= low - slack && q <= high + slack;
  }

  // A stick's static set of Q where the stage passes P_b: the motor's
  // friction in [-B, B] and the stage's loss between (eta_b,s - 1) P_b and
  // (1 / eta_s - 1) P_b.
  void static_set(const elements::TrainFriction& train, double transmitted, double& low,
                  double& high) const noexcept {
    const double forward = (train.torque_ratio(1, true) - 1.0) * transmitted;
    const double backward = (train.torque_ratio(-1, true) - 1.0) * transmitted;
    low = std::min(forward, backward) - friction;
    high = std::max(forward, backward) + friction;
  }

  // A stuck rotor's margin (w = 0, Q its holding torque): >= 0 while Q
  // lies in the static set (the event-driven scheme's root).
  double stick_margin(const elements::TrainFriction& train, double q) const noexcept {
    double low = 0.0, high = 0.0;
    static_set(train, at(0.0) - q, low, high);
    return std::min(q - low, high - q);
  }
};

// A penalty stop engaged over a step: its force at the theta point,
// F_theta = k (d0+ + theta h d'_theta) + c d'_theta, measured from the face,
// or from the step's start where the step engages it (d0 <= 0), so that
// engaging creates no energy. du_theta: the load's speed at the theta point.
inline double penalty_stop_force(const elements::EndStop& stop, double u0, double du_theta,
                                 double h, double theta) noexcept {
  const double rate = stop.side * du_theta;
  return stop.stiffness * (std::max(stop.penetration(u0), 0.0) + theta * h * rate) +
         stop.damping * rate;
}

// Its loss over the step: an engaged stop's damper h c d'_theta^2 (its
// spring's part is the scheme's numerical dissipation, as every spring's);
// a released one gives up the elastic energy k (d0+^2 - d1+^2) / 2 it loses
// with no force (as the event-driven scheme's loss after a release).
inline double penalty_stop_loss(const elements::EndStop& stop, bool engaged, double u0, double u1,
                                double du_theta, double h) noexcept {
  if (engaged) return h * stop.damping * du_theta * du_theta;
  const double d0 = std::max(stop.penetration(u0), 0.0);
  const double d1 = std::max(stop.penetration(u1), 0.0);
  return std::max(0.0, 0.5 * stop.stiffness * (d0 * d0 - d1 * d1));
}

// A penalty flank over a step: a force along the play e (its generalized
// force -F grad e), F = S(e1) + c e'_theta with e1 the play at the step's
// end. Its elastic part is the discrete gradient of the flanks' potential,
// S(e1) = (U(e1) - U(e0)) / (e1 - e0), whose work over the step, S (e1 -
// e0), is U's change exactly (for the nonlinear bistop and cubic forces, at
// any penetration, engaging or leaving a flank within the step); it is
// linearised at the step's end estimate e1k, S_k + S'_k (e1 - e1k), the
// slope S'_k >= 0 entering the iteration matrix, and the step solved again
// at its new end (Newton) until e1 settles. S rises with e1 (U is convex)
// and the step's end falls with S, so the end a step linearised at x finds
// lies on the side of x where the fixed point is: those x bracket it, and a
// Newton iterate outside the bracket is replaced by its midpoint. The damping c of the flank at
// the step's mid-play (>= 0: its loss h c e'_theta^2). Where the step's
// force at its end, S(e1) + c e'_theta, would pull, the flank is released
// for the rest of the step (no force), as a penalty end stop, losing the
// energy U(e0) - U(e1) >= 0; where the step without a force then runs into
// the flank, it is engaged again without its damper (the elastic force
// alone, which always pushes).
struct PenaltyFlank {
  double e0 = 0.0, e1k = 0.0;            // the play at the step's start, its end's estimate [m]
  double potential0 = 0.0;               // U(e0) [J] (start: every linearisation needs it)
  double secant = 0.0, slope = 0.0;      // S_k [N] and S'_k [N/m] at e1k
  double damping = 0.0;                  // c [N s/m]
  int side = 0;                          // the flank: +1 upper (e > 0), -1 lower, 0 none
  bool released = false, undamped = false;
  // The bracket of the step's end play [m].
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();

  // The step's start at the play `start`: no force yet (linearise).
  void start(const elements::ThreadPair& thread, double start) noexcept {
    *this = PenaltyFlank{};
    e0 = start;
    potential0 = thread.flank_potential(start);
  }
  void linearise(const elements::ThreadPair& thread, double end) noexcept {
    e1k = end;
    const double delta = end - e0;
    const double scale = std::max({std::abs(e0), std::abs(end), 1e-300});
    if (std::abs(delta) > 1e-7 * scale) {
      secant = (thread.flank_potential(end) - potential0) / delta;
      slope = std::max(0.0, (thread.flank_slope(end) - secant) / delta);
    } else {  // (the midpoint's slope: the secant's limit without its cancellation)
      secant = thread.flank_slope(0.5 * (e0 + end));
      slope = 0.5 * thread.flank_curvature(0.5 * (e0 + end));
    }
    damping = undamped ? 0.0 : thread.flank_damping(0.5 * (e0 + end));
    side = secant > 0.0 ? 1 : secant < 0.0 ? -1 : 0;
    if (side == 0 && damping > 0.0) side = e0 + end > 0.0 ? 1 : -1;
  }
  bool active() const noexcept { return !released && side != 0; }
  // F at the step's end play e1 and the play's rate at the theta point.
  double force(double end, double rate) const noexcept {
    if (!active()) return 0.0;
    return secant + slope * (end - e1k) + damping * rate;
  }
  // The step's loss: the damper's, or a released flank's elastic energy.
  double loss(const elements::ThreadPair& thread, double end, double rate, double h) const {
    if (active()) return h * damping * rate * rate;
    if (!released) return 0.0;
    return std::max(0.0, potential0 - thread.flank_potential(end));
  }
};

// A penalty flank's slip over a step where the flank LCP finds none: the
// LCP (friction/flank_lcp.hpp) needs 1 + mu sigma alpha > 0, which a step
// whose springs make the flank's friction impulse a lever on its normal
// impulse (mu |alpha| >= 1, W's h^2 S' grad e grad e^T dominating the
// masses) breaks on one edge of the cone. The flank's normal impulse is
// its force's, pushing without friction (sigma beta >= 0: else the force
// pulls and the flank is released), and d > 0; then exactly one of stick
// (flank_stick, tried before) and the two slips at the cone's edges is
// consistent (docs/physics/drive_models.md, "Moreau-Jean on penalty
// flanks"), so each edge is tried directly: the slip s at the step's end,
// P_T = -s mu sigma P_N with P_N = beta + alpha P_T on the side sigma.
inline friction::FlankLcpResult penalty_flank_slip(double c, double d, double alpha, double beta,
                                                  double mu, int sigma) noexcept {
  for (const int s : {1, -1}) {
    const double coupling = 1.0 + s * mu * sigma * alpha;
    if (coupling == 0.0) continue;
    friction::FlankLcpResult r;
    r.status = lcp::Status::solved;
    r.friction_force = -s * mu * sigma * beta / coupling;
    r.normal_force = beta + alpha * r.friction_force;
    r.slip_acceleration = c + d * r.friction_force;
    r.consistent = sigma * r.normal_force >= 0.0 && s * r.slip_acceleration > 0.0;
    if (r.consistent) return r;
  }
  return friction::FlankLcpResult{};
}

}  // namespace leadscrew::model::drive::moreau_contacts
