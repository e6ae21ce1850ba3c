// Checks the code paths of the LCP core that Python does not reach:
//  - Lemke's fixed-size paths (n <= kMaxFixedLemkeSize) against its
//    size-generic path, bit for bit, and against enumerate where the solution
//    is unique, on seeded random families for every n they cover;
//  - the checked and unchecked entry points give the same answer;
//  - NaN or inf anywhere in M or q through the unchecked entry points never
//    yields Status::solved (every method, both Lemke paths, also where the
//    q >= 0 pre-check or a support-free column would hide it), while the
//    checked entry point throws InvalidArgument.
//
// Prints one line per check and "RESULT: PASS" or "RESULT: FAIL"; exit code 0
// on success.
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/lcp/enumerate.hpp"
#include "leadscrew/lcp/lcp.hpp"
#include "leadscrew/lcp/lemke.hpp"
#include "leadscrew/lcp/workspace.hpp"
#include "random_problems.hpp"

namespace lcp = leadscrew::lcp;

namespace {

int failures = 0;

void check(bool ok, const std::string& what, long value) {
  std::printf("%s %s (%ld)\n", ok ? "PASS" : "FAIL", what.c_str(), value);
  if (!ok) ++failures;
}

struct Problem {
  const char* family;
  bool unique;  // a P-matrix: one solution, which enumerate finds
  Eigen::MatrixXd M;
  Eigen::VectorXd q;
};

// Seeded families for size n: P-matrices (SPD, nonsymmetric positive
// definite, triangular with integer entries and degenerate q, Murty's) and
// degenerate positive semidefinite ones with many solutions.
std::vector<Problem> families(int n, std::mt19937& rng) {
  std::vector<Problem> problems;
  const Eigen::MatrixXd spd = lcp_problems::spd(rng, n, 0.1);
  problems.push_back({"spd", true, spd, lcp_problems::gaussian(rng, n, 1)});
  const Eigen::MatrixXd K = lcp_problems::gaussian(rng, n, n);
  problems.push_back({"pd_nonsym", true, Eigen::MatrixXd(spd + K - K.transpose()),
                      lcp_problems::gaussian(rng, n, 1)});
  std::uniform_int_distribution<int> entry(-1, 2), sign(-1, 1);
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = j + 1; i < n; ++i) T(i, j) = entry(rng);
  if (entry(rng) > 0) T.transposeInPlace();
  problems.push_back({"degenerate_p", true, T, lcp_problems::q_from_solution(T, rng)});
  Eigen::MatrixXd murty;
  Eigen::VectorXd murty_q;
  lcp_problems::murty(n, murty, murty_q);
  problems.push_back({"murty", true, murty, murty_q});
  Eigen::MatrixXd B(n, std::max(1, n / 2));
  for (int j = 0; j < B.cols(); ++j)
    for (int i = 0; i < n; ++i) B(i, j) = sign(rng);
  const Eigen::MatrixXd psd = lcp_problems::gram(B);
  problems.push_back({"degenerate_psd", false, psd, lcp_problems::q_from_solution(psd, rng)});
  return problems;
}

bool same_bits(const lcp::Result& a, const lcp::Result& b) {
  return a.status == b.status && a.iterations == b.iterations &&
         (a.residual == b.residual || (std::isnan(a.residual) && std::isnan(b.residual)));
}

void fixed_size_paths() {
  constexpr int kSeeds = 40;
  lcp::Workspace workspace;
  lcp::Options options;
  std::mt19937 rng(314159);
  for (int n = 1; n <= lcp::kMaxFixedLemkeSize; ++n) {
    long compared = 0, differ = 0, checked_differ = 0, unique = 0, enumerate_differ = 0,
         unsolved = 0;
    for (int seed = 0; seed < kSeeds; ++seed) {
      for (const Problem& p : families(n, rng)) {
        Eigen::VectorXd z(n), w(n), zg(n), wg(n), zc(n), wc(n), ze(n), we(n);
        const lcp::Result fixed = lcp::solve_lemke_unchecked(p.M, p.q, z, w, options, workspace);
        const lcp::Result generic =
            lcp::solve_lemke_generic(p.M, p.q, zg, wg, options, workspace);
        const lcp::Result checked = lcp::solve_lemke(p.M, p.q, zc, wc, options, workspace);
        ++compared;
        if (!same_bits(fixed, generic) || z != zg || w != wg) {
          ++differ;
          std::printf("INFO differ: %s n=%d seed %d\n", p.family, n, seed);
        }
        if (!same_bits(fixed, checked) || z != zc || w != wc) ++checked_differ;
        if (fixed.status != lcp::Status::solved) ++unsolved;
        if (p.unique) {
          ++unique;
          lcp::Options enumerate = options;
          enumerate.method = lcp::Method::enumerate;
          const lcp::Result reference = lcp::solve(p.M, p.q, ze, we, enumerate, workspace);
          const double scale = 1.0 + ze.cwiseAbs().maxCoeff();
          if (reference.status != lcp::Status::solved ||
              (z - ze).cwiseAbs().maxCoeff() > 1e-9 * scale)
            ++enumerate_differ;
        }
      }
    }
    const std::string size = "n=" + std::to_string(n);
    check(differ == 0 && compared == 5 * kSeeds,
          "fixed-size lemke == generic lemke bit for bit, " + size, compared);
    check(checked_differ == 0, "checked lemke == unchecked lemke, " + size, compared);
    check(unsolved == 0, "lemke solves every problem, " + size, compared);
    check(enumerate_differ == 0 && unique == 4 * kSeeds,
          "fixed-size lemke == enumerate on P-matrices, " + size, unique);
  }
}

// NaN, +inf, -inf at every entry of M and q (a sample of the entries for
// n > 8) of a problem that is solved without them: the unchecked entry
// points must never report solved, the checked one must throw.
void non_finite_input() {
  const double poisons[] = {std::numeric_limits<double>::quiet_NaN(),
                            std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity()};
  lcp::Workspace workspace;
  std::mt19937 rng(2718);
  long solves = 0, claimed_solved = 0, not_thrown = 0, base_unsolved = 0;
  for (const int n : {1, 2, 3, 5, 8, 9, 12, 16}) {
    const Eigen::MatrixXd spd = lcp_problems::spd(rng, n, 0.1);
    // Two bases: q with negative entries (pivoting) and q >= 0 (Lemke's
    // pre-check, z = 0, where only the columns off the support hold the NaN).
    std::vector<Eigen::VectorXd> bases = {lcp_problems::gaussian(rng, n, 1),
                                          lcp_problems::gaussian(rng, n, 1).cwiseAbs()};
    bases[0][0] = -1.0;
    const int stride = n <= 8 ? 1 : 7;
    for (const Eigen::VectorXd& q0 : bases) {
      for (int entry = 0; entry < n * n + n; entry += stride) {
        for (const double poison : poisons) {
          Eigen::MatrixXd M = spd;
          Eigen::VectorXd q = q0;
          if (entry < n * n)
            M(entry % n, entry / n) = poison;
          else
            q[entry - n * n] = poison;
          for (int m = 0; m < 5; ++m) {  // lemke, pgs, newton_fb, enumerate, lemke generic
            lcp::Options options;
            options.method = static_cast<lcp::Method>(m % 4);
            if (options.method == lcp::Method::enumerate && n > lcp::kMaxEnumerateSize) continue;
            if (options.method == lcp::Method::pgs) options.max_iter = 200;
            Eigen::VectorXd z = Eigen::VectorXd::Zero(n), w(n);
            const lcp::Result result =
                m == 4 ? lcp::solve_lemke_generic(M, q, z, w, options, workspace)
                       : lcp::solve_unchecked(M, q, z, w, options, workspace);
            ++solves;
            if (result.status == lcp::Status::solved || result.residual <= options.tol) {
              ++claimed_solved;
              std::printf("INFO claimed solved: n=%d entry %d value %g method %d\n", n, entry,
                          poison, m);
            }
            if (m == 4) continue;
            try {
              lcp::solve(M, q, z, w, options, workspace);
              ++not_thrown;
            } catch (const leadscrew::InvalidArgument&) {
            }
          }
        }
      }
      // The same base without poison is solved (the checks above test something).
      Eigen::VectorXd z(n), w(n);
      if (lcp::solve(spd, q0, z, w, lcp::Options{}, workspace).status != lcp::Status::solved)
        ++base_unsolved;
    }
  }
  check(claimed_solved == 0, "NaN or inf in M or q never solved (unchecked entry points)",
        solves);
  check(not_thrown == 0, "NaN or inf in M or q throws InvalidArgument (checked entry point)",
        solves);
  check(base_unsolved == 0, "the problems without NaN or inf are solved", base_unsolved);
  check(lcp::complementarity_residual(Eigen::Vector2d(std::nan(""), 0.0), Eigen::Vector2d(1, 1)) ==
            std::numeric_limits<double>::infinity(),
        "complementarity_residual of a NaN pair is +inf", 0);
}

}  // namespace

int main() {
  fixed_size_paths();
  non_finite_input();
  std::printf("RESULT: %s\n", failures == 0 ? "PASS" : "FAIL");
  return failures == 0 ? 0 : 1;
}
