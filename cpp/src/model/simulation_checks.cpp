#include "leadscrew/model/simulation_checks.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/integrate/ode.hpp"

namespace leadscrew::model {

void check_meaningful_tolerances(const integrate::IntegratorOptions& options, double t_end) {
  // The tolerances' real ranges first, NaN and values no integrator takes
  // included (validate_options' own ranges, rtol in (0, 1), atol > 0, are
  // wider: its message would name a range that is not the one that holds).
  // (The messages are formatted only where they are thrown: formatting the
  // ranges up front cost 24,000 instructions per run, 4 % of the friction
  // block's whole simulation.)
  if (!(options.rtol > 0.0 && options.rtol <= kLoosestRelativeTolerance))
    throw InvalidArgument("rtol = " + format_value(options.rtol) +
                          " is invalid: must be a finite number in (0, " +
                          format_value(kLoosestRelativeTolerance) + "]" +
                          (options.rtol > kLoosestRelativeTolerance
                               ? " (a looser tolerance no longer bounds the error, which "
                                 "accumulates over the steps)"
                               : ""));
  if (!(options.atol >= kTightestAbsoluteTolerance && options.atol <= kLoosestAbsoluteTolerance))
    throw InvalidArgument(
        "atol = " + format_value(options.atol) + " is invalid: must be a finite number in [" +
        format_value(kTightestAbsoluteTolerance) + ", " + format_value(kLoosestAbsoluteTolerance) +
        "]" +
        (options.atol > kLoosestAbsoluteTolerance
             ? " (it bounds the error of positions in m and rad: more exceeds a lead screw's "
               "pitch and play)"
             : options.atol < kTightestAbsoluteTolerance && options.atol > 0.0
                   ? " (the error weights 1 / atol overflow when squared)"
                   : ""));
  integrate::validate_options(options);  // the other options' ranges
  if (options.max_step > 0.0 && t_end / options.max_step > static_cast<double>(options.max_steps))
    throw InvalidArgument("max_step = " + format_value(options.max_step) +
                          " is invalid: reaching t_end = " + format_value(t_end) +
                          " s takes more steps than max_steps = " +
                          std::to_string(options.max_steps) + " (must be 0 or >= " +
                          format_value(t_end / static_cast<double>(options.max_steps)) + " s)");
  const double resolution = 64.0 * std::numeric_limits<double>::epsilon() * t_end;
  if (options.first_step > 0.0 && options.first_step < resolution)
    throw InvalidArgument("first_step = " + format_value(options.first_step) +
                          " is invalid: must be 0 (the integrator's choice) or >= " +
                          format_value(resolution) + " s, the time's resolution at t_end");
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
