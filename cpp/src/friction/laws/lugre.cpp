// LuGre friction (Canudas de Wit, Olsson, Astrom and Lischinsky, IEEE TAC
// 40(3), 1995): a bristle deflection z per contact,
//   z' = gamma - sigma0 |gamma| z / mu(|gamma|),
//   T = -|N| (sigma0 z + sigma1 z') - viscous gamma,
// with Stribeck's curve mu(v); sigma0 and sigma1 per unit normal force, so
// that the law scales with the flank load. In steady sliding z = mu sign(gamma)
// / sigma0 and T is Stribeck's; for small displacements the bristles are a
// spring of stiffness sigma0 |N| (presliding). The bristle energy
// |N| sigma0 z^2 / 2 is elastic energy in the account.
#include <vector>
#include "leadscrew/friction/stribeck.hpp"

namespace leadscrew::friction {

namespace {

class LuGre final : public Law {
 public:
  LuGre(StribeckCurve curve, double viscous, double sigma0, double sigma1)
      : curve_(curve), viscous_(viscous), sigma0_(sigma0), sigma1_(sigma1) {}
  Resolution resolution() const override { return Resolution::bristle; }
  double mu() const override { return curve_.mu; }
  double mu_static() const override { return curve_.mu_static; }
  double slip_mu(double speed) const override { return stribeck_curve(curve_, speed); }
  double viscous() const override { return viscous_; }
  double bristle_rate(double slip, double z) const override {
    return slip - sigma0_ * std::abs(slip) * z / stribeck_curve(curve_, std::abs(slip));
  }
  double bristle_coefficient(double slip, double z) const override {
    return sigma0_ * z + sigma1_ * bristle_rate(slip, z);
  }
  double bristle_stiffness() const override { return sigma0_; }
  double bristle_damping() const override { return sigma1_; }
  // z / bristle_range (in [-1, 1]: its error controlled at its own scale),
  // and the bristles' stored energy per unit normal force integrated.
  std::vector<const char*> state_names() const override {
    return {"bristle_share", "bristle_energy"};
  }
  double bristle_range() const override {
    return std::max(curve_.mu, curve_.mu_static) / sigma0_;
  }
  // The bristle energy sigma0 z^2 / 2 per unit normal force is elastic
  // energy of the account; the friction's power sigma0 z z' goes into it.
  double stored_energy(double z) const override { return 0.5 * sigma0_ * z * z; }
  double storing_power(double slip, double z) const override {
    return sigma0_ * z * bristle_rate(slip, z);
  }
  // sigma1 z' can carry the coefficient above mu_static transiently.
  double max_mu() const override {
    return std::max(curve_.mu, curve_.mu_static) * (1.0 + 1e-9);
  }

 private:
  StribeckCurve curve_;
  double viscous_, sigma0_, sigma1_;
};

}  // namespace

LawType lugre_law() {
  LawType type;
  type.name = "lugre";
  type.doc = "LuGre friction (Canudas de Wit et al. 1995): bristles of deflection z per "
             "contact, z' = slip_velocity - sigma0 |slip_velocity| z / mu(|slip_velocity|), "
             "friction = -|normal| (sigma0 z + sigma1 z') - viscous slip_velocity, mu(v) "
             "Stribeck's curve";
  type.parameters = stribeck_parameters();
  // mu > 0: the bristle rate divides by mu(v), which is mu at high slip
  // speed and mu_static (>= mu) at rest; at mu = mu_static = 0 it is 0 / 0
  // at rest (a NaN right-hand side at t = 0; a frictionless thread is
  // coulomb's mu = 0).
  type.parameters[0].low_open = true;
  const double inf = std::numeric_limits<double>::infinity();
  type.parameters.push_back({"sigma0", "1/m",
                             "bristle stiffness per unit normal force (presliding stiffness "
                             "sigma0 |normal|)",
                             1e5, nullptr, 0.0, inf, true});
  type.parameters.push_back({"sigma1", "s/m", "bristle damping per unit normal force", 0.0});
  type.ode = true;
  type.make = [](const std::vector<double>& v) -> std::unique_ptr<Law> {
    return std::make_unique<LuGre>(StribeckCurve{v[0], v[1], v[2], v[3]}, v[4], v[5], v[6]);
  };
  return type;
}

}  // namespace leadscrew::friction
