#include "leadscrew/model/simulation_checks.hpp"

#include <cmath>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/integrate/ode.hpp"

namespace leadscrew::model {

void check_meaningful_tolerances(const integrate::IntegratorOptions& options) {
  integrate::validate_options(options);  // the ranges first: rtol in (0, 1], atol > 0, ...
  if (options.rtol > kLoosestRelativeTolerance)
    throw InvalidArgument("rtol = " + format_value(options.rtol) + " is invalid: must be <= " +
                          format_value(kLoosestRelativeTolerance) +
                          " (a looser tolerance no longer bounds the error, which accumulates "
                          "over the steps)");
  if (options.atol > kLoosestAbsoluteTolerance)
    throw InvalidArgument("atol = " + format_value(options.atol) + " is invalid: must be <= " +
                          format_value(kLoosestAbsoluteTolerance) +
                          " (it bounds the error of positions in m and rad: more exceeds a "
                          "lead screw's pitch and play)");
  if (options.atol < kTightestAbsoluteTolerance)
    throw InvalidArgument("atol = " + format_value(options.atol) + " is invalid: must be >= " +
                          format_value(kTightestAbsoluteTolerance) +
                          " (the error weights 1 / atol overflow when squared)");
}

void check_step_resolves_loads(double dt, double t_end,
                               std::initializer_list<const Excitation*> loads) {
  if (dt > t_end)
    throw InvalidArgument("dt = " + format_value(dt) + " is invalid: must be <= t_end = " +
                          format_value(t_end) + " s (a step longer than the run)");
  for (const Excitation* load : loads) {
    // A sine: a finite time scale (its period) without breakpoints (a
    // table's knots); Excitation::time_scale().
    const double period = load->time_scale();
    if (!(std::isfinite(period) && period > 0.0 && load->breakpoints().empty())) continue;
    if (dt > 0.25 * period)
      throw InvalidArgument("dt = " + format_value(dt) + " is invalid: must be <= " +
                            format_value(0.25 * period) +
                            " s, a quarter of the period of the load " + load->describe() +
                            " (fewer steps per period cannot resolve it)");
  }
}

}  // namespace leadscrew::model
