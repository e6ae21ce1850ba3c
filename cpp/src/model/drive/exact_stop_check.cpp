// The result check exact_stops (checks.hpp): the load never lies beyond an
// exact end stop's face by more than the root's resolution
// (docs/physics/result_checks.md, "exact_stops"; docs/physics/end_stops.md,
// "Exact stops").
#include <algorithm>
#include <cmath>
#include <limits>

#include "checks.hpp"

namespace leadscrew::model::drive {

integrate::InvariantCheck exact_stop_check(const DriveModel& model,
                                           const DriveSimulationOptions& options,
                                           bool time_stepping,
                                           const integrate::SimulationResult& result) {
  integrate::InvariantCheck check;
  check.name = "exact_stops";
  check.what = "the load never lies beyond an exact end stop's face (by more than the root's "
               "resolution)";
  check.unit = "m";
  const std::vector<elements::ExactEndStop>& stops = model.elements().exact_stops;
  const int position = result.channel_index("u_load");
  const int speed = result.channel_index("v_load");
  // Interpolated between Moreau-Jean's steps, a row is no state of the scheme.
  check.applies = !stops.empty() && position >= 0 && speed >= 0 &&
                  !(time_stepping && result.interpolated);
  if (!check.applies) return check;
  const std::size_t n = result.point_count(), width = result.channel_count();
  const double* values = result.values.data();
  double fastest = 0.0, farthest_face = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    fastest = std::max(fastest, std::abs(values[i * width + static_cast<std::size_t>(speed)]));
  for (const elements::ExactEndStop& stop : stops)
    farthest_face = std::max(farthest_face, std::abs(stop.position));
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const integrate::IntegratorOptions& tolerances = options.integrator_options;
  // The event-driven scheme: the row at an impact's root lies where the gap
  // has just changed sign, by the load's speed times the root's time
  // resolution (CVODE's 100 ulp of t, our Runge-Kutta engines' 4: 128 ulp of
  // t_end, as friction_power's); between roots the gap is the integrator's,
  // resolved to its tolerances on the position (ten, as flank_gap's atol).
  // Moreau-Jean meets the face on the velocity level, a step late: three
  // steps of the load's largest speed (as flank_gap's play).
  const double bound =
      time_stepping
          ? 3.0 * options.dt * fastest
          : fastest * 128.0 * eps * options.output.t_end +
                10.0 * (tolerances.atol + tolerances.rtol * farthest_face);
  check.bound = bound + 64.0 * eps * farthest_face;
  check.value = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const double u = values[i * width + static_cast<std::size_t>(position)];
    for (const elements::ExactEndStop& stop : stops) {
      const double beyond = -stop.gap(u);
      if (beyond > check.value) {
        check.value = beyond;
        check.time = result.time[i];
      }
    }
  }
  if (n == 0) check.value = 0.0;
  check.passed = check.value <= check.bound;
  return check;
}

}  // namespace leadscrew::model::drive
