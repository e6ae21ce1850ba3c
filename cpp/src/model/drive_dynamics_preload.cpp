// DriveDynamics (model/drive_dynamics.hpp): a preloaded nut's half B at
// the friction law's coefficient (docs/physics/preloaded_nut.md, "Friction
// laws"; elements/preloaded_nut.hpp, PreloadedNut::normal_at). Each half's
// flank takes the law at the common slip gamma_T; half B's axial balance
// gives its normal force N_B = side S / (cos(a) - side kappa' sin(a)) at the
// mode's coefficient kappa' (friction_factor's), its friction
// -kappa' |N_B|: a given force of the mode in solve.
#include <functional>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model {

// Whether a preloaded nut's half B takes the law's coefficient kappa' in
// the mode `spec` (docs/physics/preloaded_nut.md, "Friction laws"): a
// velocity law's, eq. (3.15)'s or LuGre's bristles' (every mode with
// friction but stick),
// Stribeck's curve in slip. Exact Coulomb's slip keeps the element's
// constant forces N_B^s, T_B^s (bit for bit as before the laws).
bool DriveDynamics::preload_at_kappa(const ModeSpec& spec) const noexcept {
  return spec.friction == FrictionMode::regularized_velocity ||
         spec.friction == FrictionMode::bristle ||
         spec.friction == FrictionMode::regularized_acceleration ||
         (spec.friction == FrictionMode::slip && !one_slip_mu_);
}

// Half B's signed coefficient kappa' in the mode `spec` (friction_factor's)
// at the state set; a SimulationError where half B would lock against its
// own spring (cos(a) - side kappa' sin(a) <= 0: LuGre's bristle damping can
// carry kappa' beyond mu_static' for a moment).
double DriveDynamics::half_b_coefficient(const elements::PreloadedNut& nut,
                                         const ModeSpec& spec) const {
  // (eq. 3.15's at zero slip acceleration: solve takes its own)
  const double kappa = friction_factor(spec, 0.0);
  if (nut.half_b_locks(kappa))
    throw SimulationError(t_,
                          "the preloaded nut's half B locks against its own spring: the law's "
                          "friction coefficient kappa' = " + format_value(kappa) +
                              " times tan(lead angle) reaches 1 on its flank",
                          "lower friction.mu (or LuGre's sigma1) or the lead");
  return kappa;
}

// Eq. (3.15) on a preloaded nut's halves: at a given coefficient kappa' the
// mode is linear (half B's force at kappa', half A's column or penalty
// flank), its slip acceleration x(kappa') (`slip_acceleration_at`, NaN where
// singular); the law's kappa' = kappa(x(kappa')) is the root of g = kappa' -
// kappa(x) on [-mu', mu'] (|kappa| < mu': g changes sign there; half B
// cannot lock, cos(a) - mu' sin(a) > 0 being checked up front), located by
// bisection to round-off. On the thread without play (`multiplier`) the
// Painleve regime raises (its friction force need not be unique); with
// lift-off half A's force is the penalty flank's, given.
double DriveDynamics::preloaded_acceleration_law(
    const ModeSpec& spec, bool multiplier,
    const std::function<double(double)>& slip_acceleration_at) const {
  if (multiplier && painleve_possible_)
    throw SimulationError(t_, "eq. (3.15) with a preloaded nut in the Painleve regime (mu' "
                              "|G_NT| >= G_NN) is not solved: its friction force need not be "
                              "unique there",
                          "use friction.law = \"arctan_velocity\" or \"coulomb\"");
  const double mu = model_.effective_mu();
  double low = -mu, high = mu;
  for (int iteration = 0;
       iteration < 200 && high - low > 4.0 * std::numeric_limits<double>::epsilon() * mu;
       ++iteration) {
    const double middle = 0.5 * (low + high);
    const double x = slip_acceleration_at(middle);
    if (!(x == x)) return middle;  // (singular: the solve says so, not regular)
    (middle - friction_factor(spec, x) < 0.0 ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

}  // namespace leadscrew::model
