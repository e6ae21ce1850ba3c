// A system's own Runge-Kutta stage loop (OdeSystem::explicit_rk_stages, its
// rhs inlined: rk_stage_kernels.hpp) gives the same numbers, bit for bit, as
// the engine's loop through the virtual rhs: for Dormand-Prince 5(4) and
// Verner 6(5), on 2 and 4 states, with a right-hand side shaped like the
// friction block's (arctan velocity law, sine load, memo members, work
// integrals). Prints PASS/FAIL lines and "RESULT: PASS" last
// (tests/test_integrate_native.py builds and runs it).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "leadscrew/excitation/sine.hpp"
#include "leadscrew/friction/arctan.hpp"
#include "leadscrew/integrate/explicit_rk.hpp"
#include "leadscrew/integrate/rk_dopri5.hpp"
#include "leadscrew/integrate/rk_stage_kernels.hpp"
#include "leadscrew/integrate/rk_verner6.hpp"

namespace integrate = leadscrew::integrate;

namespace {

// m u'' = V sin(w t) - (2/pi) mu N atan(k_V u'), with the works of the load
// and of friction as states 3 and 4 when N = 4.
template <int N>
struct Block {
  double velocity_memo = NAN, friction_memo = 0.0;
  void evaluate(double t, const double* y, double* ydot) {
    const double velocity = y[1];
    const double force = 6.0 * leadscrew::excitation::sine(4.0 * M_PI * t);
    if (velocity != velocity_memo) {
      friction_memo = 2.0 / M_PI * 3.0 * leadscrew::friction::arctan(10.0 * velocity);
      velocity_memo = velocity;
    }
    ydot[0] = velocity;
    ydot[1] = force - friction_memo;
    if constexpr (N == 4) {
      ydot[2] = force * velocity;
      ydot[3] = friction_memo * velocity;
    }
  }
};

template <int N>
struct Virtual final : integrate::OdeSystem {
  Block<N> block;
  int size() const override { return N; }
  void rhs(double t, const double* y, double* ydot) override { block.evaluate(t, y, ydot); }
};

template <int N>
struct Inlined final : integrate::OdeSystem {
  Block<N> block;
  int size() const override { return N; }
  void rhs(double t, const double* y, double* ydot) override { block.evaluate(t, y, ydot); }
  integrate::RkStageKernel explicit_rk_stages(int stage_count) const override {
    return integrate::rk_kernels::stage_kernel_for<Inlined, N>(stage_count);
  }
};

// Every accepted step's (t, y), and the run's wall time [s].
template <class System>
std::vector<double> run(const integrate::ButcherTableau& tableau, double* seconds) {
  System system;
  integrate::IntegratorOptions options;
  options.rtol = 1e-7;
  options.atol = 1e-9;
  integrate::ExplicitRungeKutta rk(tableau, options);
  const int n = system.size();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
  std::vector<double> out;
  const auto start = std::chrono::steady_clock::now();
  rk.initialize(system, 0.0, y);
  for (int step = 0; step < 100000; ++step) {
    const auto r = rk.advance(2.0, y, true);
    out.push_back(r.t);
    for (int i = 0; i < n; ++i) out.push_back(y[i]);
    if (r.t >= 2.0) break;
  }
  *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

bool all_pass = true;

void check(bool pass, const std::string& label) {
  std::printf("%s %s\n", pass ? "PASS" : "FAIL", label.c_str());
  all_pass = all_pass && pass;
}

template <int N>
void compare(const integrate::ButcherTableau& tableau) {
  const std::string what = tableau.name + ", " + std::to_string(N) + " states";
  check(Inlined<N>().explicit_rk_stages(tableau.stages) != nullptr &&
            Virtual<N>().explicit_rk_stages(tableau.stages) == nullptr,
        "own stage loop offered: " + what);
  double virtual_seconds = 0.0, inlined_seconds = 0.0;
  const std::vector<double> reference = run<Virtual<N>>(tableau, &virtual_seconds);
  const std::vector<double> own = run<Inlined<N>>(tableau, &inlined_seconds);
  check(reference.size() > 40 * (N + 1) && own.size() == reference.size() &&
            std::memcmp(own.data(), reference.data(), own.size() * sizeof(double)) == 0,
        "same bits with the own stage loop: " + what + " (" +
            std::to_string(reference.size() / (N + 1)) + " steps)");
  std::printf("INFO %s: virtual %.1f us, own %.1f us\n", what.c_str(), 1e6 * virtual_seconds,
              1e6 * inlined_seconds);
}

}  // namespace

int main() {
  compare<2>(integrate::dopri5_tableau());
  compare<4>(integrate::dopri5_tableau());
  compare<2>(integrate::verner6_tableau());
  compare<4>(integrate::verner6_tableau());
  std::printf("RESULT: %s\n", all_pass ? "PASS" : "FAIL");
  return all_pass ? 0 : 1;
}
