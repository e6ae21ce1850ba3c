// Exact Coulomb friction (thesis eq. 2.17), with a static coefficient:
// stick holds while |T| <= mu_static |N|, slip at mu |N| (mu_static = mu:
// the thesis's law, decided by its LCP, eq. 3.10-3.14).
#include "leadscrew/friction/law.hpp"

namespace leadscrew::friction {

namespace {

class Coulomb final : public Law {
 public:
  Coulomb(double mu, double mu_static) : mu_(mu), mu_static_(mu_static) {}
  Resolution resolution() const override { return Resolution::set_valued; }
  double mu() const override { return mu_; }
  double mu_static() const override { return mu_static_; }

 private:
  double mu_, mu_static_;
};

}  // namespace

LawType coulomb_law() {
  LawType type;
  type.name = "coulomb";
  type.doc = "exact set-valued Coulomb friction (LCP, thesis eq. 3.10-3.14): stick while "
             "|friction| <= mu_static' |normal|, slip at mu'";
  type.parameters = {
      {"mu", "", "friction coefficient (kinetic)", 0.3},
      {"mu_static", "", "static friction coefficient, the stick limit and breakaway (>= mu)",
       std::numeric_limits<double>::quiet_NaN(), "mu", 0.0, std::numeric_limits<double>::infinity(),
       false, false, "mu"},
  };
  type.time_stepping = true;
  type.make = [](const std::vector<double>& v) -> std::unique_ptr<Law> {
    return std::make_unique<Coulomb>(v[0], v[1]);
  };
  return type;
}

}  // namespace leadscrew::friction
