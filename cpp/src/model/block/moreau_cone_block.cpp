// The block on a plane that slips across its path at the prescribed
// velocity w(t) (issue 34; docs/physics/transverse_slip.md), Moreau-Jean
// time stepping with the exact 2-D cone of a set-valued law (Coulomb;
// Stribeck's mu(|(v, w)|) at the step's start and its viscous term at the
// end, as the 1-D block's). With w+ = w(t + h) given,
// the step's friction impulse P = (P_path, P_across) acts on the new slip
// (v+, w+) (maximal dissipation, as the 1-D block's):
//   |P| <= mu_static N h                  where v+ = w+ = 0,
//   P = mu N h (v+, w+) / |(v+, w+)|      otherwise,
// and W (v+ - v_free) = -P_path. Where w+ != 0 the path component is a
// smooth, strictly increasing function of v+, so v+ is the one root of
//   g(v) = W (v - v_free) + mu N h v / sqrt(v^2 + w+^2),
// between 0 and v_free: a bracketed Newton iteration to round-off, no
// polygon of the cone. Where w+ = 0 the step is the 1-D block's.
#include <algorithm>
#include <cmath>

#include "block_system.hpp"
#include "leadscrew/core/errors.hpp"

namespace leadscrew::model::block {

namespace {

// The root v of W (v - v_free) + a v / sqrt(v^2 + w^2) + b v (a = mu N h
// > 0, b = viscous h >= 0, w != 0), bracketed by 0 and v_free: Newton's
// steps kept inside the bracket (bisection where one leaves it), to the
// bracket's round-off.
double cone_slip_velocity(double W, double v_free, double a, double b, double w) {
  double lo = std::min(0.0, v_free), hi = std::max(0.0, v_free);
  double v = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double s = std::hypot(v, w);
    const double g = W * (v - v_free) + a * v / s + b * v;
    if (g == 0.0) return v;
    (g > 0.0 ? hi : lo) = v;
    const double slope = W + a * w * w / (s * s * s) + b;
    double next = v - g / slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == v || hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * std::abs(hi))
      return next;
    v = next;
  }
  return v;  // (the bracket halves at least every other step: never reached)
}

class MoreauConeBlock final : public integrate::TimeSteppingSystem {
 public:
  MoreauConeBlock(const FrictionBlock& block, const friction::Law& law)
      : block_(block),
        law_(law),
        transverse_(*block.transverse_velocity),
        kinetic0_(initial_kinetic(block)) {
    last_.stick = true;  // (the row at t = 0: at rest)
  }

  int size() const override { return kConeStateSize; }

  void step(double t, double h, double theta, const double* y, double* y_next) override {
    const MoreauFreeStep free = moreau_free_step(block_, t, h, theta, y);
    const double mass = free.mass, free_velocity = free.free_velocity;
    const double w = transverse_(t + h);
    const double normal_impulse = block_.normal_force() * h;
    // Stribeck's coefficient at the step's start slip speed (as the 1-D
    // block's), the viscous term at its end (implicit).
    const double coulomb =
        law_.slip_mu(std::hypot(y[kVelocity], transverse_(t))) * normal_impulse;
    const double viscous = law_.viscous() * h;
    double velocity = 0.0, path = 0.0, across = 0.0;  // impulses opposing +u, +w
    if (w != 0.0) {
      const double v = cone_slip_velocity(mass, free_velocity, coulomb, viscous, w);
      const double s = std::hypot(v, w);
      const double magnitude = coulomb + viscous * s;
      path = magnitude * v / s;  // on the cone to round-off
      across = magnitude * w / s;
      velocity = free_velocity - path / mass;
    } else if (std::abs(mass * free_velocity) <= law_.mu_static() * normal_impulse) {
      path = mass * free_velocity;  // stick: both slip components vanish
    } else {
      const double s = free_velocity > 0.0 ? 1.0 : -1.0;
      velocity = (mass * free_velocity - s * coulomb) / (mass + viscous);
      path = mass * (free_velocity - velocity);
    }
    moreau_advance(block_, free, h, theta, velocity, y, y_next);
    // The impulse acts at the new slip (v+, w+): its power is never negative;
    // the plane's excitation does the transverse part's work.
    y_next[kFrictionLoss] = y[kFrictionLoss] + path * velocity + across * w;
    y_next[kTransverseWork] = y[kTransverseWork] + across * w;
    last_.friction = path / h;
    last_.acceleration = (velocity - y[kVelocity]) / h;
    last_.stick = velocity == 0.0 && w == 0.0;
    last_transverse_friction_ = across / h;
  }

  const std::vector<std::string>& channel_names() const override { return cone_channel_names(); }

  void channels(double t, const double* y, double* out) override {
    Row row = last_;
    row.force = block_.force(t);
    write_cone_channels(block_, kinetic0_, t, y, row, transverse_(t), last_transverse_friction_,
                        out);
  }

 private:
  const FrictionBlock& block_;
  const friction::Law& law_;
  const Excitation& transverse_;
  double kinetic0_;
  Row last_;
  double last_transverse_friction_ = 0.0;
};

}  // namespace

std::unique_ptr<integrate::TimeSteppingSystem> make_moreau_cone_block(const FrictionBlock& block,
                                                                      const friction::Law& law) {
  return std::make_unique<MoreauConeBlock>(block, law);
}

}  // namespace leadscrew::model::block
