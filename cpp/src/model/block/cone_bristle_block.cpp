// The block on a plane that slips across its path at the prescribed
// velocity w(t) (issue 34; docs/physics/transverse_slip.md) with LuGre's
// bristles as an isotropic 2-D law (one smooth mode, no roots): the slip is
// the vector gamma = (v, w), the bristles' deflection the vector z,
//   z' = gamma - sigma0 |gamma| z / mu(|gamma|),
//   lambda = N (sigma0 z + sigma1 z') + viscous gamma,
// the 1-D law's (lugre.cpp) with |gamma| for |v|: in steady sliding z =
// mu(|gamma|) gamma / (sigma0 |gamma|) and lambda is Stribeck's 2-D cone; the
// set |z| <= max(mu, mu_static) / sigma0 is invariant (d|z|^2/dt <=
// 2 |gamma| |z| (1 - sigma0 |z| / mu)). The bristles' energy
// N sigma0 |z|^2 / 2 is elastic (write_channels). The state carries z over
// the law's bristle_range, a state of size 1 per component.
#include <cmath>

#include "block_system.hpp"

namespace leadscrew::model::block {

namespace {

constexpr int kPathBristle = kConeStateSize, kTransverseBristle = kConeStateSize + 1;

class ConeBristleBlock final : public integrate::HybridSystem {
 public:
  ConeBristleBlock(const FrictionBlock& block, const friction::Law& law)
      : block_(block),
        law_(law),
        force_(block.force),
        transverse_(*block.transverse_velocity),
        kinetic0_(initial_kinetic(block)),
        range_(law.bristle_range()) {}

  int size() const override { return kConeStateSize + 2; }

  void rhs(double t, const double* y, double* ydot) override {
    const double force = force_(t);
    const double spring = block_.spring_force(t, y[kPosition]);
    const Forces f = forces(y, transverse_(t));
    ydot[kPosition] = y[kVelocity];
    ydot[kVelocity] = (force + spring - f.path) / block_.mass;
    ydot[kWorkForce] = applied_power(block_, force, spring, y[kVelocity]);
    ydot[kFrictionLoss] = f.path * y[kVelocity] + f.across * f.w;
    ydot[kTransverseWork] = f.across * f.w;
    ydot[kPathBristle] = f.path_rate / range_;
    ydot[kTransverseBristle] = f.across_rate / range_;
  }

  void select_initial_mode(double, double*) override {}
  std::string handle_event(double, double*, const std::vector<int>&) override { return ""; }

  const std::vector<std::string>& channel_names() const override {
    static const std::vector<std::string> names = [] {
      std::vector<std::string> result = cone_channel_names();
      result.emplace_back("bristle_deflection");
      result.emplace_back("bristle_deflection_transverse");
      return result;
    }();
    return names;
  }

  void channels(double t, const double* y, double* out) override {
    Row row;
    row.force = force_(t);
    const Forces f = forces(y, transverse_(t));
    row.friction = f.path;
    row.acceleration =
        (row.force + block_.spring_force(t, y[kPosition]) - f.path) / block_.mass;
    const double z_path = y[kPathBristle] * range_, z_across = y[kTransverseBristle] * range_;
    const double z = std::hypot(z_path, z_across);
    // "stick": the bristles carry less than the slip's steady state (the
    // 1-D block's, smooth_block.cpp, on the magnitudes).
    row.stick = law_.bristle_stiffness() * z < law_.slip_mu(f.speed);
    row.bristle_energy = block_.normal_force() * law_.stored_energy(z);
    write_cone_channels(block_, kinetic0_, t, y, row, f.w, f.across, out);
    const std::size_t cone = cone_channel_names().size();
    out[cone] = z_path;
    out[cone + 1] = z_across;
  }

  std::vector<double> breakpoints() const override { return cone_breakpoints(block_); }

 private:
  struct Forces {
    double w, speed, path, across, path_rate, across_rate;
  };

  Forces forces(const double* y, double w) const {
    Forces f;
    f.w = w;
    const double v = y[kVelocity];
    f.speed = std::hypot(v, w);
    const double sigma0 = law_.bristle_stiffness(), sigma1 = law_.bristle_damping();
    const double relaxation = sigma0 * f.speed / law_.slip_mu(f.speed);
    const double z_path = y[kPathBristle] * range_, z_across = y[kTransverseBristle] * range_;
    f.path_rate = v - relaxation * z_path;
    f.across_rate = w - relaxation * z_across;
    const double normal = block_.normal_force(), viscous = law_.viscous();
    f.path = normal * (sigma0 * z_path + sigma1 * f.path_rate) + viscous * v;
    f.across = normal * (sigma0 * z_across + sigma1 * f.across_rate) + viscous * w;
    return f;
  }

  const FrictionBlock& block_;
  const friction::Law& law_;
  LoadAtTime force_;
  const Excitation& transverse_;
  double kinetic0_;
  double range_;
};

}  // namespace

std::unique_ptr<integrate::HybridSystem> make_cone_bristle_block(const FrictionBlock& block,
                                                                 const friction::Law& law) {
  return std::make_unique<ConeBristleBlock>(block, law);
}

}  // namespace leadscrew::model::block
