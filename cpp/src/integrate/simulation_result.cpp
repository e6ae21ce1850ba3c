#include "leadscrew/integrate/simulation_result.hpp"

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::integrate {

void SimulationResult::reserve(std::size_t points) {
  time.reserve(points);
  values.reserve(points * channel_count());
}

void SimulationResult::append(double t, const double* row) {
  time.push_back(t);
  values.insert(values.end(), row, row + channel_count());
}

void SimulationResult::copy_channel(std::size_t k, double* out) const {
  const std::size_t stride = channel_count();
  const double* in = values.data() + k;
  for (std::size_t i = 0; i < time.size(); ++i) out[i] = in[i * stride];
}

int SimulationResult::channel_index(const std::string& name) const {
  for (std::size_t k = 0; k < channel_names.size(); ++k)
    if (channel_names[k] == name) return static_cast<int>(k);
  return -1;
}

void enforce_checks(const SimulationResult& result) {
  for (const InvariantCheck& check : result.checks) {
    if (!check.applies || check.passed) continue;
    const std::string unit = *check.unit ? std::string(" ") + check.unit : std::string();
    throw SimulationError(
        check.time,
        std::string("the result fails its check '") + check.name + "' (" + check.what +
            "): " + format_value(check.value) + unit + " against the bound " +
            format_value(check.bound) + unit,
        std::string("the run did not resolve the scene (") +
            (result.integrator == "moreau" ? "shorten dt" : "tighten rtol/atol") +
            ") or met a defect; check=False returns the result unchecked, and please report "
            "the scene");
  }
}

void validate_output_request(const OutputRequest& request, double t0) {
  require_finite("t_end", request.t_end);
  if (!(request.t_end > t0))
    throw InvalidArgument("t_end = " + format_value(request.t_end) +
                          " is invalid: must be a finite number > " + format_value(t0));
  for (std::size_t i = 0; i < request.t_eval.size(); ++i) {
    const double t = request.t_eval[i];
    const std::string name = "t_eval[" + std::to_string(i) + "]";
    require_in_range(name, t, t0, request.t_end);
    if (i > 0 && t < request.t_eval[i - 1])
      throw InvalidArgument(name + " = " + format_value(t) +
                            " is invalid: t_eval must be non-decreasing");
  }
}

}  // namespace leadscrew::integrate
