// The result checks' `finite` invariant (cpp/src/model/result_checks.cpp)
// over every position of a non-finite value: its test sums v - v in four
// lanes (a hand-written kernel), so each lane, the tail after the last four
// and the output times must each be seen. Prints `PASS <label> (<count>)`
// per check, or `FAIL <label>: ...` and exits 1.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "leadscrew/integrate/simulation_result.hpp"
#include "leadscrew/model/result_checks.hpp"

using leadscrew::integrate::InvariantCheck;
using leadscrew::integrate::SimulationResult;

namespace {

int failures = 0;

void report(const char* label, int count, int bad) {
  if (bad == 0) {
    std::printf("PASS %s (%d)\n", label, count);
  } else {
    std::printf("FAIL %s: %d of %d cases wrong\n", label, bad, count);
    ++failures;
  }
}

// A result of `points` rows of `channels` finite channels (the names the
// checks read, and others), every value distinct.
SimulationResult make_result(std::size_t points, std::size_t channels) {
  SimulationResult r;
  const std::vector<std::string> names = {"slip_velocity", "friction_force", "normal_force",
                                          "friction_loss", "energy_residual", "kinetic",
                                          "other_a",       "other_b",        "other_c"};
  r.channel_names.assign(names.begin(), names.begin() + static_cast<long>(channels));
  for (std::size_t i = 0; i < points; ++i) {
    r.time.push_back(0.1 * static_cast<double>(i));
    for (std::size_t k = 0; k < channels; ++k)
      r.values.push_back(k == 5 ? 1.0 : 1e-3 * static_cast<double>(i * channels + k + 1));
  }
  return r;
}

const InvariantCheck& finite_check(const SimulationResult& r) {
  for (const InvariantCheck& c : r.checks)
    if (std::string(c.name) == "finite") return c;
  std::printf("FAIL no finite check\n");
  std::exit(1);
}

leadscrew::model::ResultCheckSpec spec() {
  leadscrew::model::ResultCheckSpec s;
  s.t_end = 10.0;
  s.rtol = 1e-8;
  s.atol = 1e-10;
  return s;
}

}  // namespace

int main() {
  const double bad_values[] = {std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity(),
                               std::numeric_limits<double>::quiet_NaN(),
                               -std::numeric_limits<double>::quiet_NaN()};
  int count = 0, wrong = 0;
  // Finite results pass, whatever their size (0 to 9 rows of 5 to 9
  // channels: every remainder of the four lanes).
  for (std::size_t points = 0; points < 10; ++points)
    for (std::size_t channels = 5; channels <= 9; ++channels) {
      SimulationResult r = make_result(points, channels);
      leadscrew::model::check_result(spec(), r);
      ++count;
      if (!finite_check(r).passed) ++wrong;
    }
  report("finite results pass", count, wrong);

  // One non-finite value anywhere fails, naming its row.
  count = wrong = 0;
  for (std::size_t points = 1; points < 8; ++points)
    for (std::size_t channels = 5; channels <= 9; ++channels)
      for (std::size_t at = 0; at < points * channels; ++at)
        for (const double bad : bad_values) {
          SimulationResult r = make_result(points, channels);
          r.values[at] = bad;
          leadscrew::model::check_result(spec(), r);
          const InvariantCheck& c = finite_check(r);
          ++count;
          if (c.passed || c.bound != static_cast<double>(at / channels)) ++wrong;
        }
  report("a non-finite value fails at its row", count, wrong);

  count = wrong = 0;
  for (std::size_t points = 1; points < 10; ++points)
    for (std::size_t at = 0; at < points; ++at)
      for (const double bad : bad_values) {
        SimulationResult r = make_result(points, 6);
        r.time[at] = bad;
        leadscrew::model::check_result(spec(), r);
        const InvariantCheck& c = finite_check(r);
        ++count;
        if (c.passed || c.bound != static_cast<double>(at)) ++wrong;
      }
  report("a non-finite time fails at its row", count, wrong);

  std::printf(failures == 0 ? "OK\n" : "FAILED\n");
  return failures == 0 ? 0 : 1;
}
