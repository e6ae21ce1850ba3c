// The Moreau-Jean step's iteration matrix and its solves (DriveMoreau,
// moreau.hpp). Internal to cpp/src/model.
#pragma once

#include <Eigen/Cholesky>
#include <cmath>

#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model::drive {

// W = W0 + s g g^T: W0 = M + theta h C + theta^2 h^2 K (with a DC motor's
// implicit back-EMF on the rotor), s g g^T a penalty flank's force at v+
// (s = h theta (h S' + c), g = grad e). W0 is factorized (Cholesky) only
// where it changed, entry for entry, from the one factorized last: while
// the step length, theta, the engaged penalty stops and the springs'
// stiffness along the nut hold, every step reuses it (the position-holding
// benchmark's flexible nut: 0.62 factorizations a step instead of 2.2, the
// screw's stiffness following the nut's position a in its last bits). The flank's rank-one term enters the solves by Sherman-Morrison
// on W0's factors, W^-1 x = y - (s g.y / (1 + s g.z)) z with y = W0^-1 x,
// z = W0^-1 g (W0 symmetric positive definite and s >= 0: the denominator
// is >= 1); without it a solve is W0's, bit for bit as before. W0^-1 g and
// W0^-1 W_T (the thread's tangent, the friction impulse's direction, solved
// twice a step) are kept with the factors.
class IterationMatrix {
 public:
  using Square =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCoordinates, kMaxCoordinates>;

  // The fixed directions: the play's gradient g and the thread's tangent W_T.
  void directions(const Eigen::VectorXd& play_gradient, const Eigen::VectorXd& tangent) {
    g_ = play_gradient;
    t_ = tangent;
    factorized_ = false;
  }

  // W0, factorized where it differs from the last one; the rank-one term's
  // coefficient s (0: none).
  void set(const Square& base, double rank_one) {
    if (!factorized_ || base.rows() != base_.rows() || base != base_) {
      base_ = base;
      factor_ = base_;
      factorize(factor_);
      llt_current_ = false;
      z_ = g_;
      solve_in_place(z_);
      tangent_ = t_;
      solve_in_place(tangent_);
      gz_ = g_.dot(z_);
      factorized_ = true;
      ++factorizations_;
    }
    set_rank_one(rank_one);
  }
  // The rank-one term's coefficient alone (W0 kept).
  void set_rank_one(double rank_one) {
    s_ = rank_one;
    scale_ = s_ != 0.0 ? s_ / (1.0 + s_ * gz_) : 0.0;
    tangent_w_ = tangent_;
    if (s_ != 0.0) tangent_w_ -= (scale_ * g_.dot(tangent_)) * z_;
  }

  // W^-1 x for a vector or the columns of a matrix.
  template <class Matrix>
  Matrix solve(const Matrix& x) const {
    Matrix y;
    if constexpr (Matrix::ColsAtCompileTime == 1) {
      y = x;
      solve_in_place(y);
    } else {  // (Eigen's own factors: its blocked solve of columns has another order)
      if (!llt_current_) llt_.compute(base_), llt_current_ = true;
      y = llt_.solve(x);
    }
    if (s_ != 0.0) y.noalias() -= z_ * (scale_ * (g_.transpose() * y));
    return y;
  }
  // W^-1 W_T (kept with the rank-one term: solved up to three times a pass).
  const CoordinateVector& tangent_solve() const { return tangent_w_; }
  long factorizations() const { return factorizations_; }

 private:
  // W0 = L L^T in place (its lower triangle), in Eigen's order of operations
  // (LLT's unblocked Cholesky below 32 rows: each column's pivot less its
  // row's squares summed in turn, the column below less the rows' products
  // summed in turn from 0), so bit for bit LLT's factor, without its
  // L1 norm and dispatch. Stops where a pivot is not positive, as LLT does
  // (no such W0: masses > 0, K and C positive semidefinite).
  static void factorize(Square& a) {
    const int n = static_cast<int>(a.rows());
    for (int k = 0; k < n; ++k) {
      double x = a(k, k);
      if (k > 0) {
        double squares = a(k, 0) * a(k, 0);
        for (int j = 1; j < k; ++j) squares += a(k, j) * a(k, j);
        x -= squares;
      }
      if (x <= 0.0) return;
      x = std::sqrt(x);
      a(k, k) = x;
      for (int i = k + 1; i < n; ++i) {
        if (k > 0) {
          double products = 0.0;
          for (int j = 0; j < k; ++j) products += a(i, j) * a(k, j);
          a(i, k) -= products;
        }
      }
      for (int i = k + 1; i < n; ++i) a(i, k) /= x;
    }
  }
  // W0^-1 x on its factors L L^T, in Eigen's own order of operations for a
  // vector (LLT::solve: the forward solve by columns, the backward one by
  // rows, each row's sum in SSE2's pairs of lanes), so bit for bit what
  // llt_.solve(x) gave (tests/cpp/test_moreau_iteration.cpp), without its
  // generic blocked kernels: a quarter of a 4-coordinate drive's step went
  // to them (the position-holding benchmark, 3.4 solves a step).
  void solve_in_place(CoordinateVector& x) const {
    const Square& l = factor_;
    const int n = static_cast<int>(x.size());
    for (int i = 0; i < n; ++i) {
      if (x[i] == 0.0) continue;
      x[i] /= l(i, i);
      const double xi = x[i];
      for (int j = i + 1; j < n; ++j) x[j] -= xi * l(j, i);
    }
    for (int i = n - 1; i >= 0; --i) {
      const int k = n - 1 - i;
      if (k > 0) x[i] -= row_sum(&l.coeffRef(i + 1, i), &x.coeffRef(i + 1), k);
      if (x[i] != 0.0) x[i] /= l(i, i);
    }
  }
  // sum_m a[m] b[m] (k >= 1) as Eigen's vectorized reduction adds it: two
  // lanes (two pairs of them from four terms on), the lanes' sum, the odd
  // term last.
  static double row_sum(const double* a, const double* b, int k) {
    const int paired = (k / 2) * 2;
    if (paired == 0) return a[0] * b[0];
    double lane0 = a[0] * b[0], lane1 = a[1] * b[1];
    if (paired > 2) {
      double next0 = a[2] * b[2], next1 = a[3] * b[3];
      const int quads = (k / 4) * 4;
      for (int m = 4; m < quads; m += 4) {
        lane0 += a[m] * b[m], lane1 += a[m + 1] * b[m + 1];
        next0 += a[m + 2] * b[m + 2], next1 += a[m + 3] * b[m + 3];
      }
      lane0 += next0, lane1 += next1;
      if (paired > quads) lane0 += a[quads] * b[quads], lane1 += a[quads + 1] * b[quads + 1];
    }
    double sum = lane0 + lane1;
    for (int m = paired; m < k; ++m) sum += a[m] * b[m];
    return sum;
  }

  // Eigen's LLT of W0, computed where a solve of columns asks for it
  // (the constraint rows: exact play, exact stops, a speed-controlled rotor).
  mutable Eigen::LLT<Square> llt_;
  mutable bool llt_current_ = false;
  Square base_, factor_;
  CoordinateVector g_, t_, z_, tangent_, tangent_w_;
  double gz_ = 0.0, s_ = 0.0, scale_ = 0.0;
  bool factorized_ = false;
  long factorizations_ = 0;
};

}  // namespace leadscrew::model::drive
