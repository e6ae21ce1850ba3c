// DriveMoreau (moreau.hpp): a preloaded nut that lifts off on Moreau-Jean's
// step (elements/preloaded_nut.hpp, "Lift-off"; docs/physics/
// preloaded_nut.md, "Lift-off on Moreau-Jean"): half A is the nut body on
// its penalty flank (moreau_flanks.cpp), half B a massless half on its own
// rigid flank, sprung against the body by S(e) = max(0, P + k_p (closing -
// side e)), Coulomb friction on both (one friction mode of the slip; with
// Stribeck's curve its coefficient at the step's start speed).
//
// Half B's force over the step is the event-driven scheme's at the spring's
// step value S: in stick side S grad(e) (its friction in the stick
// impulse), in slip s N_B^s(S) W_N + T_B^s(S) W_T = (cos(a) / D_s) side S
// grad(e) + T_B^s W_T with D_s = cos(a) - s side mu' sin(a). Its elastic part
// is the discrete gradient G of V = S^2 / (2 k_p) along the play (S = -side
// G: V's change over the step exactly, as the flank's), linearised at the
// step's end estimate and updated by Newton with the flank's
// (update_half_b); along grad(e) in the mode m it is c_m G with c_0 = 1 and
// c_s = cos(a) / D_s, a rank-one term c_m h^2 theta G' in W. So each
// friction mode is a linear step of its own: stick (P_T = -c / d, the
// halves' cone at mu_static' checked at its impulses), slip s (P_T = -s mu'
// (|P_N,A| + h S / D_s), P_N,A and S affine in P_T, gamma+ of sign s);
// the first consistent one of stick, slip +, slip - is the step's. Half B's
// friction works on its own slip gamma_T - sin(a) e' (book_step).
#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/law.hpp"
#include "moreau.hpp"

namespace leadscrew::model::drive {

void DriveMoreau::HalfBSpring::linearise(const elements::PreloadedNut& nut, double end) {
  e1k = end;
  const double delta = end - e0;
  const double scale = std::max({std::abs(e0), std::abs(end), 1e-300});
  // V' = -side S, V'' = k_p where S > 0.
  if (std::abs(delta) > 1e-7 * scale) {
    secant = (nut.spring_energy(end) - nut.spring_energy(e0)) / delta;
    slope = std::max(0.0, (-nut.side * nut.spring_force(end) - secant) / delta);
  } else {
    const double middle = 0.5 * (e0 + end);
    secant = -nut.side * nut.spring_force(middle);
    slope = nut.spring_force(middle) > 0.0 ? 0.5 * nut.stiffness : 0.0;
  }
}

// Half B's factor c_m along grad(e) in the friction mode m (0: stick).
double DriveMoreau::half_b_factor(const elements::PreloadedNut& nut, int m) const {
  return m == 0 ? 1.0 : nut.cos_lead / (nut.cos_lead - m * nut.side * nut.mu * nut.sin_lead);
}

// The step in the friction mode m at the friction impulse P_T: half B's
// rank-one term and force in W and the right-hand side (the pass's, with
// the flank's), solved.
DriveMoreau::Impulses DriveMoreau::lift_off_step(const elements::PreloadedNut& nut, int m,
                                                 double h, double theta,
                                                 const CoordinateVector& v0,
                                                 double normal_target, double rotor_target,
                                                 double tangential) {
  const double c_m = half_b_factor(nut, m);
  const elements::ThreadPair& thread = model_.thread_pair();
  iteration_.set_rank_one(flank_coefficient(h, theta) + c_m * h * h * theta * half_b_.slope);
  const double g0 = thread.play_gradient().dot(v0);
  const double force =
      half_b_.secant + half_b_.slope * (half_b_.e0 + h * (1.0 - theta) * g0 - half_b_.e1k);
  free_ = iteration_.solve(CoordinateVector(pass_rhs_ - h * c_m * force * thread.play_gradient()));
  return solve(false, normal_target, rotor_target, tangential);
}

// Half B's spring force over the step (S = -side G) at the step's end v1.
// (clamped: at least 0; unclamped, the linearisation's affine value)
double DriveMoreau::half_b_spring(const elements::PreloadedNut& nut, double h, double theta,
                                  const CoordinateVector& v0, const CoordinateVector& v1,
                                  bool clamped) const {
  const double rate = model_.play_gradient().dot((1.0 - theta) * v0 + theta * v1);
  const double spring = -nut.side * half_b_.gradient(half_b_.e0 + h * rate);
  return clamped ? std::max(0.0, spring) : spring;
}

// The mode m's affine maps in the friction impulse P_T: the slip gamma+ =
// c + d P, half A's normal impulse beta + alpha P, the spring's S0 + sigma P.
DriveMoreau::LiftOffMaps DriveMoreau::lift_off_maps(const elements::PreloadedNut& nut, int m,
                                                    double h, double theta,
                                                    const CoordinateVector& v0,
                                                    double normal_target, double rotor_target) {
  const Eigen::VectorXd& tangent = model_.tangent_direction();
  const Impulses zero = lift_off_step(nut, m, h, theta, v0, normal_target, rotor_target, 0.0);
  const Impulses one = lift_off_step(nut, m, h, theta, v0, normal_target, rotor_target, 1.0);
  LiftOffMaps r;
  r.c = tangent.dot(zero.velocity);
  r.d = tangent.dot(one.velocity) - r.c;
  r.beta = flank_impulse(h, theta, v0, zero.velocity);
  r.alpha = flank_impulse(h, theta, v0, one.velocity) - r.beta;
  r.s0 = half_b_spring(nut, h, theta, v0, zero.velocity, false);
  r.sigma = half_b_spring(nut, h, theta, v0, one.velocity, false) - r.s0;
  return r;
}

DriveMoreau::Impulses DriveMoreau::solve_lift_off_thread(double t, double h, double theta,
                                                         const CoordinateVector& v0,
                                                         double normal_target,
                                                         double rotor_target, bool& stick) {
  // Stribeck's curve (without a viscous term: check_preload_integrator):
  // the halves slip at the curve's coefficient at the step's start speed,
  // explicit, as the nut without lift-off (moreau_preload.cpp) and the
  // plain thread; they stick at mu_static'.
  const elements::PreloadedNut nut = lift_off_slipping(v0);
  auto maps = [&](int m) {
    return lift_off_maps(nut, m, h, theta, v0, normal_target, rotor_target);
  };
  using Maps = LiftOffMaps;
  // Stick at the halves' cone at mu_static' (the two-step test's first):
  // gamma+ = 0 at P = -c / d inside both edges at the step's impulses.
  const elements::PreloadedNut rest = model_.preloaded_nut()->sticking();
  auto sticks = [&](const Maps& k, double& p) {
    if (!(k.d > 0.0)) return false;
    p = -k.c / k.d;
    const double normal_a = k.beta + k.alpha * p, spring = h * std::max(0.0, k.s0 + k.sigma * p);
    return rest.split_bound(1, normal_a, spring) + p >= 0.0 &&
           rest.split_bound(-1, normal_a, spring) - p >= 0.0;
  };
  // factor: the mode of half B's force (0: its spring's, +-1: at slip +-1's
  // edge); stuck: gamma+ = 0.
  int factor = 2;  // (none yet)
  bool stuck = false;
  double friction = 0.0;
  if (sticks(maps(0), friction)) factor = 0, stuck = true;
  for (int s : {1, -1}) {
    if (factor != 2) break;
    const Maps k = maps(s);
    const double denominator = nut.cos_lead - s * nut.side * nut.mu * nut.sin_lead;
    for (int sigma_a : {1, -1}) {
      // P = -s mu' (sigma_a (beta + alpha P) + h (S0 + sigma P) / D_s)
      const double coupling =
          1.0 + s * nut.mu * (sigma_a * k.alpha + h * k.sigma / denominator);
      if (!(coupling > 0.0)) continue;
      const double p = -s * nut.mu * (sigma_a * k.beta + h * k.s0 / denominator) / coupling;
      const double normal_a = k.beta + k.alpha * p;
      if (!(sigma_a * normal_a >= 0.0) || !(s * (k.c + k.d * p) > 0.0)) continue;
      factor = s, friction = p;
      break;
    }
  }
  // At the stick's edge half B's friction's axial part (in slip s) presses
  // half A's flank harder: the stick impulse can lie beyond the cone with B
  // at its spring's force while the slip's edge, B at its slip state,
  // stops the slip. The halves then stick with half B at that edge (each
  // half inside its own cone: an admissible split of the stick force, which
  // stick leaves indeterminate).
  for (int s : {1, -1})
    if (factor == 2 && sticks(maps(s), friction)) factor = s, stuck = true;
  ++lcp_solves_;
  if (factor == 2)
    throw SimulationError(t, "no friction mode of the preloaded nut's halves (half A on its "
                             "penalty flank, half B on its own) is consistent in the Moreau-Jean "
                             "step (dt = " + format_value(h) + " s)",
                          "shorten dt, or use integrator = \"event_driven\"");
  const int mode = factor;
  Impulses impulses = lift_off_step(nut, mode, h, theta, v0, normal_target, rotor_target, friction);
  const double spring = half_b_spring(nut, h, theta, v0, impulses.velocity, true);
  const double denominator = mode == 0 ? nut.cos_lead
                                       : nut.cos_lead - mode * nut.side * nut.mu * nut.sin_lead;
  impulses.preload_normal = h * nut.side * spring / denominator;
  impulses.friction = friction;
  impulses.normal = flank_impulse(h, theta, v0, impulses.velocity) + impulses.preload_normal;
  // Half B's friction impulse (its own slip's share of the loss: book_step).
  half_b_friction_ = mode == 0 || stuck ? 0.0 : -mode * nut.mu * h * spring / denominator;
  half_b_spring_ = spring;
  stick = stuck;
  return impulses;
}

// The nut's element in slip over the step from v0: the model's, or with
// Stribeck's curve its coefficient at the start's slip speed.
elements::PreloadedNut DriveMoreau::lift_off_slipping(const CoordinateVector& v0) const {
  const elements::PreloadedNut& nut = *model_.preloaded_nut();
  const friction::Law& law = dynamics_.law();
  if (law.slip_mu(0.0) == law.mu() && law.slip_mu(1.0) == law.mu()) return nut;
  return nut.with_mu(law.slip_mu(std::abs(model_.tangent_direction().dot(v0))) *
                     model_.flank_factor());
}

// Half B's spring linearised again at the step's end (Newton, with the
// flank's: solve_step's passes). True where it moved.
bool DriveMoreau::update_half_b(double h, double theta, const CoordinateVector& v0,
                                const Impulses& impulses) {
  const elements::PreloadedNut& nut = *model_.preloaded_nut();
  const double rate = model_.play_gradient().dot((1.0 - theta) * v0 + theta * impulses.velocity);
  const double end = half_b_.e0 + h * rate;
  const double scale = std::max(std::abs(half_b_.e0), std::abs(end));
  if (std::abs(end - half_b_.e1k) <= 1e-13 * scale) return false;
  (end > half_b_.e1k ? half_b_.low : half_b_.high) = half_b_.e1k;
  if (!(half_b_.high - half_b_.low > 1e-13 * scale)) return false;
  const double next =
      end > half_b_.low && end < half_b_.high ? end : 0.5 * (half_b_.low + half_b_.high);
  const double secant = half_b_.secant, slope = half_b_.slope;
  half_b_.linearise(nut, next);
  return half_b_.secant != secant || half_b_.slope != slope;
}

}  // namespace leadscrew::model::drive
