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

// What the integrator sees of a hybrid system: its right-hand side, and its
// root functions with exact zeros moved to the side not yet crossed in the
// direction that ends the mode. A mode often starts with a root function at
// exactly zero (a normal force after a plastic impact, the play on the flank
// just left); CVODE rejects a root function that stays zero just after a
// restart, and such a zero is no crossing anyway.
class RootGuard final : public OdeSystem {
 public:
  explicit RootGuard(HybridSystem& system)
      : system_(system), directions_(static_cast<std::size_t>(std::max(system.root_count(), 0))) {}
  int size() const override { return system_.size(); }
  void rhs(double t, const double* y, double* ydot) override { system_.rhs(t, y, ydot); }
  int root_count() const override { return system_.root_count(); }
  int quadrature_count() const override { return system_.quadrature_count(); }
  void roots(double t, const double* y, double* g) override {
    system_.roots(t, y, g);
    // Far below any physical value, far above underflow: CVODE interpolates
    // between root values, and DBL_MIN there gives NaN times.
    constexpr double tiny = 1e-200;
    // The directions (a function of the mode) are read only when a value is
    // exactly 0, which is rare: no second virtual call on every evaluation.
    bool directions_read = false;
    for (std::size_t i = 0; i < directions_.size(); ++i) {
      if (g[i] != 0.0) continue;
      if (!directions_read) {
        system_.root_directions(directions_.data());
        directions_read = true;
      }
      g[i] = directions_[i] > 0 ? -tiny : tiny;
    }
  }

 private:
  HybridSystem& system_;
  std::vector<int> directions_;
};

}  // namespace

double max_step_from_time_scales(std::initializer_list<double> time_scales) {
  double shortest = std::numeric_limits<double>::infinity();
  for (double scale : time_scales)
    if (scale > 0.0) shortest = std::min(shortest, scale);
  return std::isfinite(shortest) ? shortest / kStepsPerLoadPeriod : 0.0;
}

SimulationResult simulate_event_driven(HybridSystem& system, double t0,
                                       const Eigen::Ref<const Eigen::VectorXd>& y0,
                                       const OutputRequest& output,
                                       const EventDrivenOptions& options) {
  validate_output_request(output, t0);
  const auto wall_start = std::chrono::steady_clock::now();

  Eigen::VectorXd y = y0;
  system.select_initial_mode(t0, y.data());

  SimulationResult result;
  result.integrator = options.integrator;
  result.channel_names = system.channel_names();
  std::vector<double> values(result.channel_names.size());
  const bool every_step = output.t_eval.empty();
  // Every step: a guess that most short runs stay within (the storage
  // doubles beyond it); a large reservation costs more than it saves here.
  result.reserve(every_step ? 128 : output.t_eval.size());
  auto record = [&](double t) {
    system.channels(t, y.data(), values.data());
    result.append(t, values.data());
  };

  IntegratorOptions integrator_options = options.integrator_options;
  const double hint = system.max_step_hint();
  if (hint > 0.0 && (integrator_options.max_step <= 0.0 || hint < integrator_options.max_step))
    integrator_options.max_step = hint;
  std::unique_ptr<Integrator> integrator = make_integrator(options.integrator, integrator_options);
  // Without root functions there is nothing to guard: the integrator calls
  // the system directly (one virtual call per right-hand side, not two).
  RootGuard guarded(system);
  if (system.root_count() > 0)
    integrator->initialize(guarded, t0, y);
  else
    integrator->initialize(system, t0, y);

  std::vector<int> directions(static_cast<std::size_t>(std::max(system.root_count(), 0)), 0);
  auto counts_as_event = [&](const std::vector<int>& info) {
    system.root_directions(directions.data());
    for (std::size_t i = 0; i < info.size() && i < directions.size(); ++i)
      if (info[i] != 0 && (directions[i] == 0 || directions[i] == info[i])) return true;
    return false;
  };

  const std::vector<double> breaks = breakpoints_inside(system, t0, output.t_end);
  std::size_t next_break = 0;
  std::size_t next_eval = 0;
  const std::size_t eval_count = output.t_eval.size();
  auto record_due_eval_points = [&](double t) {
    while (next_eval < eval_count && output.t_eval[next_eval] <= t) {
      record(t);
      ++next_eval;
    }
  };
  if (every_step)
    record(t0);
  else
    record_due_eval_points(t0);

  // Every pass either consumes integrator steps (bounded by its max_steps),
  // an event (bounded by max_events), an output time or a breakpoint.
  const long max_passes = options.integrator_options.max_steps + options.max_events +
                          static_cast<long>(eval_count + breaks.size()) + 16;
  double t = t0;
  long events = 0;
  for (long pass = 0; t < output.t_end; ++pass) {
    if (pass > max_passes)
      throw SimulationError(t, "the event-driven scheme made no progress",
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
        output_due ? integrator->advance_to_output(output.t_eval[next_eval], stop, y)
                   : integrator->advance(stop, y, every_step);
    t = step.t;
    if (step.status == AdvanceStatus::root_found && !counts_as_event(integrator->root_info())) {
      if (every_step) record(t);
      continue;
    }
    if (step.status == AdvanceStatus::root_found) {
      if (every_step) record(t);  // the value just before the event
      else
        record_due_eval_points(t);
      const std::string kind = system.handle_event(t, y.data(), integrator->root_info());
      if (!kind.empty()) {
        result.events.push_back({t, kind});
        if (++events > options.max_events)
          throw SimulationError(t,
                                "more than max_events = " + std::to_string(options.max_events) +
                                    " events",
                                "events accumulate (Zeno behaviour or chattering); use "
                                "integrator=\"moreau\" or raise max_events");
      }
      integrator->reinitialize(t, y);
      if (every_step) record(t);  // and just after it
      continue;
    }
    if (every_step)
      record(t);
    else
      record_due_eval_points(t);
    if (next_break < breaks.size() && t >= breaks[next_break]) {
      integrator->reinitialize(t, y);
      ++next_break;
    }
  }

  const IntegratorStats integrator_stats = integrator->stats();
  result.stats.steps = integrator_stats.steps;
  result.stats.rhs_evaluations = integrator_stats.rhs_evaluations;
  result.stats.restarts = integrator_stats.restarts;
  result.stats.jacobian_evaluations = integrator_stats.jacobian_evaluations;
  result.stats.error_test_failures = integrator_stats.error_test_failures;
  result.stats.nonlinear_failures = integrator_stats.nonlinear_failures;
  result.stats.events = events;
  result.stats.lcp_solves = system.lcp_solves();
  result.stats.nonlinear_iterations = system.nonlinear_iterations();
  result.stats.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace leadscrew::integrate
