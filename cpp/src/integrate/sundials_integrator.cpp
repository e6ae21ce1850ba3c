#include "leadscrew/integrate/sundials_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/integrate/integrator_checks.hpp"

namespace leadscrew::integrate::sundials {

SundialsIntegrator::SundialsIntegrator(std::string name, const IntegratorOptions& options,
                                       bool implicit, bool explicit_steps)
    : options_(options),
      name_(std::move(name)),
      implicit_(implicit),
      watch_budget_(explicit_steps && options.stop_when_stiff) {}

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
  budget_mark_steps_ = 0;
  budget_mark_time_ = t0;
  short_pieces_ = 0;
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

  bridge_.clear_call();
  double t_reached = t_;
  const int flag = evolve_within_budget(t_out, t_stop, one_step, &t_reached);
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

// options_.max_steps bounds all steps since initialize; SUNDIALS' own
// mxstep counts per call, so it gets what is left of the budget. An
// explicit method (ERKStep) evolves at most kBudgetPiece steps per call
// (the pieces continue one run, no restart: the solution is the one a
// single call gives), and its budget is watched over every kBudgetPiece
// steps since initialize, whatever the calls (check_budget).
int SundialsIntegrator::evolve_within_budget(double t_out, double t_stop, bool one_step,
                                             double* t_reached) {
  for (;;) {  // (bounded: every piece takes steps from the budget)
    const long left = options_.max_steps - (before_restart_.steps + solver_stats().steps);
    if (left <= 0)
      throw_solver_failure(t_, -1, flag_name(-1), name_, implicit_, bridge_, options_);
    const long piece = !watch_budget_ || one_step ? left : std::min(left, kBudgetPiece);
    check_setup(limit_solver(t_stop, piece), "setting the stop time");
    const int flag = evolve_solver(t_out, one_step, t_reached);
    if (watch_budget_ && (flag >= 0 || flag == -1)) check_budget(t_stop, *t_reached);
    if (flag != -1 || piece == left) return flag;  // (ARK_TOO_MUCH_WORK: -1)
    bridge_.clear_call();  // (the piece's ARK_TOO_MUCH_WORK is no failure)
  }
}

// Where three pieces of kBudgetPiece steps in a row held the step so short
// that the rest to t_stop (the run's end or its next breakpoint) would take
// more steps than max_steps leaves, the run stops there with the hint to
// use an implicit method: a stiff problem holds an explicit step at its
// stability boundary (a flexible nut on ARKODE's dopri5 ran 31 s to reach
// max_steps = 1e7 at t = 8.2 s of 10; issue 31, reproduction 11). A run
// whose rest fits the budget goes on.
void SundialsIntegrator::check_budget(double t_stop, double t_now) {
  const long taken = before_restart_.steps + solver_stats().steps;
  if (taken - budget_mark_steps_ < kBudgetPiece) return;
  const double step =
      (t_now - budget_mark_time_) / static_cast<double>(taken - budget_mark_steps_);
  const double needed = step > 0.0 ? (t_stop - t_now) / step : HUGE_VAL;
  const long left = options_.max_steps - taken;
  short_pieces_ = needed > static_cast<double>(left) ? short_pieces_ + 1 : 0;
  budget_mark_steps_ = taken;
  budget_mark_time_ = t_now;
  if (short_pieces_ < 3) return;
  throw SimulationError(
      t_now,
      "ARK_STIFF: " + name_ + " held its step at h = " + format_value(step) +
          " s on average over its last " + std::to_string(kBudgetPiece) + " steps; the " +
          format_value(t_stop - t_now) + " s left to t = " + format_value(t_stop) +
          " would take some " + format_value(needed) + " steps, more than the " +
          std::to_string(left) +
          " that max_steps leaves (a step held this short by an explicit method is the mark of "
          "a stiff problem)",
      "use an implicit method: cvode_bdf (smooth_integrator = \"cvode_bdf\" inside "
      "integrator = \"event_driven\"), or raise max_steps (now " +
          std::to_string(options_.max_steps) + ")");
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
