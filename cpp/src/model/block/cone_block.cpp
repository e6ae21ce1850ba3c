// The block on a plane that slips across its path at the prescribed
// velocity w(t) (issue 34; docs/physics/transverse_slip.md): exact Coulomb
// friction as an isotropic 2-D cone, event-driven. The slip is (v, w);
//   slip:   lambda = mu N (v, w) / |(v, w)|, the path component a smooth
//           function of v wherever w != 0 (no event where v crosses zero);
//   stick:  v = 0 where w = 0 and stays 0 (held: w' = 0 to the right),
//           lambda_path = A (whatever keeps the block at rest) while |A| <=
//           mu_static N, lambda_transverse = 0 (nothing loads it).
// A stick ends where |A| reaches mu_static N or w leaves zero; a slip ends
// where v falls to zero while w is held at zero. Where w only passes
// through zero the slip vector may vanish for an instant: the slip goes on
// (the integrator restarts at w's root, so no step straddles the cone's
// apex). The excitation that moves the plane does the transverse friction's
// work, lambda_transverse w: the state books it (kTransverseWork) beside the
// 2-D friction loss lambda . (v, w).
#include <algorithm>
#include <cmath>

#include "block_system.hpp"

namespace leadscrew::model::block {

void write_cone_channels(const FrictionBlock& block, double kinetic0, double t, const double* y,
                         const Row& row, double transverse_velocity, double transverse_friction,
                         double* out) {
  write_channels(block, kinetic0, 0.0, t, y, row, false, out);
  const std::size_t plain = channel_names(false).size();
  // The plane's excitation puts in what the transverse friction takes out.
  out[10] += y[kTransverseWork];
  out[plain] = transverse_velocity;
  out[plain + 1] = transverse_friction;
  out[plain + 2] = y[kTransverseWork];
}

std::vector<double> cone_breakpoints(const FrictionBlock& block) {
  std::vector<double> times = block.force.breakpoints();
  for (double time : block.transverse_velocity->breakpoints()) times.push_back(time);
  std::sort(times.begin(), times.end());
  return times;
}

const std::vector<std::string>& cone_channel_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> result = channel_names(false);
    for (const char* name : {"transverse_velocity", "transverse_friction", "work_transverse"})
      result.emplace_back(name);
    return result;
  }();
  return names;
}

namespace {

class ConeBlock final : public integrate::HybridSystem {
 public:
  ConeBlock(const FrictionBlock& block, const friction::Law& law)
      : block_(block),
        law_(law),
        force_(block.force),
        transverse_(*block.transverse_velocity),
        kinetic0_(initial_kinetic(block)),
        normal_force_(block.normal_force()) {}

  int size() const override { return kConeStateSize; }
  int root_count() const override { return 4; }

  void rhs(double t, const double* y, double* ydot) override {
    const double force = force_(t);
    const double spring = block_.spring_force(t, y[kPosition]);
    const double w = transverse_(t);
    double path = 0.0, across = 0.0;
    friction(force + spring, y[kVelocity], w, path, across);
    ydot[kPosition] = y[kVelocity];
    ydot[kVelocity] = mode_ == Mode::stick ? 0.0 : (force + spring - path) / block_.mass;
    ydot[kWorkForce] = applied_power(block_, force, spring, y[kVelocity]);
    ydot[kFrictionLoss] = path * y[kVelocity] + across * w;
    ydot[kTransverseWork] = across * w;
  }

  void roots(double t, const double* y, double* g) override {
    const double w = transverse_(t);
    if (mode_ == Mode::stick) {
      const double applied = force_(t) + block_.spring_force(t, y[kPosition]);
      const double limit = law_.mu_static() * normal_force_;
      g[0] = applied - limit;
      g[1] = applied + limit;
      g[2] = w;  // the plane starts to slip across: either way
      g[3] = w;
    } else {
      g[0] = y[kVelocity];
      g[1] = w;
      g[2] = 1.0;
      g[3] = 1.0;
    }
  }

  void root_directions(int* directions) const override {
    if (mode_ == Mode::stick) {
      directions[0] = 1;
      directions[1] = -1;
      directions[2] = 1;
      directions[3] = -1;
    } else {
      // v's zero matters only while w is held at zero: it falls through zero
      // against the slip's sign (round-off just after a start from rest may
      // show a crossing back, which is none).
      directions[0] = path_sign_ > 0.0 ? -1 : 1;
      directions[1] = 0;
      directions[2] = 0;
      directions[3] = 0;
    }
  }

  void select_initial_mode(double t, double* y) override {
    mode_ = Mode::slip;
    path_sign_ = y[kVelocity] >= 0.0 ? 1.0 : -1.0;
    if (y[kVelocity] == 0.0) settle_at_rest(t, y);
  }

  std::string handle_event(double t, double* y, const std::vector<int>& root_info) override {
    const Mode before = mode_;
    if (mode_ == Mode::stick) {
      mode_ = Mode::slip;
      settle_at_rest(t, y);
    } else if (root_info[0] != 0) {
      path_sign_ = -path_sign_;  // v crossed zero
      if (held_at_zero(t)) {
        y[kVelocity] = 0.0;  // the root: project onto exactly zero slip
        settle_at_rest(t, y);
      }
    }
    // (A root of w in slip: the slip vector reverses across; the integrator
    // restarts there, nothing else changes.)
    if (mode_ == before) return "";
    return before == Mode::stick ? "stick->slip" : "slip->stick";
  }

  const std::vector<std::string>& channel_names() const override { return cone_channel_names(); }

  void channels(double t, const double* y, double* out) override {
    Row row;
    row.force = force_(t);
    const double applied = row.force + block_.spring_force(t, y[kPosition]);
    const double w = transverse_(t);
    double across = 0.0;
    friction(applied, y[kVelocity], w, row.friction, across);
    row.acceleration = mode_ == Mode::stick ? 0.0 : (applied - row.friction) / block_.mass;
    row.stick = mode_ == Mode::stick;
    write_cone_channels(block_, kinetic0_, t, y, row, w, across, out);
  }

  std::vector<double> breakpoints() const override { return cone_breakpoints(block_); }
  double max_step_hint() const override {
    return integrate::max_step_from_time_scales(
        {block_.force.time_scale(), transverse_.time_scale()});
  }

 private:
  enum class Mode { stick, slip };

  // w is zero at t and stays zero (its slope to the right is zero).
  bool held_at_zero(double t) const {
    return transverse_(t) == 0.0 && transverse_.derivative(t) == 0.0;
  }

  // At v = 0: stick where w is held at zero and |A| <= mu_static N, slip
  // otherwise (toward A where w is held at zero).
  void settle_at_rest(double t, const double* y) {
    if (!held_at_zero(t)) return;
    const double applied = force_(t) + block_.spring_force(t, y[kPosition]);
    if (std::abs(applied) <= law_.mu_static() * normal_force_) {
      mode_ = Mode::stick;
    } else {
      mode_ = Mode::slip;
      path_sign_ = applied > 0.0 ? 1.0 : -1.0;
    }
  }

  // The friction's components (lambda on the block's slip (v, w), opposing
  // it): `path` along +u, `across` along +w.
  void friction(double applied, double v, double w, double& path, double& across) const {
    across = 0.0;
    if (mode_ == Mode::stick) {
      path = applied;
      return;
    }
    const double speed = std::hypot(v, w);
    const double magnitude = law_.slip_mu(speed) * normal_force_ + law_.viscous() * speed;
    if (w == 0.0 && v != 0.0) {
      // The plane at rest across: the 1-D slip, its friction against the
      // mode's slip sign (exact_block.cpp's), not sign(v): a trial stage
      // past v's zero continues the mode smoothly, and the root of v ends it
      // (against sign(v), the integrator ground to a halt at v = 0 with w
      // held at zero, its steps rejected across the jump).
      path = path_sign_ * magnitude;
    } else if (speed > 0.0) {
      path = magnitude * v / speed;
      across = magnitude * w / speed;
    } else {  // the cone's apex for an instant: the set-valued law's value at rest
      path = std::clamp(applied, -magnitude, magnitude);
    }
  }

  const FrictionBlock& block_;
  const friction::Law& law_;
  LoadAtTime force_;
  const Excitation& transverse_;
  double kinetic0_;
  double normal_force_;
  Mode mode_ = Mode::slip;
  double path_sign_ = 1.0;  // the sign of v in slip (its last crossing)
};

}  // namespace

std::unique_ptr<integrate::HybridSystem> make_cone_block(const FrictionBlock& block,
                                                         const friction::Law& law) {
  return std::make_unique<ConeBlock>(block, law);
}

}  // namespace leadscrew::model::block
