// Moreau-Jean's iteration matrix (cpp/src/model/drive/moreau_iteration.hpp):
// W = W0 + s g g^T solved on W0's kept factors by Sherman-Morrison, on
// random symmetric positive definite W0 of 1 to 6 coordinates, s up to 1e4
// times W0's norm (the flank dominating W): the residual of W y = x within
// 1e-12 of |W| |y| + |x| (the Cholesky factorization of W itself reaches
// about 1e-15; the worst case here 1.5e-13); with s = 0 the solves are
// W0's bit for bit, with s > 0 bit for bit the Eigen expressions the
// fixed-size kernels replaced (LLT's solves, y -= z (scale g^T y)); W0 is
// factorized again only where it changed. The step's dot products
// (lane_dot, lane_abs_dot, theta_dot) are Eigen's bit for bit. Prints
// `PASS <label> (<count>)` per check, or `FAIL <label>: ...` and exits 1.
#include <Eigen/Cholesky>
#include <cmath>
#include <cstdio>
#include <random>

#include "moreau_iteration.hpp"

using leadscrew::model::CoordinateVector;
using leadscrew::model::drive::IterationMatrix;
using leadscrew::model::drive::lane_abs_dot;
using leadscrew::model::drive::lane_dot;
using leadscrew::model::drive::theta_dot;
using Square = IterationMatrix::Square;

namespace {

int failures = 0;

void report(const char* label, int count, bool passed, double worst) {
  if (passed) {
    std::printf("PASS %s (%d)\n", label, count);
  } else {
    std::printf("FAIL %s: worst %.3e\n", label, worst);
    ++failures;
  }
}

}  // namespace

int main() {
  std::mt19937_64 random(20261207);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  int cases = 0;
  double worst_rank_one = 0.0, worst_plain = 0.0;
  bool kept = true, refactorized = true, eigen_order = true;
  for (int trial = 0; trial < 600; ++trial) {
    const int n = 1 + trial % 6;
    Square a(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) a(i, j) = uniform(random);
    // Masses of 1e-3 to 1 and a stiffness term: SPD, condition up to ~1e6.
    Square w0 = a * a.transpose() * std::pow(10.0, 3.0 * uniform(random));
    for (int i = 0; i < n; ++i) w0(i, i) += std::pow(10.0, 1.5 * uniform(random) - 1.5);
    Eigen::VectorXd g(n), t(n);
    for (int i = 0; i < n; ++i) g[i] = uniform(random), t[i] = uniform(random);
    const double s = trial % 4 == 0 ? 0.0 : std::pow(10.0, 4.0 * uniform(random)) * w0.norm();
    IterationMatrix iteration;
    iteration.directions(g, t);
    iteration.set(w0, s);
    const Square w = w0 + s * (g * g.transpose());
    const Eigen::LLT<Square> direct(w);
    CoordinateVector x(n);
    for (int i = 0; i < n; ++i) x[i] = uniform(random);
    if (trial % 3 == 0) x[trial % n] = 0.0;  // (a zero entry: the solves skip its division)
    const CoordinateVector ours = iteration.solve(x), theirs = direct.solve(x);
    const CoordinateVector tangent = iteration.tangent_solve();
    const CoordinateVector tangent_direct = direct.solve(CoordinateVector(t));
    // (The residual of W y = x relative to |W| |y| + |x|: backward stable.)
    const double residual =
        std::max((w * ours - x).norm() / (w.norm() * ours.norm() + x.norm()),
                 (w * tangent - t).norm() / (w.norm() * tangent.norm() + t.norm()));
    if (s == 0.0) {
      const bool same = ours == theirs && tangent == tangent_direct;
      worst_plain = std::max(worst_plain, same ? 0.0 : (ours - theirs).norm());
    } else {
      worst_rank_one = std::max(worst_rank_one, residual);
      // (the expressions before the fixed-size kernels, on Eigen's LLT of W0)
      const Eigen::LLT<Square> base(w0);
      const CoordinateVector z = base.solve(CoordinateVector(g));
      const double scale = s / (1.0 + s * CoordinateVector(g).dot(z));
      CoordinateVector y = base.solve(x), tangent_w = base.solve(CoordinateVector(t));
      const CoordinateVector gc = g;
      y.noalias() -= z * (scale * (gc.transpose() * y));
      tangent_w -= (scale * gc.dot(tangent_w)) * z;
      eigen_order = eigen_order && y == ours && tangent_w == tangent;
    }
    // The same W0 again: no factorization; another s: none either.
    iteration.set(w0, 0.5 * s);
    iteration.set_rank_one(s);
    kept = kept && iteration.factorizations() == 1 && iteration.solve(x) == ours;
    Square changed = w0;
    changed(0, 0) *= 1.0 + 1e-15;  // (one ulp's change is a change)
    iteration.set(changed, s);
    refactorized = refactorized && iteration.factorizations() == 2;
    ++cases;
  }
  // The dot products against Eigen's, n = 1 to 6, entries of mixed scales.
  int dots = 0;
  bool dots_same = true;
  for (int trial = 0; trial < 6000; ++trial) {
    const int n = 1 + trial % 6;
    Eigen::VectorXd g(n);
    CoordinateVector v0(n), v1(n);
    for (int i = 0; i < n; ++i)
      g[i] = uniform(random), v0[i] = std::pow(10.0, 6.0 * uniform(random)) * uniform(random),
      v1[i] = uniform(random);
    const double theta = trial % 2 == 0 ? 0.5 : 0.5 + 0.5 * std::abs(uniform(random));
    dots_same = dots_same && lane_dot(g, v0) == g.dot(v0) &&
                lane_abs_dot(g, v1) == g.cwiseProduct(v1).cwiseAbs().sum() &&
                theta_dot(g, v0, v1, theta) == g.dot((1.0 - theta) * v0 + theta * v1);
    ++dots;
  }
  report("rank-one solves: residual of W y = x below 1e-12", cases,
         worst_rank_one < 1e-12, worst_rank_one);
  report("without the rank-one term: W0's solves bit for bit", cases, worst_plain == 0.0,
         worst_plain);
  report("rank-one solves: Eigen's expressions bit for bit", cases, eigen_order, 0.0);
  report("the step's dot products: Eigen's bit for bit", dots, dots_same, 0.0);
  report("the same W0: its factors kept", cases, kept, 0.0);
  report("W0 changed by an ulp: factorized again", cases, refactorized, 0.0);
  std::printf(failures == 0 ? "OK\n" : "FAILED\n");
  return failures == 0 ? 0 : 1;
}
