#include "leadscrew/model/friction_block.hpp"

#include "leadscrew/model/result_checks.hpp"
#include "leadscrew/model/simulation_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/flank_lcp.hpp"
#include "leadscrew/integrate/event_driven.hpp"
#include "leadscrew/integrate/moreau.hpp"
#include "leadscrew/integrate/rk_stage_kernels.hpp"

namespace leadscrew::model {

namespace {

enum State { kPosition = 0, kVelocity = 1, kWorkForce = 2, kFrictionLoss = 3, kStateSize = 4 };

const std::vector<std::string>& block_channel_names() {
  static const std::vector<std::string> names = {
      "u",           "v",          "acceleration",  "friction_force", "normal_force",
      "force",       "stick",      "work_force",    "friction_loss",  "kinetic",
      "energy_residual"};
  return names;
}

// Writes the channels from the state, the load F(t) (evaluated by the caller,
// who has it) and the current friction force and acceleration.
void write_channels(const FrictionBlock& block, double kinetic0, double force, const double* y,
                    double acceleration, double friction_force, bool stick, double* out) {
  const double kinetic = 0.5 * block.mass * y[kVelocity] * y[kVelocity];
  out[0] = y[kPosition];
  out[1] = y[kVelocity];
  out[2] = acceleration;
  out[3] = friction_force;
  out[4] = block.normal_force();
  out[5] = force;
  out[6] = stick ? 1.0 : 0.0;
  out[7] = y[kWorkForce];
  out[8] = y[kFrictionLoss];
  out[9] = kinetic;
  out[10] = y[kWorkForce] - y[kFrictionLoss] - (kinetic - kinetic0);
}

// The load F(t) with a one-entry memo. Evaluations repeat their time: the
// last two stages of Dormand-Prince share t_n + h, the root functions and the
// output are evaluated at the step end, where the last stage was.
class LoadAtTime {
 public:
  explicit LoadAtTime(const Excitation& load) : load_(load) {}
  double operator()(double t) {
    if (t != time_) {  // always true for the initial NaN
      value_ = load_(t);
      time_ = t;
    }
    return value_;
  }

 private:
  const Excitation& load_;
  double time_ = std::numeric_limits<double>::quiet_NaN();
  double value_ = 0.0;
};

double initial_kinetic(const FrictionBlock& block) {
  return 0.5 * block.mass * block.initial_velocity * block.initial_velocity;
}

// ---------------------------------------------------------------------------
// Exact Coulomb friction, event-driven: modes stick, slip+, slip-.
class CoulombBlock final : public integrate::HybridSystem {
 public:
  explicit CoulombBlock(const FrictionBlock& block)
      : block_(block), force_(block.force), kinetic0_(initial_kinetic(block)) {}

  int size() const override { return kStateSize; }
  int root_count() const override { return 2; }

  void rhs(double t, const double* y, double* ydot) override {
    const double force = force_(t);
    const double friction = friction_force(force);
    const double acceleration = mode_ == Mode::stick ? 0.0 : (force - friction) / block_.mass;
    ydot[kPosition] = y[kVelocity];
    ydot[kVelocity] = acceleration;
    ydot[kWorkForce] = force * y[kVelocity];
    ydot[kFrictionLoss] = friction * y[kVelocity];
  }

  void roots(double t, const double* y, double* g) override {
    if (mode_ == Mode::stick) {
      // Stick ends when the force needed to stick reaches the friction bound.
      const double force = force_(t);
      g[0] = force - friction_bound();
      g[1] = force + friction_bound();
    } else {
      // Slip ends at a zero of the slip velocity.
      g[0] = y[kVelocity];
      g[1] = 1.0;
    }
  }

  void root_directions(int* directions) const override {
    switch (mode_) {
      case Mode::stick:  // leaving the friction cone outward
        directions[0] = 1;
        directions[1] = -1;
        break;
      case Mode::slip_positive:  // the velocity falls through zero
        directions[0] = -1;
        directions[1] = 0;
        break;
      default:
        directions[0] = 1;
        directions[1] = 0;
    }
  }

  void select_initial_mode(double t, double* y) override {
    if (y[kVelocity] > 0.0)
      mode_ = Mode::slip_positive;
    else if (y[kVelocity] < 0.0)
      mode_ = Mode::slip_negative;
    else
      mode_ = mode_from_lcp(t, Mode::stick);
  }

  std::string handle_event(double t, double* y, const std::vector<int>& root_info) override {
    const Mode before = mode_;
    if (mode_ == Mode::stick) {
      // Leaving the friction cone outward: the LCP at the boundary admits both
      // stick and slip (|F| = mu N); the crossing direction of the root breaks
      // the tie, which is the sign of the tangential jerk.
      Mode crossing = Mode::stick;
      if (root_info[0] > 0) crossing = Mode::slip_positive;
      if (root_info[1] < 0) crossing = Mode::slip_negative;
      if (crossing == Mode::stick) return "";  // re-entering the cone: nothing changes
      mode_ = mode_from_lcp(t, crossing);
    } else {
      if (root_info[0] == 0) return "";
      y[kVelocity] = 0.0;  // the root: project onto exactly zero slip
      mode_ = mode_from_lcp(t, Mode::stick);
    }
    if (mode_ == before) return "";
    return mode_name(before) + "->" + mode_name(mode_);
  }

  const std::vector<std::string>& channel_names() const override {
    return block_channel_names();
  }

  void channels(double t, const double* y, double* out) override {
    const double force = force_(t);
    const double friction = friction_force(force);
    const double acceleration = mode_ == Mode::stick ? 0.0 : (force - friction) / block_.mass;
    write_channels(block_, kinetic0_, force, y, acceleration, friction, mode_ == Mode::stick,
                   out);
  }

  std::vector<double> breakpoints() const override { return block_.force.breakpoints(); }
  long lcp_solves() const override { return lcp_solves_; }
  double max_step_hint() const override {
    return integrate::max_step_from_time_scales({block_.force.time_scale()});
  }

 private:
  enum class Mode { stick, slip_positive, slip_negative };

  static std::string mode_name(Mode mode) {
    switch (mode) {
      case Mode::stick:
        return "stick";
      case Mode::slip_positive:
        return "slip+";
      default:
        return "slip-";
    }
  }

  double friction_bound() const { return block_.mu * block_.normal_force(); }

  double friction_force(double force) const {
    switch (mode_) {
      case Mode::stick:
        return force;  // whatever keeps the block at rest (|F| <= mu N in stick)
      case Mode::slip_positive:
        return friction_bound();
      default:
        return -friction_bound();
    }
  }

  // The thesis's friction LCP (eq. 3.10-3.14) at zero slip velocity decides
  // between stick and slip in either direction. `tie` is the mode taken when
  // the LCP sits exactly on the cone boundary and admits stick as well.
  Mode mode_from_lcp(double t, Mode tie) {
    const double force = force_(t);
    // gamma' = F/m + lambda/m with the friction force lambda along +u,
    // normal force m g given (alpha = 0).
    const friction::FlankLcpResult solution =
        friction::solve_flank_lcp(force / block_.mass, 1.0 / block_.mass, 0.0,
                                  block_.normal_force(), block_.mu, 1, lcp_workspace_, lcp_options_);
    ++lcp_solves_;
    if (solution.status != lcp::Status::solved)
      throw SimulationError(t, "the friction LCP failed: " + lcp::status_name(solution.status),
                            "report this: the block's LCP always has a solution");
    if (solution.slip_acceleration > 0.0) return Mode::slip_positive;
    if (solution.slip_acceleration < 0.0) return Mode::slip_negative;
    return tie;
  }

  const FrictionBlock& block_;
  LoadAtTime force_;
  double kinetic0_;
  Mode mode_ = Mode::stick;
  long lcp_solves_ = 0;
  lcp::Workspace lcp_workspace_{2};
  lcp::Options lcp_options_{};
};

// ---------------------------------------------------------------------------
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
// 3.16) with as many instructions as glibc's atan: below the 10 % a
// replacement of a library function must gain (benchmarks/block/README.md).
class RegularizedBlock final : public integrate::HybridSystem {
 public:
  RegularizedBlock(const FrictionBlock& block, FrictionLaw law, double k_v)
      : block_(block),
        law_(law),
        k_v_(k_v),
        force_at_(block.force),
        kinetic0_(initial_kinetic(block)),
        inverse_mass_(1.0 / block.mass),
        friction_scale_(kTwoOverPi * block.mu * block.normal_force()) {}

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
    double acceleration = 0.0, friction = 0.0;
    evaluate(t, force, velocity, acceleration, friction);
    ydot[kPosition] = velocity;
    ydot[kVelocity] = acceleration;
    ydot[kWorkForce] = force * velocity;
    ydot[kFrictionLoss] = friction * velocity;
  }

  void select_initial_mode(double, double*) override {}
  std::string handle_event(double, double*, const std::vector<int>&) override { return ""; }

  const std::vector<std::string>& channel_names() const override {
    return block_channel_names();
  }

  void channels(double t, const double* y, double* out) override {
    const double force = force_at_(t);
    double acceleration = 0.0, friction = 0.0;
    evaluate(t, force, y[kVelocity], acceleration, friction);
    // "stick" of a regularized law: inside the regularization band |k_V x| <= 1.
    const double regularized = law_ == FrictionLaw::arctan_velocity ? y[kVelocity] : acceleration;
    write_channels(block_, kinetic0_, force, y, acceleration, friction,
                   std::abs(k_v_ * regularized) <= 1.0, out);
  }

  std::vector<double> breakpoints() const override { return block_.force.breakpoints(); }
  long nonlinear_iterations() const override { return nonlinear_iterations_; }

 private:
  void evaluate(double t, double force, double velocity, double& acceleration,
                double& friction) {
    if (law_ == FrictionLaw::arctan_velocity) {
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
    const double bound = block_.mu * block_.normal_force();
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
  FrictionLaw law_;
  double k_v_;
  LoadAtTime force_at_;
  double kinetic0_;
  double inverse_mass_;
  double friction_scale_;  // (2/pi) mu N
  long nonlinear_iterations_ = 0;
  // Memos (see the class comment). (F, a) = (0, 0) is an exact root of
  // eq. (3.15): the first predictor starts from it.
  double friction_velocity_ = nan_, friction_value_ = 0.0;
  double root_force_ = 0.0, root_acceleration_ = 0.0;
  double root_inverse_slope_ = 1.0 / (block_.mass + friction_scale_ * k_v_);
  double root_curvature_ = 0.0, root_jerk_ = 0.0;  // r'' and r''' at the last iterate
};

// ---------------------------------------------------------------------------
// Moreau-Jean time stepping with exact Coulomb friction: one velocity-level
// friction LCP per step (the impulse form of eq. 3.10-3.14).
class MoreauBlock final : public integrate::TimeSteppingSystem {
 public:
  explicit MoreauBlock(const FrictionBlock& block)
      : block_(block), kinetic0_(initial_kinetic(block)) {}

  int size() const override { return kStateSize; }

  void step(double t, double h, double theta, const double* y, double* y_next) override {
    const double force = block_.force(t + theta * h);
    const double free_velocity = y[kVelocity] + h * force / block_.mass;
    // Velocity level: new velocity = free velocity + impulse / m, the
    // impulse bounded by mu m g h.
    const friction::FlankLcpResult solution = friction::solve_flank_lcp(
        free_velocity, 1.0 / block_.mass, 0.0, block_.normal_force() * h, block_.mu, 1,
        lcp_workspace_, lcp_options_);
    ++lcp_solves_;
    if (solution.status != lcp::Status::solved)
      throw SimulationError(t, "the friction LCP failed: " + lcp::status_name(solution.status),
                            "reduce dt");
    const double velocity = solution.slip_acceleration;  // the new velocity on this level
    const double impulse = -solution.friction_force;     // opposing +u, as lambda_T in eq. 3.9
    y_next[kVelocity] = velocity;
    y_next[kPosition] = y[kPosition] + h * ((1.0 - theta) * y[kVelocity] + theta * velocity);
    y_next[kWorkForce] = y[kWorkForce] + force * (y_next[kPosition] - y[kPosition]);
    // The friction impulse acts at the new velocity (maximal dissipation):
    // its power is never negative.
    y_next[kFrictionLoss] = y[kFrictionLoss] + impulse * velocity;
    last_friction_force_ = impulse / h;
    last_acceleration_ = (velocity - y[kVelocity]) / h;
    last_stick_ = velocity == 0.0;
  }

  const std::vector<std::string>& channel_names() const override {
    return block_channel_names();
  }

  void channels(double t, const double* y, double* out) override {
    write_channels(block_, kinetic0_, block_.force(t), y, last_acceleration_, last_friction_force_,
                   last_stick_, out);
  }

  long lcp_solves() const override { return lcp_solves_; }

 private:
  const FrictionBlock& block_;
  double kinetic0_;
  long lcp_solves_ = 0;
  double last_friction_force_ = 0.0;
  double last_acceleration_ = 0.0;
  bool last_stick_ = true;
  lcp::Workspace lcp_workspace_{2};
  lcp::Options lcp_options_{};
};

}  // namespace

FrictionBlock::FrictionBlock(double mass_, double mu_, double g_, Excitation force_,
                             double initial_position_, double initial_velocity_)
    : mass(require_positive("mass", mass_)),
      mu(require_nonnegative("mu", mu_)),
      g(require_nonnegative("g", g_)),
      force(std::move(force_)),
      initial_position(require_finite("initial_position", initial_position_)),
      initial_velocity(require_finite("initial_velocity", initial_velocity_)) {}

namespace {
// Made once: a short simulation takes microseconds.
const std::vector<std::string>& fitting_integrators(FrictionLaw law) {
  static const std::vector<std::string> exact = {"event_driven", "moreau"};
  static const std::vector<std::string> regularized = integrate::integrator_names();
  return law == FrictionLaw::coulomb ? exact : regularized;
}
}  // namespace

std::vector<std::string> integrators_for(FrictionLaw law) { return fitting_integrators(law); }

integrate::SimulationResult simulate(const FrictionBlock& block,
                                     const BlockSimulationOptions& options) {
  const std::vector<std::string>& allowed = fitting_integrators(options.friction);
  if (std::find(allowed.begin(), allowed.end(), options.integrator) == allowed.end())
    require_choice("integrator", options.integrator, allowed,
                   "friction = \"" + friction_law_name(options.friction) + "\"");
  if (options.friction != FrictionLaw::coulomb) require_positive("k_v", options.k_v);
  integrate::validate_output_request(options.output, 0.0);
  if (options.integrator == "moreau") {
    check_step_resolves_loads(options.dt, options.output.t_end, {&block.force});
  } else {
    check_meaningful_tolerances(options.integrator_options, options.output.t_end);
  }

  Eigen::VectorXd y0(kStateSize);
  y0 << block.initial_position, block.initial_velocity, 0.0, 0.0;
  integrate::SimulationResult result;
  if (options.friction == FrictionLaw::coulomb && options.integrator == "moreau") {
    MoreauBlock system(block);
    const integrate::MoreauOptions moreau{options.dt, options.theta,
                                          options.integrator_options.max_steps};
    result = integrate::simulate_moreau(system, 0.0, y0, options.output, moreau);
  } else {
    integrate::EventDrivenOptions driver;
    driver.integrator_options = options.integrator_options;
    driver.max_events = options.max_events;
    if (options.friction == FrictionLaw::coulomb) {
      // Smooth phases of the block are non-stiff: our own Verner 6(5) pair
      // with exact event location is an order of magnitude cheaper than CVODE.
      driver.integrator = "rk_verner6";
      CoulombBlock system(block);
      result = integrate::simulate_event_driven(system, 0.0, y0, options.output, driver);
      result.integrator = "event_driven";
    } else {
      driver.integrator = options.integrator;
      RegularizedBlock system(block, options.friction, options.k_v);
      result = integrate::simulate_event_driven(system, 0.0, y0, options.output, driver);
    }
  }
  result.friction = friction_law_name(options.friction);
  ResultCheckSpec spec;
  spec.slip = "v";
  spec.friction_sign = -1.0;  // lambda_T opposes the block: m u'' = F - lambda_T
  spec.work = {"work_force"};
  spec.stored = {"kinetic"};
  spec.losses = {"friction_loss"};
  spec.t_end = options.output.t_end;
  spec.cone_mu = options.friction == FrictionLaw::coulomb ? block.mu : -1.0;
  spec.law = options.friction == FrictionLaw::coulomb ? ResultCheckSpec::Law::coulomb
             : options.friction == FrictionLaw::arctan_velocity
                 ? ResultCheckSpec::Law::arctan_velocity
                 : ResultCheckSpec::Law::none;
  spec.law_mu = block.mu;
  spec.k_v = options.k_v;
  spec.friction_dissipates = options.friction != FrictionLaw::arctan_acceleration;
  spec.slip_resolution = options.integrator_options.atol;  // the slip is the state's velocity
  spec.time_stepping = options.integrator == "moreau";
  spec.rtol = options.integrator_options.rtol;
  spec.atol = options.integrator_options.atol;
  spec.momentum_factor = std::sqrt(2.0 * block.mass);
  spec.quadratures = kStateSize - 2;
  check_result(spec, result);
  if (options.check) integrate::enforce_checks(result);
  return result;
}

}  // namespace leadscrew::model
