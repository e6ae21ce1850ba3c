// The thesis's arctan regularization in the slip acceleration (eq. 3.15):
// T = -(2/pi) mu |N| atan(k_V gamma'). Its friction opposes the slip
// acceleration, not the slip: it may push the slip, and it does not converge
// to Coulomb's law as k_V grows (docs/physics/rigid_drive.md). Kept for
// comparison with the thesis; its runs are checked for their energy balance
// only.
#include "leadscrew/friction/law.hpp"

namespace leadscrew::friction {

namespace {

class ArctanAcceleration final : public Law {
 public:
  ArctanAcceleration(double mu, double k_v) : mu_(mu), k_v_(k_v) {}
  Resolution resolution() const override { return Resolution::acceleration; }
  double mu() const override { return mu_; }
  double acceleration_coefficient(double slip_acceleration) const override {
    return kTwoOverPi * mu_ * std::atan(k_v_ * slip_acceleration);
  }
  double gain() const override { return k_v_; }

 private:
  double mu_, k_v_;
};

}  // namespace

LawType arctan_acceleration_law() {
  LawType type;
  type.name = "arctan_acceleration";
  type.doc = "the thesis's arctan regularization in the slip acceleration (eq. 3.15): "
             "friction = -(2/pi) mu' |normal| atan(k_v slip_acceleration); it may do positive "
             "work (its friction opposes the acceleration)";
  type.parameters = {
      {"mu", "", "friction coefficient", 0.3},
      {"k_v", "s^2/m", "regularization gain in the slip acceleration", 1e4, nullptr, 0.0,
       std::numeric_limits<double>::infinity(), true},
  };
  type.ode = true;
  type.make = [](const std::vector<double>& v) -> std::unique_ptr<Law> {
    return std::make_unique<ArctanAcceleration>(v[0], v[1]);
  };
  return type;
}

}  // namespace leadscrew::friction
