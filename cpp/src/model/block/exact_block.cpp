// The block with a set-valued law (exact Coulomb with a static coefficient,
// Stribeck's curve), event-driven: modes stick, slip+, slip-.
//
// With the applied force A(t, u) = F(t) + F_spring(t, u):
//   stick:  u' = 0, lambda_T = A (whatever keeps the block at rest), until
//           |A| reaches mu_static N (roots A -+ mu_static N);
//   slip s: lambda_T = s (mu(|v|) N + viscous |v|), until v falls to zero.
// At zero slip the thesis's LCP decides stick or slip where the law is plain
// Coulomb (one coefficient, eq. 3.10-3.14); with a static coefficient the
// block sticks where |A| <= mu_static N and slips toward A otherwise (it
// then slips at mu(0+) <= mu_static: the acceleration is A's).
#include <cmath>

#include "block_system.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/friction/flank_lcp.hpp"

namespace leadscrew::model::block {

namespace {

// `kSpring`: the block has the stick-slip oscillator's spring (stiffness >
// 0). Without it (the thesis's block) the right-hand side skips the spring's
// terms: 10 % of the exact block's run (issue 17's benchmark).
// `kPlain`: the law is plain Coulomb without a viscous term (one
// coefficient: the slip force is the constant mu m g), the thesis's block;
// its right-hand side skips the general law's speed-dependent terms
// (callgrind, the block benchmark: 27k of its 550k instructions per call,
// 30 per right-hand side; issue 17's benchmark).
template <bool kSpring, bool kPlain>
class ExactBlock final : public integrate::HybridSystem {
 public:
  ExactBlock(const FrictionBlock& block, const friction::Law& law)
      : block_(block),
        law_(law),
        force_(block.force),
        kinetic0_(initial_kinetic(block)),
        stick_mu_(law.mu_static()),
        viscous_(law.viscous()),
        normal_force_(block.normal_force()),
        plain_slip_force_(law.mu_static() * block.normal_force()) {}

  int size() const override { return kStateSize; }
  int root_count() const override { return 2; }

  void rhs(double t, const double* y, double* ydot) override {
    const double force = force_(t);
    const double spring = spring_force(t, y);
    const double friction = friction_force(force + spring, y[kVelocity]);
    const double acceleration =
        mode_ == Mode::stick ? 0.0 : (force + spring - friction) / block_.mass;
    ydot[kPosition] = y[kVelocity];
    ydot[kVelocity] = acceleration;
    ydot[kWorkForce] = kSpring ? applied_power(block_, force, spring, y[kVelocity])
                               : force * y[kVelocity];
    ydot[kFrictionLoss] = friction * y[kVelocity];
  }

  void roots(double t, const double* y, double* g) override {
    if (mode_ == Mode::stick) {
      // Stick ends when the force needed to stick reaches the stick limit.
      const double applied = force_(t) + spring_force(t, y);
      g[0] = applied - stick_limit();
      g[1] = applied + stick_limit();
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
      mode_ = mode_at_rest(t, y, Mode::stick);
  }

  std::string handle_event(double t, double* y, const std::vector<int>& root_info) override {
    const Mode before = mode_;
    if (mode_ == Mode::stick) {
      // Leaving the friction cone outward: at the boundary both stick and slip
      // are consistent (|A| = mu_static N); the crossing direction of the root
      // breaks the tie, which is the sign of the tangential jerk.
      Mode crossing = Mode::stick;
      if (root_info[0] > 0) crossing = Mode::slip_positive;
      if (root_info[1] < 0) crossing = Mode::slip_negative;
      if (crossing == Mode::stick) return "";  // re-entering the cone: nothing changes
      mode_ = mode_at_rest(t, y, crossing);
    } else {
      if (root_info[0] == 0) return "";
      y[kVelocity] = 0.0;  // the root: project onto exactly zero slip
      mode_ = mode_at_rest(t, y, Mode::stick);
    }
    if (mode_ == before) return "";
    return mode_name(before) + "->" + mode_name(mode_);
  }

  const std::vector<std::string>& channel_names() const override {
    return block::channel_names(false);
  }

  void channels(double t, const double* y, double* out) override {
    Row row;
    row.force = force_(t);
    const double applied = row.force + spring_force(t, y);
    row.friction = friction_force(applied, y[kVelocity]);
    row.acceleration = mode_ == Mode::stick ? 0.0 : (applied - row.friction) / block_.mass;
    row.stick = mode_ == Mode::stick;
    write_channels(block_, kinetic0_, 0.0, t, y, row, false, out);
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

  double spring_force(double t, const double* y) const {
    return kSpring ? block_.spring_force(t, y[kPosition]) : 0.0;
  }

  double stick_limit() const { return stick_mu_ * normal_force_; }

  // (The law's constant coefficients are read once: a virtual call per
  // right-hand side cost the exact block 4 % of its run. Plain Coulomb's
  // slip coefficient is its mu, the same number slip_mu returns.)
  double friction_force(double applied, double velocity) const {
    // Stick: whatever keeps the block at rest (|A| <= mu_static N).
    if (mode_ == Mode::stick) return applied;
    double magnitude = plain_slip_force_;
    if constexpr (!kPlain) {
      const double speed = std::abs(velocity);
      magnitude = law_.slip_mu(speed) * normal_force_ + viscous_ * speed;
    }
    return mode_ == Mode::slip_positive ? magnitude : -magnitude;
  }

  // Stick or slip at zero slip velocity (state at rest). `tie` is the mode
  // taken where the force sits exactly on the cone's boundary.
  Mode mode_at_rest(double t, const double* y, Mode tie) {
    const double applied = force_(t) + spring_force(t, y);
    if constexpr (!kPlain) {
      if (std::abs(applied) < stick_limit()) return Mode::stick;
      if (std::abs(applied) > stick_limit())
        return applied > 0.0 ? Mode::slip_positive : Mode::slip_negative;
      return tie;
    }
    // The thesis's friction LCP (eq. 3.10-3.14): gamma' = A/m + lambda/m
    // with the friction force lambda along +u, normal force m g given
    // (alpha = 0).
    const friction::FlankLcpResult solution = friction::solve_flank_lcp(
        applied / block_.mass, 1.0 / block_.mass, 0.0, block_.normal_force(), law_.mu(), 1,
        lcp_workspace_, lcp_options_);
    ++lcp_solves_;
    if (solution.status != lcp::Status::solved)
      throw SimulationError(t, "the friction LCP failed: " + lcp::status_name(solution.status),
                            "report this: the block's LCP always has a solution");
    if (solution.slip_acceleration > 0.0) return Mode::slip_positive;
    if (solution.slip_acceleration < 0.0) return Mode::slip_negative;
    return tie;
  }

  const FrictionBlock& block_;
  const friction::Law& law_;
  LoadAtTime force_;
  double kinetic0_;
  double stick_mu_;  // mu_static (plain Coulomb: mu)
  double viscous_;   // [N s/m]
  double normal_force_;      // m g [N]
  double plain_slip_force_;  // plain Coulomb's mu m g [N]
  Mode mode_ = Mode::stick;
  long lcp_solves_ = 0;
  lcp::Workspace lcp_workspace_{2};
  lcp::Options lcp_options_{};
};

}  // namespace

std::unique_ptr<integrate::HybridSystem> make_exact_block(const FrictionBlock& block,
                                                          const friction::Law& law) {
  const bool plain = law.plain_coulomb();
  if (block.stiffness > 0.0) {
    if (plain) return std::make_unique<ExactBlock<true, true>>(block, law);
    return std::make_unique<ExactBlock<true, false>>(block, law);
  }
  if (plain) return std::make_unique<ExactBlock<false, true>>(block, law);
  return std::make_unique<ExactBlock<false, false>>(block, law);
}

}  // namespace leadscrew::model::block
