// Seeded random matrices for the native LCP test and the LCP benchmark
// (benchmarks/lcp adds this directory to its include path). Plain loops
// instead of Eigen's matrix products keep the files that use them quick to
// compile.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <random>

namespace lcp_problems {

// rows x cols standard normal entries.
inline Eigen::MatrixXd gaussian(std::mt19937& rng, int rows, int cols) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd m(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) m(i, j) = normal(rng);
  return m;
}

// A A^T
inline Eigen::MatrixXd gram(const Eigen::MatrixXd& A) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(A.rows(), A.rows());
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    for (Eigen::Index j = 0; j < A.rows(); ++j)
      for (Eigen::Index k = 0; k < A.cols(); ++k) G(i, j) += A(i, k) * A(j, k);
  return G;
}

// A A^T / n + shift I with A n x n standard normal: symmetric positive definite.
inline Eigen::MatrixXd spd(std::mt19937& rng, int n, double shift) {
  return gram(gaussian(rng, n, n)) / n + shift * Eigen::MatrixXd::Identity(n, n);
}

// M z by columns (plain loops, see above).
inline Eigen::VectorXd times(const Eigen::MatrixXd& M, const Eigen::VectorXd& z) {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(M.rows());
  for (Eigen::Index j = 0; j < M.cols(); ++j) y += z[j] * M.col(j);
  return y;
}

// q = w* - M z* for a complementary pair with random support, some indices
// degenerate (z*_i = w*_i = 0): feasible, with ties for Lemke.
inline Eigen::VectorXd q_from_solution(const Eigen::MatrixXd& M, std::mt19937& rng) {
  const int n = static_cast<int>(M.rows());
  std::uniform_int_distribution<int> pick(0, 2), value(1, 3);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n), w = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    const int kind = pick(rng);
    if (kind == 0) z[i] = value(rng);
    if (kind == 1) w[i] = value(rng);
  }
  return w - times(M, z);
}

// Murty's problem of size n (Murty 1978): M upper triangular with unit
// diagonal and 2 above it, q_i = -(2^(n+1) - 2^(i+1)); Lemke needs 2^n pivots.
inline void murty(int n, Eigen::MatrixXd& M, Eigen::VectorXd& q) {
  M = Eigen::MatrixXd::Identity(n, n);
  q.resize(n);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) M(i, j) = 2.0;
    q[i] = -(std::ldexp(1.0, n + 1) - std::ldexp(1.0, i + 1));
  }
}

}  // namespace lcp_problems
