// The friction block with the thesis's arctan laws (eq. 3.15, 3.16): a fast
// path, its right-hand side the cost of a step (the block benchmark's
// regularized rows).
#include <algorithm>
#include <cmath>
#include <limits>

#include "block_system.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/integrate/rk_stage_kernels.hpp"

namespace leadscrew::model::block {

namespace {

// Regularized friction (eq. 3.15 / 3.16): one smooth mode, no roots.
//
// The right-hand side is evaluated ~6 times per step, and its cost is that of
// the step: the law is kept to one sine and one arctan per distinct argument.
// Evaluations repeat their arguments: Dormand-Prince's last two stages share
// the time t_n + h, and the output at a step end takes the state of its last
// stage; a one-entry memo of F(t) and of lambda_T(v) (or a(F)) returns those
// without recomputation (bitwise-equal arguments give the same value).
// std::atan: an own arctan kernel (removed in issue 18) made a block run at
// most 8 % faster inside C++ (eq. 3.15's Newton solve; up to 5 % for eq.
// 3.16) with as many instructions as glibc's atan: below the 10 % an own
// math kernel must gain (benchmarks/block/README.md).
class RegularizedBlock final : public integrate::HybridSystem {
 public:
  RegularizedBlock(const FrictionBlock& block, const friction::Law& law)
      : block_(block),
        velocity_law_(law.resolution() == friction::Resolution::velocity),
        k_v_(law.gain()),
        force_at_(block.force),
        kinetic0_(initial_kinetic(block)),
        inverse_mass_(1.0 / block.mass),
        friction_scale_(kTwoOverPi * law.mu() * block.normal_force()),
        bound_(law.mu() * block.normal_force()) {}

  int size() const override { return kStateSize; }
  // Its own Runge-Kutta stage loop, the rhs inlined (rk_stage_kernels.hpp).
  // It has no root functions, so the event-driven driver hands the
  // integrator this object itself (a system with roots is wrapped in a
  // RootGuard, which offers no loop of its own: the engine's runs).
  integrate::RkStageKernel explicit_rk_stages(int stage_count) const override {
    return integrate::rk_kernels::stage_kernel_for<RegularizedBlock, kStateSize>(stage_count);
  }

  void rhs(double t, const double* y, double* ydot) override {
    // The state is read before any store: a store to a double (the memos
    // of the load and of the friction law, ydot) might change y for all
    // the compiler knows, and the velocity would be loaded back from
    // memory. Read first, it stays in a register from the Runge-Kutta
    // stage that computed it (rk_stage_kernels.hpp inlines this rhs).
    const double velocity = y[kVelocity];
    const double force = force_at_(t);
    // The spring (the stick-slip oscillator) adds to the applied force; the
    // thesis's block has none (a branch the predictor learns).
    const double spring = block_.stiffness > 0.0 ? block_.spring_force(t, y[kPosition]) : 0.0;
    double acceleration = 0.0, friction = 0.0;
    evaluate(t, force + spring, velocity, acceleration, friction);
    ydot[kPosition] = velocity;
    ydot[kVelocity] = acceleration;
    ydot[kWorkForce] = applied_power(block_, force, spring, velocity);
    ydot[kFrictionLoss] = friction * velocity;
  }

  void select_initial_mode(double, double*) override {}
  std::string handle_event(double, double*, const std::vector<int>&) override { return ""; }

  const std::vector<std::string>& channel_names() const override {
    return block::channel_names(false);
  }

  void channels(double t, const double* y, double* out) override {
    Row row;
    row.force = force_at_(t);
    const double spring = block_.stiffness > 0.0 ? block_.spring_force(t, y[kPosition]) : 0.0;
    evaluate(t, row.force + spring, y[kVelocity], row.acceleration, row.friction);
    // "stick" of a regularized law: inside the regularization band |k_V x| <= 1.
    const double regularized = velocity_law_ ? y[kVelocity] : row.acceleration;
    row.stick = std::abs(k_v_ * regularized) <= 1.0;
    write_channels(block_, kinetic0_, 0.0, t, y, row, false, out);
  }

  std::vector<double> breakpoints() const override { return block_.force.breakpoints(); }
  long nonlinear_iterations() const override { return nonlinear_iterations_; }

 private:
  void evaluate(double t, double force, double velocity, double& acceleration,
                double& friction) {
    if (velocity_law_) {
      // Eq. (3.16): lambda_T = (2/pi) mu N atan(k_V v).
      if (velocity != friction_velocity_) {
        friction_value_ = friction_scale_ * std::atan(k_v_ * velocity);
        friction_velocity_ = velocity;
      }
      friction = friction_value_;
      acceleration = (force - friction) * inverse_mass_;
      return;
    }
    if (force != root_force_) solve_acceleration(t, force);
    acceleration = root_acceleration_;
    friction = force - block_.mass * acceleration;
  }

  // Eq. (3.15): r(a) = m a + c atan(k_V a) - F = 0 with c = (2/pi) mu N.
  // r' = m + c k_V / (1 + (k_V a)^2) >= m > 0, so the root is unique, and it
  // lies in [(F - mu N)/m, (F + mu N)/m] since |c atan| < mu N. With
  // x = k_V a and q = 1 / (1 + x^2): r'' = -2 c k_V^2 x q^2 and
  // r''' = -2 c k_V^3 (1 - 3 x^2) q^3.
  //
  // Predictor: the Taylor polynomial of degree 3 of the inverse function
  // a(F) at the previous root (a0, F0): with u = (F - F0) / r',
  //   a = a0 + u - r'' u^2 / (2 r') + (3 r''^2 - r' r''') u^3 / (6 r'^2),
  // the derivatives taken at the last iterate (as good for a predictor): no
  // arctan, no division. Corrector: Chebyshev's method (Newton's step d plus
  // -r'' d^2 / (2 r'), third order), with the bracket kept and Newton, then
  // bisection, whenever the step leaves it or does not halve (rtsafe). It
  // stops once Newton's own error bound is below half an ulp of a, and then
  // returns Newton's iterate a + d: its error is r''(xi) e^2 / (2 r'(a)) with
  // e = root - a ~ d, and |r''(x)| <= min(2 c k_V^3 |x|, (3 sqrt 3 / 8) c k_V^2);
  // bounding |xi| by |a| + |d| and e^2 by 2 d^2 makes the bound safe (the
  // ulp is that of a, or the root's condition eps (|m a| + |c atan| + |F|) / r'
  // when that is larger); when its own (cubic) error bound is below that, the
  // Chebyshev iterate is returned instead. The divisions do not wait for the
  // arctan. 1 or 2 arctan evaluations per solve (measured on the benchmark
  // block: 1.2 to 1.9 on average for k_V = 1 to 100; Newton from the last
  // root with a "step below an ulp" test took ~4), the residual at rounding
  // level.
  void solve_acceleration(double t, double force) {
    const double mass = block_.mass;
    const double c = friction_scale_;
    const double k = k_v_;
    const double ck = c * k;
    const double bound = bound_;
    double low = (force - bound) * inverse_mass_, high = (force + bound) * inverse_mass_;
    double a = 0.0;
    {
      const double s = root_inverse_slope_;  // 1 / r'
      const double u = (force - root_force_) * s;
      const double c2 = 0.5 * root_curvature_ * s;
      const double c3 = (3.0 * root_curvature_ * root_curvature_ * s - root_jerk_) * s / 6.0;
      a = root_acceleration_ + u * (1.0 + u * (-c2 + u * c3));
    }
    if (!(a > low && a < high)) a = 0.5 * (low + high);
    const double peak_curvature = 0.6495190528383290 * ck * k;  // max |r''|
    const double bracket_tolerance =
        4e-16 * std::max({std::abs(low), std::abs(high), 1e-300});
    double previous_step = high - low;
    for (int iteration = 0; iteration < 200; ++iteration) {
      ++nonlinear_iterations_;
      const double x = k * a;
      const double d = 1.0 + x * x;
      const double inverse_slope = d / (mass * d + ck);  // 1 / r'(a)
      const double q = 1.0 / d;
      const double friction = c * std::atan(x);
      const double r = mass * a + friction - force;
      // r'' and r''' here, for the corrector and the next predictor.
      const double curvature_here = -2.0 * ck * k * x * q * q;
      root_inverse_slope_ = inverse_slope;
      root_curvature_ = curvature_here;
      root_jerk_ = -2.0 * ck * k * k * (1.0 - 3.0 * x * x) * q * q * q;
      if (r == 0.0) return accept(force, a);
      if (r > 0.0)
        high = a;
      else
        low = a;
      const double step = -r * inverse_slope;  // Newton
      const double newton = a + step;
      if (!(newton > low && newton < high) || 2.0 * std::abs(step) > previous_step) {
        const double middle = 0.5 * (low + high);  // bisection
        previous_step = std::abs(middle - a);
        if (high - low <= bracket_tolerance) return accept(force, middle);
        a = middle;
        continue;
      }
      previous_step = std::abs(step);
      const double reach = std::abs(a) + std::abs(step);
      const double curvature = std::min(2.0 * ck * k * k * reach, peak_curvature);
      const double error_bound = curvature * step * step * inverse_slope;
      // Rounding: r carries eps times its terms, a + d that over r'. Below
      // that floor (taken at a + d, where c atan = F - m a) nothing is
      // certain; and the terms at a must be those at the root, or a step
      // from far (a tiny root after a large a) inherits their rounding.
      const double terms_here = std::abs(mass * a) + std::abs(friction) + std::abs(force);
      const double terms_root =
          std::abs(mass * newton) + std::abs(force) + std::abs(force - mass * newton);
      const double floor = std::max(std::abs(newton), terms_root * inverse_slope);
      const bool near_root = terms_here <= 2.0 * terms_root;
      if (error_bound <= 0.5 * eps_ * floor && near_root) return accept(force, newton);
      const double chebyshev = newton - 0.5 * curvature_here * step * step * inverse_slope;
      if (!(chebyshev > low && chebyshev < high)) {
        a = newton;
        continue;
      }
      // Chebyshev's error: with A = |r''(a)| / r', B = max |r'''| / r' =
      // 2 c k_V^3 / r' and the Taylor expansion of r at a to r'''(xi),
      // e - d = -r''(a) e^2 / (2 r') - r'''(xi) e^3 / (6 r'), so |e| <= 2 |d|
      // while A |d| <= 1/4 and B d^2 <= 1/10, and the iterate's error
      // r''(a) (d^2 - e^2) / (2 r') - r'''(xi) e^3 / (6 r') is at most
      // (3 A^2 + 2 B) |d|^3.
      const double A = std::abs(curvature_here) * inverse_slope;
      const double B = 2.0 * ck * k * k * inverse_slope;
      const double size = std::abs(step);
      if (A * size <= 0.25 && B * size * size <= 0.1 && near_root &&
          (3.0 * A * A + 2.0 * B) * size * size * size <= 0.5 * eps_ * floor)
        return accept(force, chebyshev);
      a = chebyshev;
    }
    throw SimulationError(t, "the acceleration of eq. (3.15) did not converge in 200 iterations",
                          "lower k_v");
  }

  void accept(double force, double acceleration) {
    root_force_ = force;
    root_acceleration_ = acceleration;
  }

  static constexpr double eps_ = 2.220446049250313e-16;
  static constexpr double nan_ = std::numeric_limits<double>::quiet_NaN();

  const FrictionBlock& block_;
  bool velocity_law_;  // eq. (3.16); else eq. (3.15)
  double k_v_;
  LoadAtTime force_at_;
  double kinetic0_;
  double inverse_mass_;
  double friction_scale_;  // (2/pi) mu N
  double bound_;           // mu N
  long nonlinear_iterations_ = 0;
  // Memos (see the class comment). (F, a) = (0, 0) is an exact root of
  // eq. (3.15): the first predictor starts from it.
  double friction_velocity_ = nan_, friction_value_ = 0.0;
  double root_force_ = 0.0, root_acceleration_ = 0.0;
  double root_inverse_slope_ = 1.0 / (block_.mass + friction_scale_ * k_v_);
  double root_curvature_ = 0.0, root_jerk_ = 0.0;  // r'' and r''' at the last iterate
};

}  // namespace

std::unique_ptr<integrate::HybridSystem> make_regularized_block(const FrictionBlock& block,
                                                                const friction::Law& law) {
  return std::make_unique<RegularizedBlock>(block, law);
}

}  // namespace leadscrew::model::block
