// Native check that Python cannot make: the integrators do not allocate on
// the heap after initialize, in restarts (reinitialize), advances, root
// location and dense output, for every method. The counter interposes malloc
// & co. for the whole process (allocation_counter.cpp), SUNDIALS included;
// positive controls show that it sees allocations. Prints PASS/FAIL lines and
// "RESULT: PASS" last (tests/test_integrate_native.py parses them).
#include <cstdio>
#include <string>
#include <vector>

#include "allocation_counter.hpp"
#include "friction_block_system.hpp"

using leadscrew::integrate::IntegratorOptions;

int main() {
  bool all_pass = true;
  auto report = [&](bool pass, const std::string& label, unsigned long count) {
    std::printf("%s %s (%lu)\n", pass ? "PASS" : "FAIL", label.c_str(), count);
    all_pass = all_pass && pass;
  };

  bench::FrictionBlock block;
  IntegratorOptions options;
  options.rtol = 1e-8;
  options.atol = 1e-10;
  options.max_step = 2.0 * bench::pi / block.W / 8.0;
  const double t_end = 2.0;

  {  // positive controls
    unsigned long before = allocation_count();
    std::vector<double> v(100, 1.0);
    volatile double sink = v[99];
    (void)sink;
    report(allocation_count() > before, "counter sees std::vector", allocation_count() - before);
    before = allocation_count();
    auto integrator = leadscrew::integrate::make_integrator("cvode_adams", options);
    integrator->initialize(block, 0.0, Eigen::Vector2d(0.0, 0.0));
    report(allocation_count() > before, "counter sees SUNDIALS allocating in initialize",
           allocation_count() - before);
  }

  for (const std::string& name : leadscrew::integrate::integrator_names()) {
    auto integrator = leadscrew::integrate::make_integrator(name, options);
    integrator->initialize(block, 0.0, Eigen::Vector2d(0.0, 0.0));
    bench::BlockRun run;
    run.events.reserve(bench::max_events);
    bench::simulate_block(*integrator, block, t_end, run);  // warm-up
    Eigen::Vector2d y;
    const unsigned long before = allocation_count();
    bench::simulate_block(*integrator, block, t_end, run);
    integrator->dense_output(t_end, y);
    const auto stats = integrator->stats();
    const std::size_t roots = integrator->root_info().size();
    const unsigned long allocations = allocation_count() - before;
    report(allocations == 0, "no allocation in " + name + " restarts, advances, roots", allocations);
    std::printf("INFO %s: %zu events, %ld steps, %ld restarts, %zu root functions\n", name.c_str(),
                run.events.size(), stats.steps, stats.restarts, roots);
  }
  std::printf("RESULT: %s\n", all_pass ? "PASS" : "FAIL");
  return all_pass ? 0 : 1;
}
