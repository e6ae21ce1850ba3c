#include "leadscrew/integrate/event_driven.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"

namespace leadscrew::integrate {

namespace {

std::vector<double> breakpoints_inside(const HybridSystem& system, double t0, double t_end) {
  std::vector<double> times = system.breakpoints();
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  times.erase(std::remove_if(times.begin(), times.end(),
                             [&](double t) { return !(t > t0 && t < t_end); }),
              times.end());
  return times;
}

}  // namespace

// What the integrator sees of a hybrid system: its right-hand side, and its
// root functions with exact zeros moved to the side not yet crossed in the
// direction that ends the mode. A mode often starts with a root function at
// exactly zero (a normal force after a plastic impact, the play on the flank
// just left); CVODE rejects a root function that stays zero just after a
// restart, and such a zero is no crossing anyway.
class EventDrivenRun::Guard final : public OdeSystem {
 public:
  explicit Guard(HybridSystem& system)
      : system_(system), directions_(static_cast<std::size_t>(std::max(system.root_count(), 0))) {}
  int size() const override { return system_.size(); }
  void rhs(double t, const double* y, double* ydot) override { system_.rhs(t, y, ydot); }
  int root_count() const override { return system_.root_count(); }
  int quadrature_count() const override { return system_.quadrature_count(); }
  bool has_projection() const override { return system_.has_projection(); }
  void project(double t, const double* y, double* correction) override {
    system_.project(t, y, correction);
  }
  void roots(double t, const double* y, double* g) override {
    system_.roots(t, y, g);
    // Far below any physical value, far above underflow: CVODE interpolates
    // between root values, and DBL_MIN there gives NaN times.
    constexpr double tiny = 1e-200;
    // The directions (a function of the mode) are read only when a value is
    // exactly 0, which is rare: no second virtual call on every evaluation,
    // and the common case one branch-free scan (this runs at every root
    // evaluation; the loop with a branch per value took 80 instructions per
    // call of a rigid drive's five, callgrind).
    const int m = static_cast<int>(directions_.size());
    bool any_zero = false;
    for (int i = 0; i < m; ++i) any_zero |= g[i] == 0.0;
    if (!any_zero) return;
    system_.root_directions(directions_.data());
    for (int i = 0; i < m; ++i)
      if (g[i] == 0.0) g[i] = directions_[i] > 0 ? -tiny : tiny;
  }

 private:
  HybridSystem& system_;
  std::vector<int> directions_;
};

double max_step_from_time_scales(std::initializer_list<double> time_scales) {
  double shortest = std::numeric_limits<double>::infinity();
  for (double scale : time_scales)
    if (scale > 0.0) shortest = std::min(shortest, scale);
  return std::isfinite(shortest) ? shortest / kStepsPerLoadPeriod : 0.0;
}

EventDrivenRun::EventDrivenRun(HybridSystem& system, double t0,
                               const Eigen::Ref<const Eigen::VectorXd>& y0,
                               const EventDrivenOptions& options)
    : system_(&system), options_(options), y_(y0), t_(t0) {
  system.select_initial_mode(t0, y_.data());
  IntegratorOptions& integrator_options = options_.integrator_options;
  const double hint = system.max_step_hint();
  if (hint > 0.0 && (integrator_options.max_step <= 0.0 || hint < integrator_options.max_step))
    integrator_options.max_step = hint;
  integrator_ = make_integrator(options_.integrator, integrator_options);
  attach(system);
}

EventDrivenRun::~EventDrivenRun() = default;

// Without root functions there is nothing to guard: the integrator calls
// the system directly (one virtual call per right-hand side, not two).
void EventDrivenRun::attach(HybridSystem& system) {
  system_ = &system;
  guard_ = std::make_unique<Guard>(system);
  directions_.assign(static_cast<std::size_t>(std::max(system.root_count(), 0)), 0);
  if (system.root_count() > 0)
    integrator_->initialize(*guard_, t_, y_);
  else
    integrator_->initialize(system, t_, y_);
}

void EventDrivenRun::restart(HybridSystem& system) {
  if (&system == system_) {
    integrator_->reinitialize(t_, y_);
    return;
  }
  const IntegratorStats before = integrator_->stats();
  carried_.steps += before.steps;
  carried_.rhs_evaluations += before.rhs_evaluations;
  carried_.restarts += before.restarts + 1;
  carried_.jacobian_evaluations += before.jacobian_evaluations;
  carried_.error_test_failures += before.error_test_failures;
  carried_.nonlinear_failures += before.nonlinear_failures;
  carried_lcp_solves_ += system_->lcp_solves();
  carried_iterations_ += system_->nonlinear_iterations();
  attach(system);
}

// Whether a root the integrator stopped at is an event: its direction is the
// one the system watches for (a root crossed the other way is not).
bool EventDrivenRun::counts_as_event(const std::vector<int>& info) {
  system_->root_directions(directions_.data());
  for (std::size_t i = 0; i < info.size() && i < directions_.size(); ++i)
    if (info[i] != 0 && (directions_[i] == 0 || directions_[i] == info[i])) return true;
  return false;
}

// The system handles the event at t_ (a new mode, an impact); the integrator
// restarts there. The count is bounded by max_events.
void EventDrivenRun::handle_root(SimulationResult& result) {
  const std::string kind = system_->handle_event(t_, y_.data(), integrator_->root_info());
  if (!kind.empty()) {
    result.events.push_back({t_, kind});
    if (++events_ > options_.max_events)
      throw SimulationError(t_,
                            "more than max_events = " + std::to_string(options_.max_events) +
                                " events",
                            "events accumulate (Zeno behaviour or chattering); use "
                            "integrator=\"moreau\" or raise max_events");
  }
  integrator_->reinitialize(t_, y_);
}

void EventDrivenRun::advance(const OutputRequest& output, SimulationResult& result) {
  validate_output_request(output, t_);
  HybridSystem& system = *system_;
  std::vector<double> values(system.channel_names().size());
  const bool every_step = output.t_eval.empty();
  auto record = [&](double t) {
    system.channels(t, y_.data(), values.data());
    result.append(t, values.data());
  };

  const std::vector<double> breaks = breakpoints_inside(system, t_, output.t_end);
  std::size_t next_break = 0;
  std::size_t next_eval = 0;
  const std::size_t eval_count = output.t_eval.size();
  auto record_due_eval_points = [&](double t) {
    while (next_eval < eval_count && output.t_eval[next_eval] <= t) {
      record(t);
      ++next_eval;
    }
  };
  if (!started_) {
    if (every_step)
      record(t_);
    else
      record_due_eval_points(t_);
    started_ = true;
  } else {  // the start's row is the last call's end
    while (next_eval < eval_count && output.t_eval[next_eval] <= t_) ++next_eval;
  }

  // Every pass either consumes integrator steps (bounded by its max_steps),
  // an event (bounded by max_events), an output time or a breakpoint.
  const long max_passes = options_.integrator_options.max_steps + options_.max_events +
                          static_cast<long>(eval_count + breaks.size()) + 16;
  Integrator& integrator = *integrator_;
  for (long pass = 0; t_ < output.t_end; ++pass) {
    if (pass > max_passes)
      throw SimulationError(t_, "the event-driven scheme made no progress",
                            "the system may chatter; try integrator=\"moreau\"");
    // The next discontinuity ends a step; an output time ends one only for
    // integrators without an interpolant of their steps' accuracy (a stop at
    // every output time clips the steps: 201 outputs over 2 s cost the
    // flexible drive with bistop backlash 4-11 % more cvode_bdf steps).
    double stop = output.t_end;
    if (next_break < breaks.size()) stop = std::min(stop, breaks[next_break]);
    const bool output_due =
        !every_step && next_eval < eval_count && output.t_eval[next_eval] < stop;
    const AdvanceResult step =
        output_due ? integrator.advance_to_output(output.t_eval[next_eval], stop, y_)
                   : integrator.advance(stop, y_, every_step);
    t_ = step.t;
    if (step.status == AdvanceStatus::root_found && !counts_as_event(integrator.root_info())) {
      if (every_step) record(t_);
      continue;
    }
    if (step.status == AdvanceStatus::root_found) {
      if (every_step) record(t_);  // the value just before the event
      else
        record_due_eval_points(t_);
      handle_root(result);
      if (every_step) record(t_);  // and just after it
      continue;
    }
    if (every_step)
      record(t_);
    else
      record_due_eval_points(t_);
    if (next_break < breaks.size() && t_ >= breaks[next_break]) {
      integrator.reinitialize(t_, y_);
      ++next_break;
    }
  }
}

void EventDrivenRun::fill_stats(SimulationResult& result) const {
  const IntegratorStats s = integrator_->stats();
  result.stats.steps = carried_.steps + s.steps;
  result.stats.rhs_evaluations = carried_.rhs_evaluations + s.rhs_evaluations;
  result.stats.restarts = carried_.restarts + s.restarts;
  result.stats.jacobian_evaluations = carried_.jacobian_evaluations + s.jacobian_evaluations;
  result.stats.error_test_failures = carried_.error_test_failures + s.error_test_failures;
  result.stats.nonlinear_failures = carried_.nonlinear_failures + s.nonlinear_failures;
  result.stats.events = events_;
  result.stats.lcp_solves = carried_lcp_solves_ + system_->lcp_solves();
  result.stats.nonlinear_iterations = carried_iterations_ + system_->nonlinear_iterations();
}

SimulationResult simulate_event_driven(HybridSystem& system, double t0,
                                       const Eigen::Ref<const Eigen::VectorXd>& y0,
                                       const OutputRequest& output,
                                       const EventDrivenOptions& options) {
  validate_output_request(output, t0);
  const auto wall_start = std::chrono::steady_clock::now();
  EventDrivenRun run(system, t0, y0, options);
  SimulationResult result;
  result.integrator = options.integrator;
  result.channel_names = system.channel_names();
  // Every step: a guess that most short runs stay within (the storage
  // doubles beyond it); a large reservation costs more than it saves here.
  result.reserve(output.t_eval.empty() ? 128 : output.t_eval.size());
  run.advance(output, result);
  run.fill_stats(result);
  result.stats.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace leadscrew::integrate
