// Proves that solving LCPs of size n <= 16 with a Workspace of the default
// capacity performs no heap allocation (checked and unchecked entry points),
// for every method and the problem
// families of tests/test_lcp.py, and that the friction builders do not
// allocate either. Positive controls show that the counter sees allocations
// (Eigen's, std::vector's, and a Workspace's growth).
//
// Prints one line per check and "RESULT: PASS" or "RESULT: FAIL"; exit code 0
// on success.
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "alloc_counter.hpp"
#include "leadscrew/friction/coulomb_lcp.hpp"
#include "leadscrew/lcp/enumerate.hpp"
#include "leadscrew/lcp/lcp.hpp"
#include "leadscrew/lcp/workspace.hpp"
#include "random_problems.hpp"

namespace lcp = leadscrew::lcp;
namespace friction = leadscrew::friction;

namespace {

int failures = 0;

void check(bool ok, const char* what, long value = 0) {
  std::printf("%s %s (%ld)\n", ok ? "PASS" : "FAIL", what, value);
  if (!ok) ++failures;
}

struct Problem {
  const char* family;
  Eigen::MatrixXd M;
  Eigen::VectorXd q;
};

using lcp_problems::gaussian;
using lcp_problems::gram;
using lcp_problems::q_from_solution;

std::vector<Problem> make_problems() {
  std::mt19937 rng(20130101);
  std::vector<Problem> problems;
  for (int n = 1; n <= 16; ++n) {
    const Eigen::MatrixXd spd = lcp_problems::spd(rng, n, 0.1);
    const Eigen::MatrixXd K = gaussian(rng, n, n);
    problems.push_back({"spd", spd, gaussian(rng, n, 1)});
    problems.push_back({"pd_nonsym", Eigen::MatrixXd(spd + K - K.transpose()), gaussian(rng, n, 1)});
    Eigen::MatrixXd murty;
    Eigen::VectorXd murty_q;
    lcp_problems::murty(n, murty, murty_q);
    problems.push_back({"murty", murty, murty_q});
    std::uniform_int_distribution<int> entry(-1, 1);
    Eigen::MatrixXd B(n, std::max(1, n / 2));
    for (int j = 0; j < B.cols(); ++j)
      for (int i = 0; i < n; ++i) B(i, j) = entry(rng);
    const Eigen::MatrixXd psd = gram(B);
    problems.push_back({"degenerate_psd", psd, q_from_solution(psd, rng)});
  }
  return problems;
}

void solver_checks(const std::vector<Problem>& problems) {
  const lcp::Method methods[] = {lcp::Method::lemke, lcp::Method::pgs, lcp::Method::newton_fb,
                                 lcp::Method::enumerate};
  lcp::Workspace workspace;  // default capacity 16
  Eigen::VectorXd z_storage(16), w_storage(16);
  for (const lcp::Method method : methods) {
    lcp::Options options;
    options.method = method;
    long allocations = 0, solves = 0, solved = 0, lemke_failures = 0;
    for (const Problem& p : problems) {
      const int n = static_cast<int>(p.q.size());
      if (method == lcp::Method::enumerate && n > lcp::kMaxEnumerateSize) continue;
      auto z = z_storage.head(n);
      auto w = w_storage.head(n);
      z.setZero();
      alloc_counter::start();
      lcp::solve_unchecked(p.M, p.q, z, w, options, workspace);
      const lcp::Result result = lcp::solve(p.M, p.q, z, w, options, workspace);
      allocations += alloc_counter::stop();
      ++solves;
      if (result.status == lcp::Status::solved) {
        ++solved;
        if (!(lcp::complementarity_residual(z, w) <= options.tol)) {
          std::printf("FAIL %s claimed solved with residual %g\n",
                      lcp::method_name(method).c_str(), result.residual);
          ++failures;
        }
      } else if (method == lcp::Method::lemke) {
        ++lemke_failures;
      }
    }
    std::printf("INFO %s: %ld solves, %ld solved\n", lcp::method_name(method).c_str(), solves,
                solved);
    const std::string label = "no allocation in " + lcp::method_name(method) + " solves, n <= 16";
    check(allocations == 0, label.c_str(), allocations);
    if (method == lcp::Method::lemke) check(lemke_failures == 0, "lemke solves every problem", lemke_failures);
  }

  // Warm starts (pgs, newton_fb) do not allocate either.
  lcp::Options warm;
  warm.warm_start = true;
  long allocations = 0;
  for (const lcp::Method method : {lcp::Method::pgs, lcp::Method::newton_fb}) {
    warm.method = method;
    const Problem& p = problems[4 * 15];  // spd, n = 16
    auto z = z_storage.head(16);
    auto w = w_storage.head(16);
    z.setConstant(0.5);
    alloc_counter::start();
    lcp::solve(p.M, p.q, z, w, warm, workspace);
    allocations += alloc_counter::stop();
  }
  check(allocations == 0, "no allocation in warm-started solves", allocations);
}

void positive_controls(const std::vector<Problem>& problems) {
  alloc_counter::start();
  std::vector<double> vector(100, 1.0);
  long count = alloc_counter::stop();
  check(count > 0 && vector[99] == 1.0, "counter sees std::vector", count);

  alloc_counter::start();
  Eigen::VectorXd eigen_vector = Eigen::VectorXd::Ones(100);
  count = alloc_counter::stop();
  check(count > 0 && eigen_vector[99] == 1.0, "counter sees Eigen's malloc", count);

  // A workspace too small for n = 12 grows once, then is allocation-free
  // (Lemke's n <= kMaxFixedLemkeSize runs on the stack and needs no growth).
  lcp::Workspace small(4);
  const Problem& p = problems[4 * 11];  // spd, n = 12
  Eigen::VectorXd z(12), w(12);
  lcp::Options options;
  alloc_counter::start();
  lcp::solve(p.M, p.q, z, w, options, small);
  count = alloc_counter::stop();
  check(count > 0 && small.capacity() == 12, "a workspace grows for n > capacity", count);
  alloc_counter::start();
  lcp::solve(p.M, p.q, z, w, options, small);
  count = alloc_counter::stop();
  check(count == 0, "and is allocation-free afterwards", count);
}

void friction_checks() {
  // Storage prepared outside the counted region, as an integrator would.
  constexpr int kContacts = 4;
  std::mt19937 rng(7);
  const Eigen::MatrixXd B = gaussian(rng, 2 * kContacts, 2 * kContacts);
  const Eigen::MatrixXd G = gram(B) / (2 * kContacts) +
                            0.05 * Eigen::MatrixXd::Identity(2 * kContacts, 2 * kContacts);
  const Eigen::VectorXd c = 3.0 * gaussian(rng, 2 * kContacts, 1);
  const Eigen::VectorXd mu = Eigen::VectorXd::Constant(kContacts, 0.3);
  const Eigen::VectorXd normal = Eigen::VectorXd::Constant(kContacts, 5.0);
  Eigen::MatrixXd A(3 * kContacts, 3 * kContacts);
  Eigen::VectorXd b(3 * kContacts), z(3 * kContacts), w(3 * kContacts);
  Eigen::VectorXd f1(kContacts), f2(kContacts), f3(kContacts), f4(kContacts);
  lcp::Workspace workspace;
  lcp::Options options;
  bool all_solved = true;

  alloc_counter::start();
  for (int n = 1; n <= kContacts; ++n) {
    // Known normal forces: the 2n friction LCP on the tangential block of G.
    auto Gt = G.bottomRightCorner(n, n);
    auto A2 = A.topLeftCorner(2 * n, 2 * n);
    friction::friction_lcp(Gt, c.tail(n), mu.head(n), normal.head(n), A2, b.head(2 * n));
    all_solved &= lcp::solve(A2, b.head(2 * n), z.head(2 * n), w.head(2 * n), options,
                             workspace).status == lcp::Status::solved;
    friction::friction_state(z.head(2 * n), w.head(2 * n), mu.head(n), normal.head(n),
                             f1.head(n), f2.head(n));
  }
  // Unknown normal forces: the 3n planar contact LCP.
  friction::contact_lcp(G, c, mu, A, b);
  all_solved &= lcp::solve(A, b, z, w, options, workspace).status == lcp::Status::solved;
  friction::contact_state(z, w, mu, f1, f2, f3, f4);
  // Fixed-size single-contact forms.
  const Eigen::Matrix2d G2 = G.topLeftCorner(2, 2);
  const Eigen::Vector2d c2 = c.head(2);
  const friction::PlanarContactLcp planar = friction::planar_contact_lcp(G2, c2, 0.3);
  Eigen::Vector3d z3, w3;
  all_solved &= lcp::solve(planar.A, planar.b, z3, w3, options, workspace).status ==
                lcp::Status::solved;
  const friction::ContactState contact = friction::planar_contact_state(z3, w3, 0.3);
  const friction::SingleFrictionLcp single = friction::single_friction_lcp(1.0, -4.0, 0.3, 10.0);
  Eigen::Vector2d z2, w2;
  all_solved &= lcp::solve(single.A, single.b, z2, w2, options, workspace).status ==
                lcp::Status::solved;
  const friction::TangentialState tangential =
      friction::single_friction_state(z2, w2, 0.3, 10.0);
  const long count = alloc_counter::stop();
  check(count == 0, "no allocation in the friction builders and their solves", count);
  check(all_solved, "every friction LCP solved by lemke");

  // The fixed-size forms agree with the general ones.
  Eigen::MatrixXd A1(3, 3);
  Eigen::VectorXd b1(3);
  friction::contact_lcp(G2, c2, Eigen::VectorXd::Constant(1, 0.3), A1, b1);
  check(planar.A == A1 && planar.b == b1, "planar_contact_lcp == contact_lcp for one contact");
  lcp::Result r = lcp::solve(A1, b1, z.head(3), w.head(3), options, workspace);
  check(r.status == lcp::Status::solved && z.head(3) == z3 && contact.normal_force == z3[0] &&
            contact.friction_force == z3[1] - 0.3 * z3[0],
        "planar_contact_state reads the same solution");
  // Block with F = 4 > mu m g = 3: slides forwards in u, g_T'' = -u'' = -(4 - 3)/1.
  check(std::abs(tangential.acceleration + 1.0) <= 1e-14 &&
            std::abs(tangential.friction_force - 3.0) <= 1e-14,
        "single_friction_lcp: the block slides with u'' = 1");
}

}  // namespace

int main() {
  const std::vector<Problem> problems = make_problems();
  positive_controls(problems);
  solver_checks(problems);
  friction_checks();
  std::printf("RESULT: %s\n", failures == 0 ? "PASS" : "FAIL");
  return failures == 0 ? 0 : 1;
}
