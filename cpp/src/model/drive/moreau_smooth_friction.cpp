// DriveMoreau (moreau.hpp): the smooth thread laws on Moreau-Jean, the
// velocity laws (arctan_velocity), LuGre's bristles and a transverse slip's
// 2-D Coulomb cone (transverse_slip.cpp)
// (docs/physics/drive_models.md, "Moreau-Jean with the smooth laws").
//
// The friction impulse of the step is the law's at the step's end slip,
// implicit (backward Euler in the friction):
//   P_T = -kappa(gamma+) |P_N| - h viscous gamma+,
//   gamma+ = c + d P_T,  P_N = beta + alpha P_T,
// c, d, alpha, beta the step's linear response (DriveMoreau::solve_thread).
// Implicit, so that a stiff law (k_V of 1e4 s/m and more: a slope
// mu' k_V |N| far beyond what an explicit step resolves) needs no short
// step: the law's slope is resolved inside the step, as the viscous term's
// and the springs' are through the iteration matrix. For LuGre the
// bristles take their implicit Euler step with the slip,
//   z+ = (z0 + h gamma+) / (1 + h sigma0 |gamma+| / mu(|gamma+|)),
// which stays in |z| <= max(mu, mu_static) / sigma0 from any start inside,
// and kappa = sigma0 z+ + sigma1 (z+ - z0) / h is the law's own
// coefficient at (gamma+, z+) (its z' the step's), so every row of a run
// satisfies the law's relation.
//
// The rows' slip: the root's gamma+ = c + d P_T is the slip of the law's
// friction. The end state's slip, the tangent of the velocities solved
// at P_T, is the same slip up to the round-off of that solve, of the
// size of c (c = 196 m/s where a wound-up flexible screw's 7e8 N meet a
// held stop, against a slip of 1e-8 m/s: 2e-11 m/s apart), and LuGre's
// slope near zero slip, |N|' d kappa / d gamma = |N|' (sigma0 h + sigma1)
// (d z+ / d gamma = h there), 2.5e9 N s/m at |N| = 1.4e8 N, turns that
// into 0.07 N of a 2.3e6 N friction, 3e-8 of it (the train fuzz's case
// 6473): the row's friction, bristles and slip no longer satisfied the law.
// The bristles therefore take their step at the root's slip (book_step),
// and LuGre's row reports it as its slip (channels); the work the
// friction does on the bodies stays -P_T times the end state's slip.
//
// The scalar equation F(P) = P + kappa(c + d P) |beta + alpha P|
// + h viscous (c + d P) = 0 rises with P wherever kappa rises with the slip
// (d >= 0) and kappa_max |alpha| < 1 (the step's coupling, which
// check_step and solve_thread hold below 1 outside the Painleve regime):
// exactly one root, bracketed from P = 0 outward and found by the
// Illinois variant of regula falsi to round-off.
#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/law.hpp"
#include "moreau.hpp"

namespace leadscrew::model::drive {

namespace {

// LuGre's bristle deflection after an implicit Euler step of h at slip g.
double bristle_step(const friction::Law& law, double z0, double g, double h) {
  const double speed = std::abs(g);
  return (z0 + h * g) / (1.0 + h * law.bristle_stiffness() * speed / law.slip_mu(speed));
}

// A component of LuGre's 2-D bristles on a transverse slip's cone (the
// event-driven scheme's DriveDynamics::bristle_rate) after the implicit
// Euler step: its slip component g relaxing at the step's end slip speed
// |(gamma+, w+)|, which keeps |(z, z_w)| <= max(mu, mu_static) / sigma0.
double planar_bristle_step(const friction::Law& law, double z0, double g, double speed,
                           double h) {
  return (z0 + h * g) / (1.0 + h * law.bristle_stiffness() * speed / law.slip_mu(speed));
}

// The bristles' coefficient sigma0 z+ + sigma1 z+' at the step's end, z+'
// the law's rate there (= (z+ - z0) / h).
double planar_bristle_coefficient(const friction::Law& law, double z1, double g, double speed) {
  return law.bristle_stiffness() * z1 +
         law.bristle_damping() *
             (g - law.bristle_stiffness() * speed * z1 / law.slip_mu(speed));
}

// The root of f between low and high (f(low) < 0 < f(high)): the Illinois
// variant of regula falsi, to the interval's round-off.
template <class F>
double bracketed_root(const F& f, double low, double f_low, double high, double f_high) {
  int side = 0;
  for (int iteration = 0; iteration < 400; ++iteration) {
    double x = (low * f_high - high * f_low) / (f_high - f_low);
    if (!(x > low && x < high)) x = 0.5 * (low + high);
    const double fx = f(x);
    if (fx == 0.0) return x;
    if (fx < 0.0) {
      low = x, f_low = fx;
      if (side == -1) f_high *= 0.5;
      side = -1;
    } else {
      high = x, f_high = fx;
      if (side == 1) f_low *= 0.5;
      side = 1;
    }
    if (high - low <= 4.0 * std::numeric_limits<double>::epsilon() *
                          std::max(std::abs(low), std::abs(high)))
      break;
  }
  return std::abs(f_low) < std::abs(f_high) ? low : high;
}

// The root of f, increasing with slope >= 1 - kappa_max |alpha| > 0, in
// `root`: bracketed from 0 outward (a few doublings of f(0)'s size), then
// bracketed_root. False where no bracket is found (f not finite or not
// rising).
template <class F>
bool increasing_root(const F& f, double& root) {
  const double f0 = f(0.0);
  root = 0.0;
  if (f0 == 0.0) return true;
  double low = 0.0, high = 0.0, f_low = f0, f_high = f0;
  double step = std::max(std::abs(f0), std::numeric_limits<double>::min());
  for (int k = 0; k < 2100 && !(f_low < 0.0 && f_high > 0.0); ++k, step *= 2.0) {
    const double x = f0 > 0.0 ? -step : step;
    const double fx = f(x);
    if (!std::isfinite(fx)) break;
    (f0 > 0.0 ? low : high) = x;
    (f0 > 0.0 ? f_low : f_high) = fx;
  }
  if (!(f_low < 0.0 && f_high > 0.0)) return false;
  root = bracketed_root(f, low, f_low, high, f_high);
  return true;
}

}  // namespace

double DriveMoreau::smooth_coefficient(double slip, double h) const {
  // The transverse slip's cone at the step's end slip (gamma+, w+): the
  // helix component mu' gamma+ / |(gamma+, w+)| (mu' Stribeck's at the
  // step's start slip speed), strictly increasing in gamma+ and below mu'
  // (one root, found to round-off: the exact cone; the viscous term is
  // the smooth step's own, implicit).
  const friction::Law& law = model_.law();
  const double factor = model_.flank_factor();
  if (transverse_state_ >= 0 && law.resolution() == friction::Resolution::bristle) {
    const double speed = std::hypot(slip, transverse_next_);
    const double z1 = planar_bristle_step(law, bristle_z0_, slip, speed, h);
    return planar_bristle_coefficient(law, z1, slip, speed) * factor;
  }
  if (transverse_state_ >= 0)
    return DriveDynamics::cone_coefficient(slip, transverse_next_, transverse_mu_);
  if (law.resolution() == friction::Resolution::bristle)
    return law.bristle_coefficient(slip, bristle_step(law, bristle_z0_, slip, h)) * factor;
  return law.velocity_coefficient(slip) * factor;
}

DriveMoreau::Impulses DriveMoreau::solve_smooth_thread(double t, double h, double theta,
                                                       const CoordinateVector& v0,
                                                       double normal_target, double rotor_target,
                                                       int sigma_fixed, double c, double d,
                                                       double alpha, double beta,
                                                       bool& contact) {
  const friction::Law& law = model_.law();
  const bool row = !model_.thread_pair().penalty();
  if (model_.effective_max_mu() * std::abs(alpha) >= 1.0 && !dynamics_.painleve_possible())
    throw SimulationError(t,
                          "dt = " + format_value(h) + " s is too long for the stiffness of "
                          "this drive here: " + step_too_long(theta, alpha),
                          "use dt < " + format_value(resolving_step(h, theta)) +
                              " s");
  const double viscous_step = law.viscous() * h;
  // The normal impulse's size: a flank (sigma_fixed != 0) carries only a
  // push, the bilateral thread (no play) either sign.
  auto normal_size = [&](double p) {
    const double n = beta + alpha * p;
    return sigma_fixed != 0 ? std::max(sigma_fixed * n, 0.0) : std::abs(n);
  };
  // A preloaded nut (the thread's row): both halves' flanks take the law at
  // the step's end slip, half B's impulse h N_B(kappa) (its axial balance,
  // PreloadedNut::normal_at) inside the net P_N: |P_N - h N_B| + h |N_B|.
  const elements::PreloadedNut* nut = row ? model_.preloaded_nut() : nullptr;
  auto half_b = [&](double kappa) {
    if (nut->half_b_locks(kappa))
      throw SimulationError(t, "the preloaded nut's half B locks against its own spring in the "
                               "Moreau-Jean step: the law's friction coefficient kappa' = " +
                                   format_value(kappa) + " times tan(lead angle) reaches 1",
                            "lower friction.mu (or LuGre's sigma1) or the lead");
    return h * nut->normal_at(kappa, nut->preload);
  };
  auto f = [&](double p) {
    const double slip = c + d * p;
    const double kappa = smooth_coefficient(slip, h);
    if (!nut) return p + kappa * normal_size(p) + viscous_step * slip;
    const double b = half_b(kappa), n = beta + alpha * p;
    return p + kappa * (std::abs(n - b) + std::abs(b)) + viscous_step * slip;
  };
  double friction = 0.0;
  if (!increasing_root(f, friction))
    throw JammingError(t, "no friction impulse of the Moreau-Jean step satisfies friction.law = "
                          "\"" + p_.friction + "\" at the step's end slip (dt = " +
                              format_value(h) + " s); " + dynamics_.jamming_report(),
                       "shorten dt, or reduce the friction");
  // A flank whose normal impulse would pull separates (no friction).
  if (sigma_fixed != 0 && !(sigma_fixed * (beta + alpha * friction) > 0.0)) {
    // (A penalty flank whose force pushes without the friction is no
    // separation: its force is the step's end state's, which then pushes
    // with no friction booked beside it. The law's friction, its viscous
    // term on wherever the flank carries a force, pulls the flank open;
    // without it the flank pushes: no impulse of the step is consistent,
    // as the Coulomb step's (coulomb_step_impulses). solve_train tries the
    // rotor's next mode.)
    if (!row && sigma_fixed * beta > 0.0)
      throw SimulationError(t, "no friction impulse of the Moreau-Jean step is consistent with "
                               "the penalty flank: friction.law = \"" + p_.friction +
                               "\" at the step's end slip pulls the flank open, without it the "
                               "flank pushes (its normal impulse " + format_value(beta) +
                               " N s, dt = " + format_value(h) + " s)",
                            "shorten dt, or lower the law's viscous coefficient");
    contact = false;
    return Impulses{};
  }
  Impulses impulses = solve(row, normal_target, rotor_target, friction);
  if (!row) impulses.normal = flank_impulse(h, theta, v0, impulses.velocity);
  impulses.friction = friction;
  impulses.law_slip = c + d * friction;
  if (nut) impulses.preload_normal = half_b(smooth_coefficient(c + d * friction, h));
  return impulses;
}

void DriveMoreau::book_bristles(double h, const double* y, double* y_next, double slip,
                                double normal_impulse) {
  const friction::Law& law = model_.law();
  if (transverse_state_ >= 0) {
    book_planar_bristles(h, y, y_next, slip, normal_impulse);
    return;
  }
  const double z1 = bristle_step(law, bristle_z0_, slip, h);
  y_next[bristle_state_] = z1 / bristle_range_;
  // The energy the bristles store over the step, |N| sigma0 (z+^2 - z0^2)
  // / 2 at the step's normal force |P_N| / h (the event-driven scheme's
  // integral of |N| sigma0 z z'); the friction's work beyond it is lost:
  // implicit Euler loses |N| sigma0 (z+ - z0)^2 / 2 >= 0 more than the
  // law's flow, the scheme's dissipation in the bristles.
  const double stored = std::abs(normal_impulse) / h * model_.flank_factor() *
                        0.5 * law.bristle_stiffness() * (z1 * z1 - bristle_z0_ * bristle_z0_);
  y_next[bristle_state_ + 1] = y[bristle_state_ + 1] + stored;
  y_next[layout_.energy_offset() + kFrictionLoss] -= stored;
}

// The 2-D bristles of a transverse slip's cone: both components' implicit
// Euler step at |(gamma+, w+)|, the energy both store (as book_bristles'),
// and the transverse component's coefficient for book_transverse.
void DriveMoreau::book_planar_bristles(double h, const double* y, double* y_next, double slip,
                                       double normal_impulse) {
  const friction::Law& law = model_.law();
  const double speed = std::hypot(slip, transverse_next_);
  const double z1 = planar_bristle_step(law, bristle_z0_, slip, speed, h);
  const double w1 = planar_bristle_step(law, bristle_w0_, transverse_next_, speed, h);
  y_next[bristle_state_] = z1 / bristle_range_;
  y_next[bristle_state_ + 2] = w1 / bristle_range_;
  transverse_bristle_coefficient_ =
      planar_bristle_coefficient(law, w1, transverse_next_, speed) * model_.flank_factor();
  const double stored = std::abs(normal_impulse) / h * model_.flank_factor() * 0.5 *
                        law.bristle_stiffness() *
                        (z1 * z1 - bristle_z0_ * bristle_z0_ + w1 * w1 - bristle_w0_ * bristle_w0_);
  y_next[bristle_state_ + 1] = y[bristle_state_ + 1] + stored;
  y_next[layout_.energy_offset() + kFrictionLoss] -= stored;
}

void DriveMoreau::book_transverse(double h, const double* y, double* y_next, bool contact,
                                  double friction_impulse, double normal_impulse, double slip) {
  // The transverse impulse against w+: its cone part put on the cone from
  // the root's helix impulse, |(P_T + h c gamma+, P_w + h c w+)| =
  // mu'(s0) |P_N| to round-off (from w+ / |(gamma+, w+)| with the step's
  // recomputed gamma+, whose round-off is of the size of w+ at its zeros,
  // it left the cone by 1 %), and the viscous impulse -h c w+. The
  // excitation that moves the nut across does the work -P_w w+ >= 0, which
  // the friction loses. (w+ = 0: the 1-D step, no transverse impulse; a
  // penalty flank out of contact: none, its viscous impulse neither.)
  double impulse = 0.0;
  if (bristle_state_ >= 0) {  // LuGre's: the transverse bristles' force (book_planar_bristles)
    if (contact)
      impulse = -(transverse_bristle_coefficient_ * std::abs(normal_impulse) +
                  dynamics_.law().viscous() * h * transverse_next_);
  } else if (transverse_next_ != 0.0 && contact) {
    const double viscous_step = dynamics_.law().viscous() * h;
    const double bound = transverse_mu_ * std::abs(normal_impulse);
    const double cone = friction_impulse + viscous_step * slip;
    impulse = -std::copysign(std::sqrt(std::max(0.0, (bound - cone) * (bound + cone))),
                             transverse_next_) -
              viscous_step * transverse_next_;
  }
  const double loss = -impulse * transverse_next_;
  y_next[transverse_state_] = y[transverse_state_] + loss;
  y_next[layout_.energy_offset() + kFrictionLoss] += loss;
  last_transverse_ = impulse / h;
}

}  // namespace leadscrew::model::drive
