// The friction block with a set-valued law, Moreau-Jean time stepping: one
// velocity-level decision per step (the impulse form of eq. 3.10-3.14).
#include <cmath>

#include "block_system.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/friction/flank_lcp.hpp"

namespace leadscrew::model::block {

namespace {

class MoreauBlock final : public integrate::TimeSteppingSystem {
 public:
  MoreauBlock(const FrictionBlock& block, const friction::Law& law)
      : block_(block), law_(law), kinetic0_(initial_kinetic(block)), plain_(law.plain_coulomb()) {}

  int size() const override { return kStateSize; }

  void step(double t, double h, double theta, const double* y, double* y_next) override {
    const MoreauFreeStep free = moreau_free_step(block_, t, h, theta, y);
    const double mass = free.mass, free_velocity = free.free_velocity;
    double velocity = 0.0, impulse = 0.0;  // impulse opposing +u, as lambda_T in eq. 3.9
    if (plain_) {
      // Velocity level: new velocity = free velocity + impulse / m, the
      // impulse bounded by mu m g h.
      const friction::FlankLcpResult solution = friction::solve_flank_lcp(
          free_velocity, 1.0 / mass, 0.0, block_.normal_force() * h, law_.mu(), 1,
          lcp_workspace_, lcp_options_);
      ++lcp_solves_;
      if (solution.status != lcp::Status::solved)
        throw SimulationError(t, "the friction LCP failed: " + lcp::status_name(solution.status),
                              "reduce dt");
      velocity = solution.slip_acceleration;  // the new velocity on this level
      impulse = -solution.friction_force;
    } else if (std::abs(mass * free_velocity) <= law_.mu_static() * block_.normal_force() * h) {
      velocity = 0.0;  // the impulse that stops it is within the stick limit
      impulse = mass * free_velocity;
    } else {
      // Slip against the free velocity at mu(|v|) of the step's start, the
      // viscous term at its end (implicit): m (v - v_free) = -s (mu N h) - c h v.
      const double s = free_velocity > 0.0 ? 1.0 : -1.0;
      const double coulomb = law_.slip_mu(std::abs(y[kVelocity])) * block_.normal_force() * h;
      velocity = (mass * free_velocity - s * coulomb) / (mass + law_.viscous() * h);
      impulse = mass * (free_velocity - velocity);
    }
    moreau_advance(block_, free, h, theta, velocity, y, y_next);
    // The friction impulse acts at the new velocity (maximal dissipation):
    // its power is never negative.
    y_next[kFrictionLoss] = y[kFrictionLoss] + impulse * velocity;
    last_friction_force_ = impulse / h;
    last_acceleration_ = (velocity - y[kVelocity]) / h;
    last_stick_ = velocity == 0.0;
  }

  const std::vector<std::string>& channel_names() const override {
    return block::channel_names(false);
  }

  void channels(double t, const double* y, double* out) override {
    Row row;
    row.force = block_.force(t);
    row.acceleration = last_acceleration_;
    row.friction = last_friction_force_;
    row.stick = last_stick_;
    write_channels(block_, kinetic0_, 0.0, t, y, row, false, out);
  }

  long lcp_solves() const override { return lcp_solves_; }

 private:
  const FrictionBlock& block_;
  const friction::Law& law_;
  double kinetic0_;
  bool plain_;
  long lcp_solves_ = 0;
  double last_friction_force_ = 0.0;
  double last_acceleration_ = 0.0;
  bool last_stick_ = true;
  lcp::Workspace lcp_workspace_{2};
  lcp::Options lcp_options_{};
};

}  // namespace

std::unique_ptr<integrate::TimeSteppingSystem> make_moreau_block(const FrictionBlock& block,
                                                                 const friction::Law& law) {
  return std::make_unique<MoreauBlock>(block, law);
}

}  // namespace leadscrew::model::block
