// The arctan regularization in the slip velocity (thesis eq. 2.25, 3.16):
// T = -(2/pi) mu |N| atan(k_V gamma).
#include "leadscrew/friction/law.hpp"

namespace leadscrew::friction {

namespace {

class ArctanVelocity final : public Law {
 public:
  ArctanVelocity(double mu, double k_v) : mu_(mu), k_v_(k_v) {}
  Resolution resolution() const override { return Resolution::velocity; }
  double mu() const override { return mu_; }
  double velocity_coefficient(double slip) const override {
    return kTwoOverPi * mu_ * std::atan(k_v_ * slip);
  }
  double gain() const override { return k_v_; }

 private:
  double mu_, k_v_;
};

}  // namespace

LawType arctan_velocity_law() {
  LawType type;
  type.name = "arctan_velocity";
  type.doc = "arctan regularization in the slip velocity (eq. 3.16): "
             "friction = -(2/pi) mu' |normal| atan(k_v slip_velocity)";
  type.parameters = {
      {"mu", "", "friction coefficient", 0.3},
      {"k_v", "s/m", "regularization gain k_V: the slope of the law at zero slip over mu", 1e4,
       nullptr, 0.0, std::numeric_limits<double>::infinity(), true},
  };
  type.ode = true;
  type.make = [](const std::vector<double>& v) -> std::unique_ptr<Law> {
    return std::make_unique<ArctanVelocity>(v[0], v[1]);
  };
  return type;
}

}  // namespace leadscrew::friction
