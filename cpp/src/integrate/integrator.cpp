// The registry of integrators: one name per method, options validated once.
#include <string>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/integrate/arkode_erk.hpp"
#include "leadscrew/integrate/cvode.hpp"
#include "leadscrew/integrate/explicit_rk.hpp"
#include "leadscrew/integrate/integrator_checks.hpp"
#include "leadscrew/integrate/rk_dopri5.hpp"
#include "leadscrew/integrate/rk_verner6.hpp"
#include "leadscrew/integrate/ode.hpp"

namespace leadscrew::integrate {

void Integrator::dense_output(double /*t*/, Eigen::Ref<Eigen::VectorXd> /*y*/) {
  throw InvalidArgument("dense_output is invalid for " + name() + ": it has no dense output");
}

AdvanceResult Integrator::advance_to_output(double t_out, double t_stop,
                                            Eigen::Ref<Eigen::VectorXd> y) {
  check_stop_time(t_out, t_stop);
  return advance(t_out, y);
}

const std::vector<std::string>& integrator_names() {
  // ARKODE's Fehlberg 8(7) (table ARKODE_FEHLBERG_13_7_8) is not offered: its error estimate vanishes identically when f depends on t only
  // (the estimating stages pair up at c = 0 and c = 1), so on y' = cos(t) it
  // takes huge steps and returns O(1) errors at any tolerance (measured:
  // error 5.8 at rtol 1e-10). Forcing terms of the drive models have that part.
  static const std::vector<std::string> names = {"cvode_bdf", "cvode_adams", "dopri5",
                                                 "verner6",   "rk_dopri5",   "rk_verner6"};
  return names;
}

void validate_options(const IntegratorOptions& options) {
  // rtol below ~1e-15 asks for more than double precision holds.
  require_in_range("rtol", options.rtol, 0.0, 1.0, true, true);
  require_positive("atol", options.atol);
  require_nonnegative("max_step", options.max_step);
  require_nonnegative("first_step", options.first_step);
  require_nonnegative("fixed_step", options.fixed_step);
  if (options.max_steps < 1)
    throw InvalidArgument("max_steps = " + std::to_string(options.max_steps) +
                          " is invalid: must be an integer >= 1");
  if (options.max_order < 0)
    throw InvalidArgument("max_order = " + std::to_string(options.max_order) +
                          " is invalid: must be 0 (the method's default) or a positive order");
}

std::unique_ptr<Integrator> make_integrator(const std::string& name,
                                            const IntegratorOptions& options) {
  const int index = require_choice("method", name, integrator_names());
  validate_options(options);
  switch (index) {
    case 0:
      return std::make_unique<CvodeIntegrator>(CvodeIntegrator::Method::bdf, options);
    case 1:
      return std::make_unique<CvodeIntegrator>(CvodeIntegrator::Method::adams, options);
    case 2:
      return std::make_unique<ArkodeErkIntegrator>(ArkodeErkIntegrator::Method::dopri5, options);
    case 3:
      return std::make_unique<ArkodeErkIntegrator>(ArkodeErkIntegrator::Method::verner6, options);
    case 4:
      return std::make_unique<ExplicitRungeKutta>(dopri5_tableau(), options);
    case 5:
      return std::make_unique<ExplicitRungeKutta>(verner6_tableau(), options);
    default:
      break;
  }
  throw InvalidArgument("method = \"" + name + "\" is invalid: not implemented");
}

}  // namespace leadscrew::integrate
