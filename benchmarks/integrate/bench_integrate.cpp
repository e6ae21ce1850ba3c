// Overhead of the ODE integrators on a 2-state problem, and the event-driven
// friction block that the target (< 50 us for 2 s at 1e-9) refers to.
//
//   per step:    a harmonic oscillator integrated without events; the time per
//                step minus the rhs calls is the integrator's own cost.
//   per restart: reinitialize + advance over 1 ms (a few steps), repeated;
//                also counts heap allocations in that loop (must be 0).
//   block:       a mass on a rough surface with a spring and sine forcing
//                (Coulomb friction, stick-slip): an event-driven simulation of
//                2 s, each event a restart; for each method the loosest
//                tolerance whose event times and final state are within 1e-9
//                of a reference, and the time the whole simulation takes.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "allocation_counter.hpp"
#include "friction_block_system.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/integrate/ode.hpp"

using leadscrew::integrate::AdvanceStatus;
using leadscrew::integrate::Integrator;
using leadscrew::integrate::IntegratorOptions;
using leadscrew::integrate::OdeSystem;
using bench::BlockRun;
using bench::FrictionBlock;
using bench::pi;
using bench::simulate_block;
using bench::max_events;

namespace {

struct Oscillator final : OdeSystem {
  double omega2 = 4.0 * pi * pi;
  int size() const override { return 2; }
  void rhs(double, const double* y, double* ydot) override {
    ydot[0] = y[1];
    ydot[1] = -omega2 * y[0];
  }
};

// The machine is shared: the minimum over repeats is the least disturbed
// run; the median is printed where it matters.
bool use_minimum = true;

template <class F>
double repeat_seconds(F&& f, int repeats, double* median = nullptr) {
  std::vector<double> times;
  for (int i = 0; i < repeats; ++i) {
    const auto a = std::chrono::steady_clock::now();
    f();
    const auto b = std::chrono::steady_clock::now();
    times.push_back(std::chrono::duration<double>(b - a).count());
  }
  std::sort(times.begin(), times.end());
  if (median) *median = times[times.size() / 2];
  return use_minimum ? times.front() : times[times.size() / 2];
}

double rhs_cost(OdeSystem& system) {
  double y[2] = {0.3, 0.1}, f[2];
  const int n = 1000000;
  volatile double sink = 0.0;
  const double s = repeat_seconds(
      [&] {
        for (int i = 0; i < n; ++i) {
          y[0] += 1e-12;
          system.rhs(1e-6 * i, y, f);
          sink = sink + f[1];
        }
      },
      5);
  return s / n;
}

}  // namespace

int main(int argc, char** argv) {
  const bool verbose = argc > 1 && std::string(argv[1]) == "-v";
  const std::vector<std::string> methods = leadscrew::integrate::integrator_names();

  Oscillator oscillator;
  const double oscillator_rhs = rhs_cost(oscillator);
  std::printf("oscillator rhs call: %.1f ns\n", oscillator_rhs * 1e9);
  {
    FrictionBlock b;
    b.mode = 1;
    std::printf("friction block rhs call (slipping): %.1f ns\n\n", rhs_cost(b) * 1e9);
  }

  std::printf("per step (oscillator, 10 periods, rtol 1e-9, atol 1e-12):\n");
  std::printf("%-14s %8s %8s %12s %14s\n", "method", "steps", "rhs", "ns/step", "ns/step-rhs");
  for (const auto& name : methods) {
    IntegratorOptions options;
    options.rtol = 1e-9;
    options.atol = 1e-12;
    auto integrator = leadscrew::integrate::make_integrator(name, options);
    Eigen::Vector2d y0(1.0, 0.0), y;
    integrator->initialize(oscillator, 0.0, y0);
    long steps = 0, rhs = 0;
    const double s = repeat_seconds(
        [&] {
          integrator->reinitialize(0.0, y0);
          const auto before = integrator->stats();
          integrator->advance(10.0, y);
          const auto after = integrator->stats();
          steps = after.steps - before.steps;
          rhs = after.rhs_evaluations - before.rhs_evaluations;
        },
        21);
    std::printf("%-14s %8ld %8ld %12.1f %14.1f\n", name.c_str(), steps, rhs, s / steps * 1e9,
                (s - rhs * oscillator_rhs) / steps * 1e9);
  }

  std::printf("\nper restart (reinitialize + advance 1 ms, oscillator, rtol 1e-9):\n");
  std::printf("%-14s %12s %12s %12s\n", "method", "us/restart", "steps/rst", "allocs/rst");
  for (const auto& name : methods) {
    IntegratorOptions options;
    options.rtol = 1e-9;
    options.atol = 1e-12;
    auto integrator = leadscrew::integrate::make_integrator(name, options);
    Eigen::Vector2d y0(1.0, 0.0), y;
    integrator->initialize(oscillator, 0.0, y0);
    const int restarts = 2000;
    long steps = 0;
    unsigned long allocations = 0;
    const double s = repeat_seconds(
        [&] {
          const long before = integrator->stats().steps;
          const unsigned long a0 = allocation_count();
          double t = 0.0;
          for (int i = 0; i < restarts; ++i) {
            integrator->reinitialize(t, y0);
            integrator->advance(t + 1e-3, y);
            t += 1e-3;
          }
          allocations = allocation_count() - a0;
          steps = integrator->stats().steps - before;
        },
        7);
    std::printf("%-14s %12.2f %12.1f %12.2f\n", name.c_str(), s / restarts * 1e6,
                double(steps) / restarts, double(allocations) / restarts);
  }

  // Reference: the tightest tolerance of every method must agree; the best
  // agreement pair is taken as the reference.
  FrictionBlock block;
  const double t_end = 2.0;
  // Roots are detected by sign changes between step ends: while the block
  // sticks, f = 0 and steps would grow without bound, stepping over both
  // crossings of a break-away root. An eighth of the forcing period resolves them.
  const double block_max_step = 2.0 * pi / block.W / 8.0;
  // The reference: ARKODE's Verner 6(5) at rtol 1e-13; its agreement with two
  // other methods at the same tolerance bounds its own error.
  auto tight_run = [&](const std::string& name) {
    IntegratorOptions options;
    options.rtol = 1e-13;
    options.atol = 1e-15;
    options.max_step = block_max_step;
    auto integrator = leadscrew::integrate::make_integrator(name, options);
    integrator->initialize(block, 0.0, Eigen::Vector2d(0.0, 0.0));
    BlockRun run;
    simulate_block(*integrator, block, t_end, run);
    return run;
  };
  const BlockRun reference = tight_run("verner6");
  for (const char* other : {"rk_verner6", "cvode_adams"}) {
    const BlockRun run = tight_run(other);
    double difference = std::fabs(run.x_end - reference.x_end);
    for (std::size_t i = 0; i < run.events.size() && i < reference.events.size(); ++i)
      difference = std::max(difference, std::fabs(run.events[i] - reference.events[i]));
    std::printf("reference check: %s at rtol 1e-13: %zu events, max difference %.2e\n", other,
                run.events.size(), difference);
  }
  std::printf("\nfriction block (2 s, %zu events; reference verner6 rtol 1e-13), x(2) = %.15f\n",
              reference.events.size(), reference.x_end);
  if (verbose)
    for (double t : reference.events) std::printf("  event %.15f\n", t);
  std::printf("%-14s %10s %14s %8s %8s %8s %10s\n", "method", "rtol", "max error", "steps",
              "us min", "us med", "us + init");
  for (const auto& name : methods) {
    bool done = false;
    for (double rtol = 1e-6; rtol >= 1e-14 && !done; rtol /= std::sqrt(10.0)) {
      IntegratorOptions options;
      options.rtol = rtol;
      options.atol = rtol * 1e-2;
      options.max_step = block_max_step;
      auto integrator = leadscrew::integrate::make_integrator(name, options);
      integrator->initialize(block, 0.0, Eigen::Vector2d(0.0, 0.0));
      BlockRun run;
      run.events.reserve(max_events);
      try {
        simulate_block(*integrator, block, t_end, run);
      } catch (const leadscrew::SimulationError& e) {
        std::printf("%-14s %10.1e failed: %s\n", name.c_str(), rtol, e.what());
        continue;
      }
      double error = std::fabs(run.x_end - reference.x_end) + std::fabs(run.v_end - reference.v_end);
      if (run.events.size() != reference.events.size()) {
        if (verbose) std::printf("  %s rtol %.1e: %zu events\n", name.c_str(), rtol, run.events.size());
        continue;
      }
      for (std::size_t i = 0; i < run.events.size(); ++i)
        error = std::max(error, std::fabs(run.events[i] - reference.events[i]));
      if (verbose) std::printf("  %s rtol %.1e: error %.2e\n", name.c_str(), rtol, error);
      if (error > 1e-9) continue;
      done = true;
      const auto s0 = integrator->stats();
      simulate_block(*integrator, block, t_end, run);
      const auto s1 = integrator->stats();
      const long steps = s1.steps - s0.steps;
      const long rhs = s1.rhs_evaluations - s0.rhs_evaluations;
      const long roots = s1.root_evaluations - s0.root_evaluations;
      const long rejected = s1.error_test_failures - s0.error_test_failures;
      const unsigned long a0 = allocation_count();
      simulate_block(*integrator, block, t_end, run);
      const unsigned long allocations = allocation_count() - a0;
      double median = 0.0;
      const double s =
          repeat_seconds([&] { simulate_block(*integrator, block, t_end, run); }, 201, &median);
      const double s_init = repeat_seconds(
          [&] {
            auto fresh = leadscrew::integrate::make_integrator(name, options);
            fresh->initialize(block, 0.0, Eigen::Vector2d(0.0, 0.0));
            simulate_block(*fresh, block, t_end, run);
          },
          51);
      std::printf(
          "%-14s %10.1e %14.2e %8ld %8.1f %8.1f %10.1f   (rhs %ld, roots %ld, rejected %ld, "
          "allocations %lu)\n",
          name.c_str(), rtol, error, steps, s * 1e6, median * 1e6, s_init * 1e6, rhs, roots,
          rejected, allocations);
    }
    if (!done) std::printf("%-14s did not reach 1e-9\n", name.c_str());
  }
  return 0;
}
