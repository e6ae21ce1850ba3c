#include "leadscrew/integrate/integrator_checks.hpp"

#include <string>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::integrate {

void check_system(const OdeSystem& system) {
  const int n = system.size();
  if (n < 1)
    throw InvalidArgument("system size = " + std::to_string(n) + " is invalid: must be >= 1");
  const int m = system.root_count();
  if (m < 0)
    throw InvalidArgument("system root_count = " + std::to_string(m) +
                          " is invalid: must be >= 0");
  const int k = system.quadrature_count();
  if (k < 0 || k >= n)
    throw InvalidArgument("system quadrature_count = " + std::to_string(k) +
                          " is invalid: must be in [0, size - 1] = [0, " + std::to_string(n - 1) +
                          "]");
}

void check_initialized(bool initialized, const char* call) {
  if (!initialized)
    throw InvalidArgument(std::string(call) +
                          " called before initialize is invalid: initialize first");
}

void check_state_size(const char* name, Eigen::Index size, int n) {
  if (size != n)
    throw InvalidArgument(std::string(name) + " has " + std::to_string(size) +
                          " components, invalid: must have the system size " + std::to_string(n));
}

void check_start(double t0, const Eigen::Ref<const Eigen::VectorXd>& y0, int n) {
  if (!std::isfinite(t0)) require_finite("t0", t0);
  check_state_size("y0", y0.size(), n);
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(y0[i])) require_finite("y0[" + std::to_string(i) + "]", y0[i]);
}

void check_output_time(double t_out, double t) {
  if (!std::isfinite(t_out)) require_finite("t_out", t_out);
  if (t_out < t)
    throw InvalidArgument("t_out = " + format_value(t_out) +
                          " is invalid: must be >= the current time " + format_value(t));
}

void check_stop_time(double t_out, double t_stop) {
  if (!(t_stop >= t_out))
    throw InvalidArgument("t_stop = " + format_value(t_stop) +
                          " is invalid: must be >= t_out = " + format_value(t_out));
}

void check_max_steps(long max_steps) {
  if (max_steps < 1)
    throw InvalidArgument("max_steps = " + std::to_string(max_steps) +
                          " is invalid: must be an integer >= 1");
}

void check_fixed_order(const IntegratorOptions& options, const std::string& method, int order) {
  if (options.max_order != 0)
    throw InvalidArgument("max_order = " + std::to_string(options.max_order) +
                          " is invalid: must be 0 for " + method +
                          " (a one-step method of fixed order " + std::to_string(order) + ")");
}

}  // namespace leadscrew::integrate
