// The argument checks that every Integrator implementation makes, in one
// place so that every method words them alike ("<name> = <value> is invalid:
// must be ..."). The checks on hot paths (advance, reinitialize) build their
// message only when they fail.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <string>

#include "leadscrew/integrate/ode.hpp"

namespace leadscrew::integrate {

inline bool all_finite(const double* v, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// Throws InvalidArgument unless system.size() >= 1, system.root_count() >= 0
// and 0 <= system.quadrature_count() < system.size().
void check_system(const OdeSystem& system);

// Throws InvalidArgument unless `call` (e.g. "advance") comes after initialize.
void check_initialized(bool initialized, const char* call);

// Throws InvalidArgument unless a state vector `name` has n components.
void check_state_size(const char* name, Eigen::Index size, int n);

// A (re)start at (t0, y0) of a system of n states: t0 finite, y0 of n finite
// components. Throws InvalidArgument naming the first bad value.
void check_start(double t0, const Eigen::Ref<const Eigen::VectorXd>& y0, int n);

// An advance from t to t_out: t_out finite and >= t. Throws InvalidArgument.
void check_output_time(double t_out, double t);

// advance_to_output's stop: t_stop >= t_out. Throws InvalidArgument.
void check_stop_time(double t_out, double t_stop);

// A bound on steps: max_steps >= 1 (the ODE methods' and Moreau's).
// Throws InvalidArgument.
void check_max_steps(long max_steps);

// A one-step method of fixed order takes no max_order (it must be 0).
// Throws InvalidArgument naming the method and its order.
void check_fixed_order(const IntegratorOptions& options, const std::string& method, int order);

}  // namespace leadscrew::integrate
