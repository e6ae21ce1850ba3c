// What every simulation returns: time, named output channels, events, stats.
#pragma once

#include <string>
#include <vector>

namespace leadscrew::integrate {

struct Event {
  double time = 0.0;
  std::string kind;  // e.g. "stick->slip+", "slip+->stick", "slip+->slip-"
};

struct SimulationStats {
  long steps = 0;
  long rhs_evaluations = 0;
  long events = 0;
  long lcp_solves = 0;
  long restarts = 0;
  long nonlinear_iterations = 0;  // scalar solves inside the rhs (arctan_acceleration)
  long jacobian_evaluations = 0;
  long error_test_failures = 0;
  long nonlinear_failures = 0;
  double wall_time = 0.0;         // [s], measured inside C++
};

// One invariant a result was checked for (model/result_checks.hpp): the
// worst value the run showed against its bound, and when.
// (Static strings: a run's checks allocate nothing but their vector.)
struct InvariantCheck {
  const char* name = "";   // e.g. "energy_balance", "friction_power"
  const char* what = "";   // what it checks, one line
  bool applies = true;     // false: not a property of this model or law (not checked)
  bool passed = true;
  double value = 0.0;      // the worst value seen (the invariant's own unit)
  double bound = 0.0;      // what the run allows
  double time = 0.0;       // [s] where the worst value occurred
  const char* unit = "";   // of value and bound
};

struct SimulationResult {
  std::vector<double> time;
  std::vector<std::string> channel_names;
  // values[i * channel_count() + k]: channel k at time[i]. Point-major, so
  // that recording an output point is one append of a row (one capacity
  // check, one contiguous write) however many channels a model has.
  std::vector<double> values;
  std::vector<Event> events;
  SimulationStats stats;
  std::string integrator;
  std::string friction;
  // The invariants checked at the end of the run (empty: not checked).
  std::vector<InvariantCheck> checks;
  // The output points interpolate between the scheme's own (Moreau-Jean at
  // requested times): products of channels there are not the scheme's.
  bool interpolated = false;

  std::size_t channel_count() const noexcept { return channel_names.size(); }
  std::size_t point_count() const noexcept { return time.size(); }
  // Copies channel k (point_count() values) to out.
  void copy_channel(std::size_t k, double* out) const;

  void reserve(std::size_t points);
  // Appends one output point; `row` holds one value per channel.
  void append(double t, const double* row);
  // Index of the channel called `name`, or -1.
  int channel_index(const std::string& name) const;
};

// Throws SimulationError naming the first check that failed (its invariant,
// time, size and bound); nothing if all passed.
void enforce_checks(const SimulationResult& result);

// When to record output: at the given times, or (empty) at every step and
// event of the integrator.
struct OutputRequest {
  double t_end = 0.0;
  std::vector<double> t_eval;
};

// Validates t_end > t0 and t_eval (finite, non-decreasing, within [t0, t_end]).
void validate_output_request(const OutputRequest& request, double t0);

}  // namespace leadscrew::integrate
