// The friction block with a smooth law of the slip velocity (a set-valued
// law's regularization, e.g. Stribeck's) or with LuGre's bristles: one smooth
// mode, no roots.
//   velocity:  lambda_T = kappa(v) N + viscous v
//   bristle:   z' = v - sigma0 |v| z / mu(|v|),
//              lambda_T = N (sigma0 z + sigma1 z') + viscous v.
// The state integrates lambda_T v as the friction's power; the bristles'
// energy N sigma0 z^2 / 2 is elastic (block_common.cpp). The bristle state
// is z / bristle_range (friction::Law::bristle_range), of size 1: its error
// is controlled at its own scale, not at atol in metres.
#include <cmath>

#include "block_system.hpp"

namespace leadscrew::model::block {

namespace {

class SmoothBlock final : public integrate::HybridSystem {
 public:
  SmoothBlock(const FrictionBlock& block, const friction::Law& law)
      : block_(block),
        law_(law),
        bristle_(law.resolution() == friction::Resolution::bristle),
        bristle_range_(law.bristle_range()),
        force_(block.force),
        kinetic0_(initial_kinetic(block)) {}

  int size() const override { return bristle_ ? kStateSize + 1 : kStateSize; }
  int quadrature_count() const override { return 0; }

  void rhs(double t, const double* y, double* ydot) override {
    const double velocity = y[kVelocity];
    const double force = force_(t);
    const double spring = block_.spring_force(t, y[kPosition]);
    double bristle_rate = 0.0;
    const double friction = friction_force(velocity, deflection(y), bristle_rate);
    ydot[kPosition] = velocity;
    ydot[kVelocity] = (force + spring - friction) / block_.mass;
    ydot[kWorkForce] = applied_power(block_, force, spring, velocity);
    ydot[kFrictionLoss] = friction * velocity;
    if (bristle_) ydot[kBristle] = bristle_rate / bristle_range_;
  }

  void select_initial_mode(double, double*) override {}
  std::string handle_event(double, double*, const std::vector<int>&) override { return ""; }

  const std::vector<std::string>& channel_names() const override {
    return block::channel_names(bristle_);
  }

  void channels(double t, const double* y, double* out) override {
    Row row;
    row.force = force_(t);
    const double spring = block_.spring_force(t, y[kPosition]);
    double bristle_rate = 0.0;
    const double z = deflection(y);
    row.friction = friction_force(y[kVelocity], z, bristle_rate);
    row.acceleration = (row.force + spring - row.friction) / block_.mass;
    // "stick": within the law's regularization band, or (LuGre) the
    // bristles carrying the load below the slip's steady state.
    row.stick = bristle_ ? std::abs(block_.normal_force() * law_.bristle_stiffness() * z) <
                               law_.slip_mu(std::abs(y[kVelocity])) * block_.normal_force()
                         : std::abs(law_.gain() * y[kVelocity]) <= 1.0;
    row.bristle_energy = bristle_ ? block_.normal_force() * law_.stored_energy(z) : 0.0;
    row.bristle_deflection = z;
    write_channels(block_, kinetic0_, 0.0, t, y, row, bristle_, out);
  }

  std::vector<double> breakpoints() const override { return block_.force.breakpoints(); }

 private:
  // The bristles' deflection z [m] from the state (0 without bristles).
  double deflection(const double* y) const { return bristle_ ? y[kBristle] * bristle_range_ : 0.0; }

  double friction_force(double velocity, double z, double& bristle_rate) const {
    const double normal = block_.normal_force();
    if (bristle_) {
      bristle_rate = law_.bristle_rate(velocity, z);
      return normal * law_.bristle_coefficient(velocity, z) + law_.viscous() * velocity;
    }
    return normal * law_.velocity_coefficient(velocity) + law_.viscous() * velocity;
  }

  const FrictionBlock& block_;
  const friction::Law& law_;
  bool bristle_;
  double bristle_range_;
  LoadAtTime force_;
  double kinetic0_;
};

}  // namespace

std::unique_ptr<integrate::HybridSystem> make_smooth_block(const FrictionBlock& block,
                                                           const friction::Law& law) {
  return std::make_unique<SmoothBlock>(block, law);
}

}  // namespace leadscrew::model::block
