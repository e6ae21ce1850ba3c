#include "leadscrew/integrate/sundials_integrator.hpp"

#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/integrate/integrator_checks.hpp"

namespace leadscrew::integrate::sundials {

SundialsIntegrator::SundialsIntegrator(std::string name, const IntegratorOptions& options,
                                       bool implicit)
    : options_(options), name_(std::move(name)), implicit_(implicit) {}

void SundialsIntegrator::check_setup(int flag, const char* call) const {
  if (flag < 0)
    throw SimulationError(t_, std::string(call) + " failed with " + flag_name(flag) + " (" +
                                  name_ + "); " + bridge_.last_message(),
                          "check the integrator options");
}

void SundialsIntegrator::load_state(double t0, const Eigen::Ref<const Eigen::VectorXd>& y0) {
  check_start(t0, y0, bridge_.size);
  double* y = N_VGetArrayPointer(y_.get());
  for (int i = 0; i < bridge_.size; ++i) y[i] = y0[i];
  t_ = t0;
}

void SundialsIntegrator::initialize(OdeSystem& system, double t0,
                                    const Eigen::Ref<const Eigen::VectorXd>& y0) {
  check_system(system);
  const int n = system.size();
  const int m = system.root_count();
  const int k = system.quadrature_count();
  initialized_ = false;
  bridge_.system = &system;
  bridge_.size = n;
  bridge_.root_count = m;
  bridge_.quadrature_count = k;
  bridge_.clear_all();
  y_ = make_vector(n, context_);
  work_ = make_vector(n, context_);
  load_state(t0, y0);
  root_info_.assign(static_cast<std::size_t>(m), 0);
  before_restart_ = IntegratorStats{};
  restarts_ = 0;
  create_solver(t0);
  initialized_ = true;
}

void SundialsIntegrator::reinitialize(double t0, const Eigen::Ref<const Eigen::VectorXd>& y0) {
  check_initialized(initialized_, "reinitialize");
  accumulate(before_restart_, solver_stats());
  load_state(t0, y0);
  bridge_.clear_all();
  check_setup(restart_solver(t0), "reinitialize");
  std::fill(root_info_.begin(), root_info_.end(), 0);
  ++restarts_;
}

AdvanceResult SundialsIntegrator::advance(double t_out, Eigen::Ref<Eigen::VectorXd> y,
                                          bool one_step) {
  return advance_until(t_out, t_out, y, one_step);
}

AdvanceResult SundialsIntegrator::advance_to_output(double t_out, double t_stop,
                                                    Eigen::Ref<Eigen::VectorXd> y) {
  require_finite("t_stop", t_stop);
  check_stop_time(t_out, t_stop);
  // Without an interpolant of the steps' accuracy the output time ends a step.
  return advance_until(t_out, interpolates_output() ? t_stop : t_out, y, false);
}

AdvanceResult SundialsIntegrator::advance_until(double t_out, double t_stop,
                                                Eigen::Ref<Eigen::VectorXd> y, bool one_step) {
  check_initialized(initialized_, "advance");
  check_output_time(t_out, t_);
  check_state_size("y", y.size(), bridge_.size);
  std::fill(root_info_.begin(), root_info_.end(), 0);
  double* state = N_VGetArrayPointer(y_.get());
  const double span = t_out - t_;
  if (span <= 8.0 * std::numeric_limits<double>::epsilon() * std::max(std::fabs(t_), 1.0)) {
    // An interval within a few roundoffs of t is too short for the solver to
    // start a step (CV_TOO_CLOSE); the state changes by f * (t_out - t), far
    // below any tolerance, so it is kept.
    for (int i = 0; i < bridge_.size; ++i) y[i] = state[i];
    t_ = t_out;
    return {t_out, AdvanceStatus::reached};
  }

  if (t_stop < solver_time())
    throw InvalidArgument("t_stop = " + format_value(t_stop) +
                          " is invalid: the integrator has already stepped to " +
                          format_value(solver_time()) +
                          " (after advance_to_output, stop times must not decrease)");

  // options_.max_steps bounds all steps since initialize; SUNDIALS' own
  // mxstep counts per call, so it gets what is left of the budget.
  const long taken = before_restart_.steps + solver_stats().steps;
  const long left = options_.max_steps - taken;
  if (left <= 0) throw_solver_failure(t_, -1, flag_name(-1), name_, implicit_, bridge_, options_);
  check_setup(limit_solver(t_stop, left), "setting the stop time");

  bridge_.clear_call();
  double t_reached = t_;
  const int flag = evolve_solver(t_out, one_step, &t_reached);
  if (flag < 0) {
    bridge_.rethrow_pending();
    // (ARKODE reports a NaN time where its step size became NaN, from a
    // state of 1e300: the failure is at the last time it reached.)
    if (const double failed_at = solver_time(); std::isfinite(failed_at)) t_ = failed_at;
    throw_solver_failure(t_, flag, flag_name(flag), name_, implicit_, bridge_, options_);
  }
  for (int i = 0; i < bridge_.size; ++i) {
    if (!std::isfinite(state[i]))
      throw SimulationError(t_reached,
                            "the state became non-finite (NaN or inf) (" + name_ + ")",
                            "the solution blows up: check the model");
    y[i] = state[i];
  }
  t_ = t_reached;
  if (flag == 2) {  // CV_ROOT_RETURN == ARK_ROOT_RETURN
    check_setup(solver_root_info(root_info_.data()), "reading the root information");
    return {t_reached, AdvanceStatus::root_found};
  }
  return {t_reached, AdvanceStatus::reached};
}

void SundialsIntegrator::dense_output(double t, Eigen::Ref<Eigen::VectorXd> y) {
  check_initialized(initialized_, "dense_output");
  check_state_size("y", y.size(), bridge_.size);
  bridge_.clear_call();
  if (solver_dense_output(t, work_.get()) < 0)
    throw InvalidArgument("t = " + format_value(t) +
                          " is invalid: must lie in the last internal step of " + name_);
  const double* v = N_VGetArrayPointer(work_.get());
  for (int i = 0; i < bridge_.size; ++i) y[i] = v[i];
}

IntegratorStats SundialsIntegrator::stats() const {
  IntegratorStats s = before_restart_;
  if (initialized_) accumulate(s, solver_stats());
  s.restarts = restarts_;
  return s;
}

}  // namespace leadscrew::integrate::sundials
