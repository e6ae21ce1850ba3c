// Element: a preloaded split nut on the thread without play (issue 19 item
// 4; scene keys nut.preload, nut.preload_stiffness; docs/physics/
// preloaded_nut.md). Two nut halves sprung apart by a spring of force P,
// each bearing on one flank. Half A carries the load; half B bears on the
// opposite flank (sign `side` of its normal force on the screw, -sigma_A).
// On the rigid concept the halves keep the spring force equal to P, and
// they stick or slip together (one slip velocity gamma_T).
//
// While the nut slips in the direction s = sign(gamma_T), half B's flank
// force (normal N_B, friction T_B = -s mu' |N_B|) has the axial component
// cos(a) N_B + sin(a) T_B = side P (the spring's force), so
//   N_B^s = side P / (cos a - s side mu' sin a),  T_B^s = -s mu' |N_B^s|,
// constant in the mode: half B is a given force N_B^s W_N + T_B^s W_T. Half
// A is the thread pair's flank force (the constraint's multiplier N_A, its
// friction -s mu' |N_A|). The net forces N = N_A + N_B^s, T = T_A + T_B^s
// are the channels. With net maps N = beta + alpha T (every constraint but
// friction enforced, T along W_T), the friction bound in the direction s is
//   -s T <= b_s(N) = mu' (|N - N_B^s| + |N_B^s|),
// convex and 1-Lipschitz in N: at stick (zero slip) T lies in
// [-b_+(N), b_-(N)], and the edge of slip s is the unique solution of
// T = -s b_s(beta + alpha T) outside the Painleve regime (mu' |alpha| < 1).
// Where N - N_B^s changes sign (the load on half B's side beyond what the
// preload holds) half A bears on its other flank: the thread without play
// is bilateral, and the bound becomes mu' |N| (half A and B on one side).
// P = 0 is no element (the plain thread, bit for bit).
#pragma once

#include <algorithm>
#include <cmath>

#include "leadscrew/friction/flank_lcp.hpp"

namespace leadscrew::model::elements {

struct PreloadedNut {
  double preload = 0.0;    // P [N] > 0: the spring's axial force between the halves
  double stiffness = 0.0;  // k_p [N/m] >= 0: the spring's rate (0: not given)
  double mu = 0.0;         // mu' = mu / cos(beta / 2)
  // mu_static' (Coulomb's law with friction.mu_static >= mu): the halves
  // stick while the friction lies in the bound at mu_static' (half B at its
  // edge's state at mu_static'), and slip at mu'. Equal to mu: one coefficient.
  double mu_static = 0.0;
  double cos_lead = 1.0, sin_lead = 0.0;
  int side = -1;  // half B's normal-force sign on the screw (half A's is -side)

  // The element at the stick limit: its bounds, edges and stick margins at
  // mu_static' (itself where mu_static' <= mu'). The breakaway from stick is
  // decided by it, the slip's forces by the element itself.
  PreloadedNut sticking() const noexcept {
    PreloadedNut at_rest = *this;
    at_rest.mu = std::max(mu, mu_static);
    return at_rest;
  }
  bool two_coefficients() const noexcept { return mu_static > mu; }

  // Half B's normal and friction force while the nut slips in direction s (+-1) [N].
  double normal(int s) const noexcept {
    return side * preload / (cos_lead - s * side * mu * sin_lead);
  }
  double friction(int s) const noexcept { return -s * mu * std::abs(normal(s)); }
  // Half B's normal and friction force at the signed friction coefficient
  // kappa' (its friction -kappa' |N_B|) and the spring force S [N]: a smooth
  // law's (arctan_velocity, LuGre's bristles, Stribeck's curve in slip),
  // each half's flank taking the law at the common slip. From B's axial
  // balance cos(a) N_B + sin(a) T_B = side S: N_B = side S / (cos(a) - side
  // kappa' sin(a)); kappa' = s mu' is normal(s). Needs cos(a) - side kappa'
  // sin(a) > 0 (else half B locks against its spring: half_b_locks).
  double normal_at(double kappa, double spring) const noexcept {
    return side * spring / (cos_lead - side * kappa * sin_lead);
  }
  double friction_at(double kappa, double spring) const noexcept {
    return -kappa * std::abs(normal_at(kappa, spring));
  }
  bool half_b_locks(double kappa) const noexcept {
    return !(cos_lead - side * kappa * sin_lead > 0.0);
  }
  // The element with the kinetic coefficient mu' (Stribeck's curve at the
  // slip's start, mu(0+)').
  PreloadedNut with_mu(double kinetic_mu) const noexcept {
    PreloadedNut at = *this;
    at.mu = kinetic_mu;
    return at;
  }
  // The friction bound b_s(N) in the direction s at the net normal force N.
  double bound(int s, double normal_force) const noexcept {
    const double b = normal(s);
    return mu * (std::abs(normal_force - b) + std::abs(b));
  }
  // The stick cone's margin at net forces (N, T): >= 0 inside, the
  // product of the two edges' reserves (as the plain thread's
  // (mu' N - T)(mu' N + T)).
  double stick_margin(double normal_force, double friction_force) const noexcept {
    return (bound(-1, normal_force) - friction_force) * (bound(1, normal_force) + friction_force);
  }
  // The slip direction a net friction force T resists (its edge): -sign T (+1 for T = 0).
  static int edge_of(double friction_force) noexcept { return friction_force > 0.0 ? -1 : 1; }
  // |N_A| + |N_B| at net forces (N, T), half B at the edge T heads for: the
  // normal force mu' multiplies (the result checks' cone and law).
  double flank_normal(double normal_force, double friction_force) const noexcept {
    const double b = normal(edge_of(friction_force));
    return std::abs(normal_force - b) + std::abs(b);
  }

  // The edge of slip s: the net friction force T = -s b_s(beta + alpha T)
  // with N = beta + alpha T the net normal force. `count`: how many of the
  // two pieces of b_s (half A's normal-force sign) give a consistent
  // solution; 1 outside the Painleve regime, 0 or 2 (distinct) is jamming.
  struct Edge {
    double friction = 0.0, normal = 0.0;
    int count = 0;
  };
  Edge edge(int s, double alpha, double beta) const noexcept {
    const double b = normal(s);
    Edge e;
    for (int sigma : {1, -1}) {
      // T = -s mu' (sigma (beta + alpha T - b) + |b|)
      const double coupling = 1.0 + s * mu * sigma * alpha;
      if (!(coupling > 0.0)) continue;
      const double t = -s * mu * (sigma * (beta - b) + std::abs(b)) / coupling;
      const double n = beta + alpha * t;
      if (!(sigma * (n - b) >= 0.0)) continue;
      // The kink (half A's force zero): both pieces, one solution to round-off.
      if (e.count > 0 && std::abs(t - e.friction) <=
                             1e-12 * (std::abs(t) + std::abs(e.friction) + mu * std::abs(b)))
        continue;
      e.friction = t;
      e.normal = n;
      ++e.count;
    }
    return e;
  }

  // Stick or slip at zero slip velocity (the flank LCP's decision, by its
  // three cases): with the slip acceleration x = c + d T (d > 0) and the
  // net normal force N = beta + alpha T, stick where T = -c / d lies
  // between the edges [T_+, T_-], slip s where x at the edge T_s has the
  // sign s. Where an edge is not unique (the Painleve regime) the drive
  // keeps sticking if the stick force lies in the cone, as the plain
  // thread does (docs/physics/rigid_drive.md, "uniqueness"); otherwise
  // `consistent` is false (jamming).
  friction::FlankLcpResult decide(double c, double d, double alpha, double beta) const {
    friction::FlankLcpResult r;
    if (!(d > 0.0)) return r;
    const Edge up = edge(1, alpha, beta), down = edge(-1, alpha, beta);
    if (up.count != 1 || down.count != 1) {
      const double stick = -c / d, normal_force = beta + alpha * stick;
      if (!(bound(-1, normal_force) - stick >= 0.0 && bound(1, normal_force) + stick >= 0.0))
        return r;
      r.status = lcp::Status::solved;
      r.consistent = true;
      r.friction_force = stick;
      r.normal_force = normal_force;
      return r;
    }
    r.status = lcp::Status::solved;
    r.consistent = true;
    const double x_up = c + d * up.friction, x_down = c + d * down.friction;
    if (x_up > 0.0) {
      r.friction_force = up.friction;
      r.slip_acceleration = x_up;
    } else if (x_down < 0.0) {
      r.friction_force = down.friction;
      r.slip_acceleration = x_down;
    } else {
      r.friction_force = -c / d;
      r.slip_acceleration = 0.0;
    }
    r.normal_force = beta + alpha * r.friction_force;
    return r;
  }

  // The same where the motor prescribes the slip (d = 0,
  // friction::solve_flank_prescribed_slip): slip in the direction of c where
  // c != 0; at c = 0 stick, with the friction force in [T_+, T_-] (at
  // mu_static', the stick's band) that leaves the motor (motor0 + motor1 T)
  // the least torque.
  friction::FlankLcpResult prescribed_slip(double c, bool slip_zero, double alpha, double beta,
                                           double motor0, double motor1) const {
    if (slip_zero && two_coefficients())
      return sticking().prescribed_slip(c, true, alpha, beta, motor0, motor1);
    friction::FlankLcpResult r;
    r.status = lcp::Status::solved;
    if (!slip_zero) {
      const Edge e = edge(c > 0.0 ? 1 : -1, alpha, beta);
      r.consistent = e.count == 1;
      r.friction_force = e.friction;
      r.normal_force = e.normal;
      r.slip_acceleration = c;
      return r;
    }
    const Edge up = edge(1, alpha, beta), down = edge(-1, alpha, beta);
    if (up.count != 1 || down.count != 1) return r;
    double friction_force = motor1 != 0.0 ? -motor0 / motor1 : 0.0;
    if (!std::isfinite(friction_force)) friction_force = 0.0;
    r.friction_force = std::min(down.friction, std::max(up.friction, friction_force));
    r.normal_force = beta + alpha * r.friction_force;
    r.slip_acceleration = 0.0;
    r.consistent = true;
    return r;
  }

  // --- Lift-off: the flexible concepts with penalty flanks
  // (docs/physics/preloaded_nut.md, "Lift-off"). Half A is the nut body's
  // flank contact across the play (the thread pair's penalty flanks); half
  // B a massless half on its own flank, taken rigid, sprung against the body
  // by S = max(0, P + k_p (b e + closing)) with b = -side the direction of
  // half B's flank in the play e and closing = c/2 + d_0 (d_0: half A's
  // flank penetrated at P, the assembled nut's play e_0 = -b closing).
  // Both halves slip with the thread's slip velocity (one friction mode). In
  // slip s half B is the rigid concept's given force at S,
  // N_B^s(S) W_N + T_B^s(S) W_T = side S grad(e) + T_B^s (W_T - sin(a) grad(e)):
  // its friction works on its own slip gamma_T - sin(a) e' (it sits on its
  // flank), the driver books that loss. In stick (and without friction) it
  // is the spring's force side S grad(e), its friction in the stick force.
  bool lift_off = false;
  double closing = 0.0;  // c/2 + d_0 [m]

  // Exact play on a flexible concept, closed by the preload (docs/physics/
  // preloaded_nut.md, "Exact play closed by the preload"): the element
  // without play, exact while half A bears on its flank. Half A lifting off
  // into the play is not modelled: the driver watches half A's normal force
  // on its flank (half_a_bearing) and raises a SimulationError where it
  // reaches zero.
  bool closes_exact_play = false;
  // Half A's normal force toward its own flank [N] (>= 0 while it bears) at
  // the net normal force N: half B at N_B^s in slip s = +-1, at its spring's
  // force side P / cos(a) along W_N (side P grad(e)) in stick or without
  // friction (s = 0). Quasi-statically in stick, with the thread's force
  // axial, it is zero at the axial load P / cos^2(a) on half B's side.
  double half_a_bearing(int s, double normal_force) const noexcept {
    const double b = s == 0 ? side * preload / cos_lead : normal(s);
    return -side * (normal_force - b);
  }

  // The spring's force S [N] at the play e and its energy S^2 / (2 k_p) [J].
  double spring_force(double play) const noexcept {
    return std::max(0.0, preload + stiffness * (closing - side * play));
  }
  double spring_energy(double play) const noexcept {
    const double force = spring_force(play);
    return force * force / (2.0 * stiffness);
  }
  // Half B's normal force [N] on its flank at the spring force S while the
  // nut slips in the direction s (its axial balance, as normal(s) at P).
  double normal(int s, double spring) const noexcept {
    return side * spring / (cos_lead - s * side * mu * sin_lead);
  }
  // The friction bound of slip s with half A's normal force N_A (the penalty
  // flanks') and the spring force S: mu' (|N_A| + |N_B^s(S)|).
  double split_bound(int s, double normal_a, double spring) const noexcept {
    return mu * (std::abs(normal_a) + std::abs(normal(s, spring)));
  }
  // Half B's friction force in slip s.
  double split_friction(int s, double spring) const noexcept {
    return -s * mu * std::abs(normal(s, spring));
  }
  // The stick cone's margin at the net friction force T (>= 0 inside).
  double split_stick_margin(double normal_a, double spring, double friction_force) const noexcept {
    return (split_bound(-1, normal_a, spring) - friction_force) *
           (split_bound(1, normal_a, spring) + friction_force);
  }
  // |N_A| + |N_B| with half B at the edge T heads for (the checks' normal).
  double split_flank_normal(double normal_a, double spring, double friction_force) const noexcept {
    return std::abs(normal_a) + std::abs(normal(edge_of(friction_force), spring));
  }
  // Stick or slip at zero slip (the LCP's three cases): with the slip
  // acceleration x = c + d T, the edges T_+ = -b_+ and T_- = b_- are
  // constants (half A's normal force is the penalty flanks', given).
  friction::FlankLcpResult decide_split(double c, double d, double normal_a,
                                        double spring) const {
    friction::FlankLcpResult r;
    if (!(d > 0.0)) return r;
    r.status = lcp::Status::solved;
    r.consistent = true;
    const double up = -split_bound(1, normal_a, spring), down = split_bound(-1, normal_a, spring);
    const double x_up = c + d * up, x_down = c + d * down;
    if (x_up > 0.0) {
      r.friction_force = up;
      r.slip_acceleration = x_up;
    } else if (x_down < 0.0) {
      r.friction_force = down;
      r.slip_acceleration = x_down;
    } else {
      r.friction_force = -c / d;
      r.slip_acceleration = 0.0;
    }
    r.normal_force = normal_a;
    return r;
  }
};

// The steady raising efficiency of the rigid drive with a preloaded nut
// (docs/physics/preloaded_nut.md): a load F >= 0 on half A's flank, preload
// P >= 0, lead angle alpha, mu' = tan rho':
//   eta = F tan(alpha) / [(F + P) tan(alpha + rho') + P tan(rho' - alpha)],
// 0 where the thread cannot be driven (alpha + rho' >= pi / 2), 1 at F = 0 with P = 0.
inline double preloaded_efficiency(double alpha, double mu_eff, double load, double preload) {
  const double rho = std::atan(mu_eff);
  const double half_pi = 1.57079632679489661923;
  if (!(alpha + rho < half_pi)) return 0.0;
  const double need =
      (load + preload) * std::tan(alpha + rho) + preload * std::tan(rho - alpha);
  if (need == 0.0) return 1.0;
  return load * std::tan(alpha) / need;
}

}  // namespace leadscrew::model::elements
