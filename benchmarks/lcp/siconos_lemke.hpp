// Siconos numerics' lexicographic Lemke (lcp_lexicolemke) behind a small
// interface, so that bench_lcp.cpp needs no Siconos header.
#pragma once

#include <Eigen/Core>
#include <memory>

class SiconosLemke {
 public:
  // Copies M (column-major, as Siconos stores dense matrices) and q.
  SiconosLemke(const Eigen::MatrixXd& M, const Eigen::VectorXd& q);
  ~SiconosLemke();
  SiconosLemke(const SiconosLemke&) = delete;
  SiconosLemke& operator=(const SiconosLemke&) = delete;

  // One call of lcp_lexicolemke; returns its info (0: converged).
  int solve(Eigen::VectorXd& z, Eigen::VectorXd& w);
  int pivots() const;  // iterations of the last solve

 private:
  struct Data;
  std::unique_ptr<Data> data_;
};
