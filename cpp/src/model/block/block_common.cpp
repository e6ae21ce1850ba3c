#include "block_system.hpp"

namespace leadscrew::model::block {

const std::vector<std::string>& channel_names(bool bristle) {
  static const std::vector<std::string> plain = {
      "u",           "v",          "acceleration",  "friction_force", "normal_force",
      "force",       "stick",      "work_force",    "friction_loss",  "kinetic",
      "energy_residual", "spring_force", "elastic"};
  static const std::vector<std::string> with_bristle = [] {
    std::vector<std::string> names = plain;
    names.push_back("bristle_deflection");
    return names;
  }();
  return bristle ? with_bristle : plain;
}

double initial_kinetic(const FrictionBlock& block) {
  return 0.5 * block.mass * block.initial_velocity * block.initial_velocity;
}

void write_channels(const FrictionBlock& block, double kinetic0, double /*elastic0*/, double t,
                    const double* y, const Row& row, bool bristle, double* out) {
  const double kinetic = 0.5 * block.mass * y[kVelocity] * y[kVelocity];
  const double spring = block.spring_force(t, y[kPosition]);
  // The spring starts relaxed, the bristles undeflected: no elastic energy at t = 0.
  const double spring_energy =
      block.stiffness > 0.0 ? 0.5 * spring * spring / block.stiffness : 0.0;
  const double elastic = spring_energy + row.bristle_energy;
  // The state integrates the friction's power; what the bristles store of it
  // is elastic, not lost.
  const double friction_loss = y[kFrictionLoss] - row.bristle_energy;
  out[0] = y[kPosition];
  out[1] = y[kVelocity];
  out[2] = row.acceleration;
  out[3] = row.friction;
  out[4] = block.normal_force();
  out[5] = row.force;
  out[6] = row.stick ? 1.0 : 0.0;
  out[7] = y[kWorkForce];
  out[8] = friction_loss;
  out[9] = kinetic;
  out[10] = y[kWorkForce] - friction_loss - (kinetic - kinetic0) - elastic;
  out[11] = spring;
  out[12] = elastic;
  if (bristle) out[13] = row.bristle_deflection;
}

}  // namespace leadscrew::model::block
