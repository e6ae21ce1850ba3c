// A regularized friction law's stick band against the integration's
// resolution of the slip velocity (check_slip_resolved, integrators.hpp).
#include <cmath>
#include <memory>

#include "integrators.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::model::drive {

namespace {

// The largest k_V |W_T| atol: the slip velocity the integration resolves
// within 1/20 of the law's velocity scale 1/k_V, where kappa = (2/pi)
// atan(k_V gamma) mu' reaches 3 % of mu'. Beyond it the integrator may park
// the slip anywhere in the band the friction holds a load with, and its
// error moves the friction by a share of mu' |N|: the self-locking rotor of
// the position_holding scene (rigid, k_V = 1e6 s/m, |W_T| = 0.026 m/rad)
// turned back 200 rad at atol 3e-6 (k_V |W_T| atol = 0.078) and held,
// to 0.1 % of its creep, at atol 1e-6 (0.026) and below (issue 31,
// reproduction 9; docs/physics/result_checks.md, "Options refused").
constexpr double kStickBandResolution = 0.05;

}  // namespace

void check_slip_resolved(const DriveModel& model, const std::string& integrator,
                         const DriveSimulationOptions& options) {
  if (integrator == "moreau") return;
  // The law that runs: a velocity law, or a set-valued law's regularization
  // in an ODE method (the event-driven scheme runs it exactly).
  const friction::Law& law = model.law();
  std::unique_ptr<friction::Law> regularized;
  const friction::Law* running = &law;
  if (law.resolution() == friction::Resolution::set_valued) {
    if (integrator == "event_driven") return;
    regularized = law.regularized();
    running = regularized.get();
  }
  if (!running || running->resolution() != friction::Resolution::velocity) return;
  const double k_v = running->gain();
  const double gradient = model.tangent_direction().cwiseAbs().sum();  // |W_T|
  const double atol = options.integrator_options.atol;
  if (!(k_v * gradient * atol > kStickBandResolution)) return;
  const double largest = kStickBandResolution / (k_v * gradient);
  throw InvalidArgument(
      "atol = " + format_value(atol) + " is invalid with friction.k_v = " + format_value(k_v) +
      " s/m: the slip velocity the integration resolves, |W_T| atol = " +
      format_value(gradient * atol) + " m/s, must lie within 1/20 of the regularized law's "
      "velocity scale 1 / k_v = " + format_value(1.0 / k_v) +
      " m/s, or the friction is undetermined in the band where it holds a load (a "
      "self-locking drive may turn back); use atol <= " + format_value(largest));
}

}  // namespace leadscrew::model::drive
