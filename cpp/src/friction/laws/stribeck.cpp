// Coulomb friction with Stribeck's curve and a viscous term: stick while
// |T| <= mu_static |N|, slip at mu(|gamma|) |N| + viscous |gamma| against the
// slip, with mu(v) = mu + (mu_static - mu) exp(-(v / v_s)^delta): the
// breakaway at mu_static falls toward mu as the slip speeds up. Set-valued
// (exact, event-driven or Moreau-Jean); an ODE integrator runs its arctan
// regularization kappa(gamma) = (2/pi) atan(k_v gamma) mu(|gamma|).
#include "leadscrew/friction/stribeck.hpp"

namespace leadscrew::friction {

double stribeck_curve(const StribeckCurve& c, double speed) {
  if (c.mu_static == c.mu) return c.mu;
  return c.mu + (c.mu_static - c.mu) * std::exp(-std::pow(speed / c.velocity, c.exponent));
}

namespace {

// What both forms of the law share: the curve, the viscous term, the gain.
class StribeckCommon : public Law {
 public:
  StribeckCommon(StribeckCurve curve, double viscous, double k_v)
      : curve_(curve), viscous_(viscous), k_v_(k_v) {}
  double mu() const override { return curve_.mu; }
  double mu_static() const override { return curve_.mu_static; }
  double slip_mu(double speed) const override { return stribeck_curve(curve_, speed); }
  double viscous() const override { return viscous_; }

 protected:
  StribeckCurve curve_;
  double viscous_, k_v_;
};

// Its regularization for the ODE integrators.
class StribeckRegularized final : public StribeckCommon {
 public:
  using StribeckCommon::StribeckCommon;
  Resolution resolution() const override { return Resolution::velocity; }
  double velocity_coefficient(double slip) const override {
    return kTwoOverPi * std::atan(k_v_ * slip) * stribeck_curve(curve_, std::abs(slip));
  }
  double gain() const override { return k_v_; }
};

class Stribeck final : public StribeckCommon {
 public:
  using StribeckCommon::StribeckCommon;
  Resolution resolution() const override { return Resolution::set_valued; }
  std::unique_ptr<Law> regularized() const override {
    return std::make_unique<StribeckRegularized>(curve_, viscous_, k_v_);
  }
};

}  // namespace

std::vector<ParameterInfo> stribeck_parameters() {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return {
      {"mu", "", "kinetic friction coefficient (the curve's limit at high slip speed)", 0.3},
      {"mu_static", "", "static friction coefficient, the stick limit and breakaway (>= mu)",
       nan, "mu", 0.0, inf, false, false, "mu"},
      {"stribeck_velocity", "m/s", "Stribeck velocity v_s: the slip speed of the curve's fall",
       1e-3, nullptr, 0.0, inf, true},
      {"stribeck_exponent", "", "Stribeck exponent delta of exp(-(v / v_s)^delta)", 2.0, nullptr,
       0.0, inf, true},
      {"viscous", "N*s/m", "viscous friction: a force of viscous * slip_velocity against the slip",
       0.0},
  };
}

LawType stribeck_law() {
  LawType type;
  type.name = "stribeck";
  type.doc = "Coulomb friction with Stribeck's curve mu(v) = mu + (mu_static - mu) "
             "exp(-(v / stribeck_velocity)^stribeck_exponent) and a viscous term; set-valued "
             "(exact breakaway at mu_static), with an ODE integrator regularized by k_v";
  type.parameters = stribeck_parameters();
  type.parameters.push_back({"k_v", "s/m",
                             "regularization gain used with an ODE integrator: kappa = (2/pi) "
                             "atan(k_v slip_velocity) mu(|slip_velocity|)",
                             1e4, nullptr, 0.0, std::numeric_limits<double>::infinity(), true});
  type.time_stepping = true;
  type.ode = true;
  type.make = [](const std::vector<double>& v) -> std::unique_ptr<Law> {
    return std::make_unique<Stribeck>(StribeckCurve{v[0], v[1], v[2], v[3]}, v[4], v[5]);
  };
  return type;
}

}  // namespace leadscrew::friction
