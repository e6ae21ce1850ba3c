// A system's own Runge-Kutta stage loop (OdeSystem::explicit_rk_stages, its
// rhs inlined: rk_stage_kernels.hpp) gives the same numbers, bit for bit, as
// the engine's loop through the virtual rhs: for Dormand-Prince 5(4) and
// Verner 6(5), on 2 and 4 states, with a right-hand side shaped like the
// friction block's (arctan velocity law, sine load, memo members, work
// integrals); the loop against a plain transcription of its definition; and
// that the engine takes a system's own loop. Prints PASS/FAIL lines and
// "RESULT: PASS" last
// (tests/test_integrate_native.py builds and runs it).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "leadscrew/excitation/sine.hpp"
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
      friction_memo = 2.0 / M_PI * 3.0 * std::atan(10.0 * velocity);
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

// Which stage loop a system offers the engine: none (the engine's own, one
// virtual rhs call per stage), its own (the rhs inlined), or its own behind
// a counter of its calls (the engine must take a system's own loop).
enum class Loop { engine, own, counted };

long counted_calls = 0;

template <int N, Loop loop>
struct BlockSystem final : integrate::OdeSystem {
  Block<N> block;
  int size() const override { return N; }
  void rhs(double t, const double* y, double* ydot) override { block.evaluate(t, y, ydot); }
  template <int S>
  static void counting(integrate::OdeSystem& system, const double* a, const double* c, double t,
                       const double* y, double h, double* k, double* y_stage) {
    ++counted_calls;
    integrate::rk_kernels::stage_kernel<BlockSystem, N, S>(system, a, c, t, y, h, k, y_stage);
  }
  integrate::RkStageKernel explicit_rk_stages(int stage_count) const override {
    if (loop == Loop::own)
      return integrate::rk_kernels::stage_kernel_for<BlockSystem, N>(stage_count);
    if (loop == Loop::counted)
      return stage_count == 7 ? &counting<7> : stage_count == 8 ? &counting<8> : nullptr;
    return nullptr;
  }
};

template <int N>
using Virtual = BlockSystem<N, Loop::engine>;
template <int N>
using Inlined = BlockSystem<N, Loop::own>;
using Counted = BlockSystem<4, Loop::counted>;

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

// The stage loop against a plain transcription of its definition,
// k_i = f(t + c_i h, y + h sum_{j<i} a_ij k_j), on arbitrary data: a slip
// in the templates' indices would show here (the engine comparison below
// runs the same templates on both sides).
template <int S>
void check_against_definition(const integrate::ButcherTableau& tableau) {
  constexpr int N = 4;
  double y[N], k[S * N], k_reference[S * N], y_stage[N], y_stage_reference[N];
  for (int r = 0; r < N; ++r) y[r] = 0.3 * r - 0.4;
  for (int r = 0; r < N; ++r) k[r] = k_reference[r] = 1.0 - 0.7 * r;
  const double t = 0.37, h = 0.011;
  const double* a = tableau.a.data();
  const double* c = tableau.c.data();
  Inlined<N> system;
  integrate::rk_kernels::stage_kernel<Inlined<N>, N, S>(system, a, c, t, y, h, k, y_stage);
  Inlined<N> reference;
  for (int i = 1; i < S; ++i) {
    for (int r = 0; r < N; ++r) {
      double sum = y[r];
      for (int j = 0; j < i; ++j) sum += (h * a[i * S + j]) * k_reference[j * N + r];
      y_stage_reference[r] = sum;
    }
    reference.rhs(t + c[i] * h, y_stage_reference, k_reference + i * N);
  }
  check(std::memcmp(k, k_reference, sizeof k) == 0 &&
            std::memcmp(y_stage, y_stage_reference, sizeof y_stage) == 0,
        "stage loop as defined: " + tableau.name);
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
  check_against_definition<7>(integrate::dopri5_tableau());
  check_against_definition<8>(integrate::verner6_tableau());
  for (const integrate::ButcherTableau* tableau :
       {&integrate::dopri5_tableau(), &integrate::verner6_tableau()}) {
    counted_calls = 0;
    double seconds = 0.0;
    const std::size_t values = run<Counted>(*tableau, &seconds).size();
    check(counted_calls > 0 && counted_calls >= static_cast<long>(values / 5) - 1,
          "the engine takes the system's own stage loop: " + tableau->name + " (" +
              std::to_string(counted_calls) + " calls)");
  }
  compare<2>(integrate::dopri5_tableau());
  compare<4>(integrate::dopri5_tableau());
  compare<2>(integrate::verner6_tableau());
  compare<4>(integrate::verner6_tableau());
  std::printf("RESULT: %s\n", all_pass ? "PASS" : "FAIL");
  return all_pass ? 0 : 1;
}
