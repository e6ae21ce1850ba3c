#include "leadscrew/model/friction_block.hpp"

#include <cmath>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/flank_lcp.hpp"
#include "leadscrew/integrate/event_driven.hpp"
#include "leadscrew/integrate/moreau.hpp"

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

// Writes the channels from the state and the current friction force and acceleration.
void write_channels(const FrictionBlock& block, double kinetic0, double t, const double* y,
                    double acceleration, double friction_force, bool stick, double* out) {
  const double kinetic = 0.5 * block.mass * y[kVelocity] * y[kVelocity];
  out[0] = y[kPosition];
  out[1] = y[kVelocity];
  out[2] = acceleration;
  out[3] = friction_force;
  out[4] = block.normal_force();
  out[5] = block.force(t);
  out[6] = stick ? 1.0 : 0.0;
  out[7] = y[kWorkForce];
  out[8] = y[kFrictionLoss];
  out[9] = kinetic;
  out[10] = y[kWorkForce] - y[kFrictionLoss] - (kinetic - kinetic0);
}

double initial_kinetic(const FrictionBlock& block) {
  return 0.5 * block.mass * block.initial_velocity * block.initial_velocity;
}

// ---------------------------------------------------------------------------
// Exact Coulomb friction, event-driven: modes stick, slip+, slip-.
class CoulombBlock final : public integrate::HybridSystem {
 public:
  explicit CoulombBlock(const FrictionBlock& block)
      : block_(block), kinetic0_(initial_kinetic(block)) {}

  int size() const override { return kStateSize; }
  int root_count() const override { return 2; }

  void rhs(double t, const double* y, double* ydot) override {
    const double force = block_.force(t);
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
      const double force = block_.force(t);
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
    const double force = block_.force(t);
    const double friction = friction_force(force);
    const double acceleration = mode_ == Mode::stick ? 0.0 : (force - friction) / block_.mass;
    write_channels(block_, kinetic0_, t, y, acceleration, friction, mode_ == Mode::stick, out);
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
    const double force = block_.force(t);
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
  double kinetic0_;
  Mode mode_ = Mode::stick;
  long lcp_solves_ = 0;
  lcp::Workspace lcp_workspace_{2};
  lcp::Options lcp_options_{};
};

// ---------------------------------------------------------------------------
// Regularized friction (eq. 3.15 / 3.16): one smooth mode, no roots.
class RegularizedBlock final : public integrate::HybridSystem {
 public:
  RegularizedBlock(const FrictionBlock& block, FrictionLaw law, double k_v)
      : block_(block), law_(law), k_v_(k_v), kinetic0_(initial_kinetic(block)) {}

  int size() const override { return kStateSize; }

  void rhs(double t, const double* y, double* ydot) override {
    const double force = block_.force(t);
    double acceleration = 0.0, friction = 0.0;
    evaluate(t, force, y[kVelocity], acceleration, friction);
    ydot[kPosition] = y[kVelocity];
    ydot[kVelocity] = acceleration;
    ydot[kWorkForce] = force * y[kVelocity];
    ydot[kFrictionLoss] = friction * y[kVelocity];
  }

  void select_initial_mode(double, double*) override {}
  std::string handle_event(double, double*, const std::vector<int>&) override { return ""; }

  const std::vector<std::string>& channel_names() const override {
    return block_channel_names();
  }

  void channels(double t, const double* y, double* out) override {
    const double force = block_.force(t);
    double acceleration = 0.0, friction = 0.0;
    evaluate(t, force, y[kVelocity], acceleration, friction);
    // "stick" of a regularized law: inside the regularization band |k_V x| <= 1.
    const double regularized = law_ == FrictionLaw::arctan_velocity ? y[kVelocity] : acceleration;
    write_channels(block_, kinetic0_, t, y, acceleration, friction,
                   std::abs(k_v_ * regularized) <= 1.0, out);
  }

  std::vector<double> breakpoints() const override { return block_.force.breakpoints(); }
  long nonlinear_iterations() const override { return nonlinear_iterations_; }

 private:
  void evaluate(double t, double force, double velocity, double& acceleration,
                double& friction) {
    const double normal = block_.normal_force();
    if (law_ == FrictionLaw::arctan_velocity) {
      friction = arctan_friction(block_.mu, normal, k_v_, velocity);
      acceleration = (force - friction) / block_.mass;
      return;
    }
    acceleration = solve_acceleration(t, force);
    friction = force - block_.mass * acceleration;
  }

  // Eq. (3.15): m a + (2/pi) mu N atan(k_V a) - F = 0. The left side rises
  // strictly in a, and a lies in [(F - mu N)/m, (F + mu N)/m]: safeguarded
  // Newton inside that bracket converges for every F.
  double solve_acceleration(double t, double force) {
    const double mass = block_.mass;
    const double bound = block_.mu * block_.normal_force();
    double low = (force - bound) / mass, high = (force + bound) / mass;
    auto residual = [&](double a) {
      return mass * a + arctan_friction(block_.mu, block_.normal_force(), k_v_, a) - force;
    };
    // Start from the previous evaluation's root (successive evaluations are
    // close in time), kept inside the bracket that always holds the root.
    double a = std::min(std::max(last_acceleration_, low), high);
    const double scale = std::max({std::abs(low), std::abs(high), 1e-300});
    // Newton on this S-shaped residual can cycle slowly inside the bracket:
    // as in rtsafe, bisect whenever a Newton step is not at least twice as
    // short as the one before.
    double previous_step = high - low;
    for (int iteration = 0; iteration < 200; ++iteration) {
      ++nonlinear_iterations_;
      const double r = residual(a);
      if (r == 0.0) return last_acceleration_ = a;
      if (r > 0.0)
        high = a;
      else
        low = a;
      const double slope =
          mass + 2.0 / 3.14159265358979323846 * bound * k_v_ / (1.0 + k_v_ * k_v_ * a * a);
      double next = a - r / slope;
      if (!(next > low && next < high) || 2.0 * std::abs(next - a) > previous_step)
        next = 0.5 * (low + high);
      previous_step = std::abs(next - a);
      if (std::abs(next - a) <= 4e-16 * scale || high - low <= 4e-16 * scale)
        return last_acceleration_ = next;
      a = next;
    }
    throw SimulationError(t, "the acceleration of eq. (3.15) did not converge in 200 iterations",
                          "lower k_v");
  }

  const FrictionBlock& block_;
  FrictionLaw law_;
  double k_v_;
  double kinetic0_;
  long nonlinear_iterations_ = 0;
  double last_acceleration_ = 0.0;
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
    write_channels(block_, kinetic0_, t, y, last_acceleration_, last_friction_force_, last_stick_,
                   out);
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

std::vector<std::string> integrators_for(FrictionLaw law) {
  if (law == FrictionLaw::coulomb) return {"event_driven", "moreau"};
  std::vector<std::string> names = integrate::integrator_names();
  return names;
}

integrate::SimulationResult simulate(const FrictionBlock& block,
                                     const BlockSimulationOptions& options) {
  const std::vector<std::string> allowed = integrators_for(options.friction);
  require_choice("integrator", options.integrator, allowed,
                 "friction = \"" + friction_law_name(options.friction) + "\"");
  if (options.friction != FrictionLaw::coulomb) require_positive("k_v", options.k_v);

  Eigen::VectorXd y0(kStateSize);
  y0 << block.initial_position, block.initial_velocity, 0.0, 0.0;
  integrate::SimulationResult result;
  if (options.friction == FrictionLaw::coulomb && options.integrator == "moreau") {
    MoreauBlock system(block);
    integrate::MoreauOptions moreau;
    moreau.dt = options.dt;
    moreau.theta = options.theta;
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
  return result;
}

}  // namespace leadscrew::model
