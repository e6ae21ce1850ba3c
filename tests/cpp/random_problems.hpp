// Seeded random matrices for the native LCP test and the LCP benchmark
// (benchmarks/lcp adds this directory to its include path). Plain loops
// instead of Eigen's matrix products keep the files that use them quick to
// compile.
#pragma once

#include <Eigen/Core>
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

}  // namespace lcp_problems
