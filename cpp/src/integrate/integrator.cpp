// The registry of integrators: one name per method, options validated once.
#include <memory>
#include <string>
#include <vector>

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

namespace {

// One entry per method: its name, the checks its constructor makes of the
// options (method limits beyond validate_options) and its factory.
struct Method {
  const char* name;
  void (*check)(const IntegratorOptions&);
  std::unique_ptr<Integrator> (*make)(const IntegratorOptions&);
};

template <class Engine, auto kind>
Method sundials_method(const char* name) {
  return {name, [](const IntegratorOptions& o) { Engine::check_options(kind, o); },
          [](const IntegratorOptions& o) -> std::unique_ptr<Integrator> {
            return std::make_unique<Engine>(kind, o);
          }};
}

template <const ButcherTableau& (*tableau)()>
Method own_method(const char* name) {
  return {name, [](const IntegratorOptions& o) { ExplicitRungeKutta::check_options(tableau(), o); },
          [](const IntegratorOptions& o) -> std::unique_ptr<Integrator> {
            return std::make_unique<ExplicitRungeKutta>(tableau(), o);
          }};
}

// ARKODE's Fehlberg 8(7) (table ARKODE_FEHLBERG_13_7_8) is not offered: its
// error estimate vanishes identically when f depends on t only (the
// estimating stages pair up at c = 0 and c = 1), so on y' = cos(t) it takes
// huge steps and returns O(1) errors at any tolerance (measured: error 5.8 at
// rtol 1e-10). Forcing terms of the drive models have that part.
const std::vector<Method>& methods() {
  static const std::vector<Method> table = {
      sundials_method<CvodeIntegrator, CvodeIntegrator::Method::bdf>("cvode_bdf"),
      sundials_method<CvodeIntegrator, CvodeIntegrator::Method::adams>("cvode_adams"),
      sundials_method<ArkodeErkIntegrator, ArkodeErkIntegrator::Method::dopri5>("dopri5"),
      sundials_method<ArkodeErkIntegrator, ArkodeErkIntegrator::Method::verner6>("verner6"),
      own_method<dopri5_tableau>("rk_dopri5"),
      own_method<verner6_tableau>("rk_verner6"),
  };
  return table;
}

// The entry of `name`; InvalidArgument listing the names otherwise.
const Method& method_named(const std::string& name) {
  return methods()[static_cast<std::size_t>(require_choice("method", name, integrator_names()))];
}

}  // namespace

const std::vector<std::string>& integrator_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const Method& method : methods()) out.emplace_back(method.name);
    return out;
  }();
  return names;
}

void validate_options(const IntegratorOptions& options) {
  // rtol below ~1e-15 asks for more than double precision holds.
  require_in_range("rtol", options.rtol, 0.0, 1.0, true, true);
  require_positive("atol", options.atol);
  require_nonnegative("max_step", options.max_step);
  require_nonnegative("first_step", options.first_step);
  require_nonnegative("fixed_step", options.fixed_step);
  check_max_steps(options.max_steps);
  if (options.max_order < 0)
    throw InvalidArgument("max_order = " + std::to_string(options.max_order) +
                          " is invalid: must be 0 (the method's default) or a positive order");
}

void check_method_limits(const std::string& name, const IntegratorOptions& options) {
  method_named(name).check(options);
}

std::unique_ptr<Integrator> make_integrator(const std::string& name,
                                            const IntegratorOptions& options) {
  const Method& method = method_named(name);
  validate_options(options);
  return method.make(options);  // the constructor checks the method's limits
}

}  // namespace leadscrew::integrate
