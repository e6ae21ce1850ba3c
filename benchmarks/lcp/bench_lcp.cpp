// Times one LCP solve of every leadscrew method (one Workspace, reused: no
// allocation) and, when built with Siconos, of Siconos numerics'
// lcp_lexicolemke on the same problems; checks that the answers agree.
// The methods are timed through lcp::solve_unchecked (no scan of M and q for
// NaN and inf: the entry point of the integrators; Siconos does not scan
// either). Lemke is also timed through the checked lcp::solve ("checked") and
// on its size-generic code path ("generic", lcp::solve_lemke_generic).
//
// Problem families, sizes n = 2, 4, 8, 16, kInstances seeded instances each:
//   spd       M = A A^T / n + 0.1 I (A standard normal), q standard normal
//   friction  leadscrew::friction::friction_lcp of n/2 coupled contacts:
//             G = B B^T / k + 0.05 I, c ~ 3 N(0, 1), mu ~ U(0.1, 0.8),
//             lambda_N ~ U(1, 5)  (unique solution, A = [[G, I], [-I, 0]])
// Per instance the time of one solve is the median over kBatches batches of
// repeated solves; the tables give the median over the instances and, for
// Siconos, the medians over instances of the ratios t_siconos / t_lemke and
// t_siconos / t_checked.
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "leadscrew/friction/coulomb_lcp.hpp"
#include "leadscrew/lcp/enumerate.hpp"
#include "leadscrew/lcp/lcp.hpp"
#include "leadscrew/lcp/lemke.hpp"
#include "leadscrew/lcp/workspace.hpp"
#include "random_problems.hpp"  // tests/cpp

#ifdef LEADSCREW_BENCH_WITH_SICONOS
#include "siconos_lemke.hpp"
#endif

namespace lcp = leadscrew::lcp;

namespace {

constexpr int kInstances = 20;
constexpr int kBatches = 7;
constexpr double kBatchSeconds = 2e-4;  // each batch runs at least this long
volatile double sink = 0.0;

struct Problem {
  Eigen::MatrixXd M;
  Eigen::VectorXd q;
};

using lcp_problems::gaussian;

Problem spd_problem(std::mt19937& rng, int n) {
  Eigen::MatrixXd M = lcp_problems::spd(rng, n, 0.1);
  return {M, gaussian(rng, n, 1)};
}

Problem friction_problem(std::mt19937& rng, int n) {
  const int k = n / 2;
  const Eigen::MatrixXd G = lcp_problems::spd(rng, k, 0.05);
  const Eigen::VectorXd c = 3.0 * gaussian(rng, k, 1);
  std::uniform_real_distribution<double> mu_draw(0.1, 0.8), normal_draw(1.0, 5.0);
  Eigen::VectorXd mu(k), normal(k);
  for (int i = 0; i < k; ++i) mu[i] = mu_draw(rng), normal[i] = normal_draw(rng);
  Problem p{Eigen::MatrixXd(n, n), Eigen::VectorXd(n)};
  leadscrew::friction::friction_lcp(G, c, mu, normal, p.M, p.q);
  return p;
}

// Median seconds per call of f() over kBatches batches.
template <class F>
double time_per_call(F&& f) {
  using clock = std::chrono::steady_clock;
  int repeats = 1;
  while (true) {  // calibrate the batch length
    const auto start = clock::now();
    for (int r = 0; r < repeats; ++r) f();
    const double elapsed = std::chrono::duration<double>(clock::now() - start).count();
    if (elapsed >= kBatchSeconds || repeats >= (1 << 24)) break;
    repeats *= 2;
  }
  std::vector<double> samples;
  for (int b = 0; b < kBatches; ++b) {
    const auto start = clock::now();
    for (int r = 0; r < repeats; ++r) f();
    samples.push_back(std::chrono::duration<double>(clock::now() - start).count() / repeats);
  }
  std::nth_element(samples.begin(), samples.begin() + kBatches / 2, samples.end());
  return samples[kBatches / 2];
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  double m = v[v.size() / 2];
  if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), v.begin() + v.size() / 2));
  return m;
}

bool agree(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() <= 1e-8 * (1.0 + b.cwiseAbs().maxCoeff());
}

}  // namespace

int main() {
  const char* families[] = {"spd", "friction"};
  const int sizes[] = {2, 4, 8, 16};
  const lcp::Method methods[] = {lcp::Method::lemke, lcp::Method::pgs, lcp::Method::newton_fb,
                                 lcp::Method::enumerate};
  lcp::Workspace workspace;
  int disagreements = 0;

  std::printf("Median time of one solve [us] over %d instances per row (each the median of "
              "%d batches)\n", kInstances, kBatches);
  std::printf("%-9s %3s | %8s %8s %8s | %9s %9s %9s", "family", "n", "lemke", "checked",
              "generic", "pgs", "newton_fb", "enumerate");
#ifdef LEADSCREW_BENCH_WITH_SICONOS
  std::printf(" | %8s %13s %15s %6s", "siconos", "siconos/lemke", "siconos/checked", "pivots");
#endif
  std::printf(" | solved (l/p/n/e%s)\n",
#ifdef LEADSCREW_BENCH_WITH_SICONOS
              "/siconos"
#else
              ""
#endif
  );

  for (const char* family : families) {
    for (const int n : sizes) {
      std::mt19937 rng(1000u * static_cast<unsigned>(n) + (family[0] == 's' ? 1u : 2u));
      std::vector<double> times[4], checked_times, generic_times, siconos_times, ratios,
          checked_ratios, lemke_pivots;
      int solved[4] = {0, 0, 0, 0}, siconos_solved = 0;
      for (int instance = 0; instance < kInstances; ++instance) {
        const Problem p = family[0] == 's' ? spd_problem(rng, n) : friction_problem(rng, n);
        Eigen::VectorXd z(n), w(n), z_lemke(n);
        for (int m = 0; m < 4; ++m) {
          if (methods[m] == lcp::Method::enumerate && n > lcp::kMaxEnumerateSize) continue;
          lcp::Options options;
          options.method = methods[m];
          const lcp::Result result = lcp::solve_unchecked(p.M, p.q, z, w, options, workspace);
          const Eigen::VectorXd z_first = z;
          if (result.status == lcp::Status::solved) {
            ++solved[m];
            if (m == 0) {
              z_lemke = z;
              lemke_pivots.push_back(result.iterations);
            } else if (!agree(z, z_lemke)) {
              ++disagreements;
              std::printf("DISAGREE %s n=%d instance %d: %s vs lemke\n", family, n, instance,
                          lcp::method_name(methods[m]).c_str());
            }
          }
          times[m].push_back(time_per_call([&] {
            sink = sink + lcp::solve_unchecked(p.M, p.q, z, w, options, workspace).residual;
          }));
          if (m != 0) continue;
          // Lemke through the checked entry point and on the generic code path:
          // the same answer, bit for bit.
          Eigen::VectorXd z_other(n), w_other(n);
          for (const bool checked : {true, false}) {
            const lcp::Result other =
                checked ? lcp::solve(p.M, p.q, z_other, w_other, options, workspace)
                        : lcp::solve_lemke_generic(p.M, p.q, z_other, w_other, options, workspace);
            if (other.status != result.status || other.iterations != result.iterations ||
                z_other != z_first) {
              ++disagreements;
              std::printf("DISAGREE %s n=%d instance %d: lemke %s vs lemke\n", family, n,
                          instance, checked ? "checked" : "generic");
            }
          }
          checked_times.push_back(time_per_call([&] {
            sink = sink + lcp::solve(p.M, p.q, z, w, options, workspace).residual;
          }));
          generic_times.push_back(time_per_call([&] {
            sink = sink + lcp::solve_lemke_generic(p.M, p.q, z, w, options, workspace).residual;
          }));
        }
#ifdef LEADSCREW_BENCH_WITH_SICONOS
        SiconosLemke siconos(p.M, p.q);
        Eigen::VectorXd zs = Eigen::VectorXd::Zero(n), ws = Eigen::VectorXd::Zero(n);
        const int info = siconos.solve(zs, ws);
        const Eigen::VectorXd w_check = p.M * zs + p.q;
        if (info == 0 && lcp::complementarity_residual(zs, w_check) <= 1e-10) ++siconos_solved;
        if (!agree(zs, z_lemke)) {
          ++disagreements;
          std::printf("DISAGREE %s n=%d instance %d: siconos (info %d) vs lemke\n", family, n,
                      instance, info);
        }
        siconos_times.push_back(time_per_call([&] {
          zs.setZero();
          sink = sink + siconos.solve(zs, ws);
        }));
        ratios.push_back(siconos_times.back() / times[0].back());
        checked_ratios.push_back(siconos_times.back() / checked_times.back());
#endif
      }
      std::printf("%-9s %3d | %8.3f %8.3f %8.3f |", family, n, 1e6 * median(times[0]),
                  1e6 * median(checked_times), 1e6 * median(generic_times));
      for (int m = 1; m < 4; ++m) {
        if (times[m].empty())
          std::printf(" %9s", "n/a");
        else
          std::printf(" %9.3f", 1e6 * median(times[m]));
      }
#ifdef LEADSCREW_BENCH_WITH_SICONOS
      std::printf(" | %8.3f %13.2f %15.2f %6.1f", 1e6 * median(siconos_times), median(ratios),
                  median(checked_ratios), median(lemke_pivots));
#endif
      std::printf(" | %d/%d/%d/%d", solved[0], solved[1], solved[2], solved[3]);
#ifdef LEADSCREW_BENCH_WITH_SICONOS
      std::printf("/%d", siconos_solved);
#endif
      std::printf("\n");
    }
  }
  std::printf("(enumerate is not run for n > 12: n/a; pgs reports 'singular' at once on the "
              "friction family, whose diagonal has zeros)\n");
  std::printf("disagreements: %d\n", disagreements);
  return disagreements == 0 ? 0 : 1;
}
