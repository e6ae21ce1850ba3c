// The Moreau-Jean step's iteration matrix and its solves (DriveMoreau,
// moreau.hpp). Internal to cpp/src/model.
#pragma once

#include <Eigen/Cholesky>
#include <cmath>

#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model::drive {

// sum_m a[m] b[m] (k >= 1) as Eigen's vectorized reduction (SSE2: two
// lanes) adds it for a vector's dot product or a row's sum: two lanes (two
// pairs of them from four terms on), the lanes' sum, the odd term last. The
// step's small vectors' dot products through it are Eigen's bit for bit
// (tests/cpp/test_moreau_iteration.cpp), without its runtime-sized
// reduction's dispatch; inlined with a constant k it unrolls.
// (Absolute: sum_m |a[m] b[m]|, as a.cwiseProduct(b).cwiseAbs().sum().)
template <bool Absolute = false>
[[gnu::always_inline]] inline double lane_sum(const double* a, const double* b, int k) {
  auto term = [&](int m) {
    const double product = a[m] * b[m];
    return Absolute ? std::abs(product) : product;
  };
  const int paired = (k / 2) * 2;
  if (paired == 0) return term(0);
  double lane0 = term(0), lane1 = term(1);
  if (paired > 2) {
    double next0 = term(2), next1 = term(3);
    const int quads = (k / 4) * 4;
    for (int m = 4; m < quads; m += 4) {
      lane0 += term(m), lane1 += term(m + 1);
      next0 += term(m + 2), next1 += term(m + 3);
    }
    lane0 += next0, lane1 += next1;
    if (paired > quads) lane0 += term(quads), lane1 += term(quads + 1);
  }
  double sum = lane0 + lane1;
  for (int m = paired; m < k; ++m) sum += term(m);
  return sum;
}
// lane_sum over n terms, its loops unrolled at each fixed n (1 to
// kMaxCoordinates: the drive's coordinate count).
template <bool Absolute = false>
inline double lane_sum_sized(const double* a, const double* b, int n) {
  switch (n) {
    case 1: return lane_sum<Absolute>(a, b, 1);
    case 2: return lane_sum<Absolute>(a, b, 2);
    case 3: return lane_sum<Absolute>(a, b, 3);
    case 4: return lane_sum<Absolute>(a, b, 4);
    case 5: return lane_sum<Absolute>(a, b, 5);
    case 6: return lane_sum<Absolute>(a, b, 6);
    default: return n > 0 ? lane_sum<Absolute>(a, b, n) : 0.0;
  }
}
// a . b of two vectors of the drive's coordinates (a.dot(b) bit for bit).
template <class A, class B>
double lane_dot(const A& a, const B& b) {
  return lane_sum_sized(a.data(), b.data(), static_cast<int>(a.size()));
}
// sum_i |a_i b_i| (a.cwiseProduct(b).cwiseAbs().sum() bit for bit).
template <class A, class B>
double lane_abs_dot(const A& a, const B& b) {
  return lane_sum_sized<true>(a.data(), b.data(), static_cast<int>(a.size()));
}
// g . ((1 - theta) v0 + theta v1), the rate along g at the theta point
// (g.dot((1.0 - theta) * v0 + theta * v1) bit for bit).
template <class G>
double theta_dot(const G& g, const CoordinateVector& v0, const CoordinateVector& v1,
                 double theta) {
  const int n = static_cast<int>(v0.size());
  double mid[kMaxCoordinates];
  for (int i = 0; i < n; ++i) mid[i] = (1.0 - theta) * v0[i] + theta * v1[i];
  return lane_sum_sized(g.data(), mid, n);
}

// W = W0 + s g g^T: W0 = M + theta h C + theta^2 h^2 K (with a DC motor's
// implicit back-EMF on the rotor), s g g^T a penalty flank's force at v+
// (s = h theta (h S' + c), g = grad e). W0 is factorized (Cholesky) only
// where it changed, entry for entry, from the one factorized last: while
// the step length, theta, the engaged penalty stops and the springs'
// stiffness along the nut hold, every step reuses it (the position-holding
// benchmark's flexible nut: 0.62 factorizations a step instead of 2.2, the
// screw's stiffness following the nut's position a in its last bits). The
// flank's rank-one term enters the solves by Sherman-Morrison on W0's
// factors, W^-1 x = y - (s g.y / (1 + s g.z)) z with y = W0^-1 x,
// z = W0^-1 g (W0 symmetric positive definite and s >= 0: the denominator
// is >= 1); without it a solve is W0's, bit for bit as before. W0^-1 g and
// W0^-1 W_T (the thread's tangent, the friction impulse's direction, solved
// twice a step) are kept with the factors. The factorization and the solves
// run on fixed-size kernels (1 to kMaxCoordinates coordinates, chosen by
// W0's size) in Eigen's order of operations.
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
    if (!factorized_ || !same_base(base)) {
      base_ = base;
      factor_ = base_;
      factorize(factor_);
      llt_current_ = false;
      z_ = g_;
      solve_in_place(z_);
      tangent_ = t_;
      solve_in_place(tangent_);
      gz_ = lane_dot(g_, z_);
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
    if (s_ != 0.0) subtract_scaled(tangent_w_, scale_ * lane_dot(g_, tangent_), z_);
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
    if (s_ != 0.0) {
      if constexpr (Matrix::ColsAtCompileTime == 1) {
        // (Eigen folds the scalar into the row: (scale g)^T y, then y -= z that.)
        const int n = static_cast<int>(y.size());
        double scaled[kMaxCoordinates];
        for (int i = 0; i < n; ++i) scaled[i] = scale_ * g_[i];
        subtract_scaled(y, lane_sum_sized(scaled, y.data(), n), z_);
      } else {
        y.noalias() -= z_ * (scale_ * (g_.transpose() * y));
      }
    }
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
  // (no such W0: masses > 0, K and C positive semidefinite). On N x N
  // (column-major, fixed size: the loops unrolled; a 4-coordinate drive's
  // runtime-sized loops took 2.5 times the instructions).
  template <int N>
  static void factorize_fixed(double* a) {
    for (int k = 0; k < N; ++k) {
      double x = a[k + k * N];
      if (k > 0) {
        double squares = a[k] * a[k];
        for (int j = 1; j < k; ++j) squares += a[k + j * N] * a[k + j * N];
        x -= squares;
      }
      if (x <= 0.0) return;
      x = std::sqrt(x);
      a[k + k * N] = x;
      for (int i = k + 1; i < N; ++i) {
        if (k > 0) {
          double products = 0.0;
          for (int j = 0; j < k; ++j) products += a[i + j * N] * a[k + j * N];
          a[i + k * N] -= products;
        }
      }
      for (int i = k + 1; i < N; ++i) a[i + k * N] /= x;
    }
  }
  // W0^-1 x on its factors L L^T, in Eigen's own order of operations for a
  // vector (LLT::solve: the forward solve by columns, the backward one by
  // rows, each row's sum in SSE2's pairs of lanes), so bit for bit what
  // llt_.solve(x) gave (tests/cpp/test_moreau_iteration.cpp), without its
  // generic blocked kernels: a quarter of a 4-coordinate drive's step went
  // to them (the position-holding benchmark, 3.4 solves a step). Fixed N.
  template <int N>
  static void solve_fixed(const double* l, double* x) {
    for (int i = 0; i < N; ++i) {
      if (x[i] == 0.0) continue;
      x[i] /= l[i + i * N];
      const double xi = x[i];
      for (int j = i + 1; j < N; ++j) x[j] -= xi * l[j + i * N];
    }
    for (int i = N - 1; i >= 0; --i) {
      const int k = N - 1 - i;
      if (k > 0) x[i] -= lane_sum(&l[(i + 1) + i * N], &x[i + 1], k);
      if (x[i] != 0.0) x[i] /= l[i + i * N];
    }
  }
  // The fixed-size kernels for W0's size (1 to kMaxCoordinates).
  static void factorize(Square& a) {
    switch (a.rows()) {
      case 1: return factorize_fixed<1>(a.data());
      case 2: return factorize_fixed<2>(a.data());
      case 3: return factorize_fixed<3>(a.data());
      case 4: return factorize_fixed<4>(a.data());
      case 5: return factorize_fixed<5>(a.data());
      default: return factorize_fixed<6>(a.data());
    }
  }
  void solve_in_place(CoordinateVector& x) const {
    const double* l = factor_.data();
    switch (x.size()) {
      case 1: return solve_fixed<1>(l, x.data());
      case 2: return solve_fixed<2>(l, x.data());
      case 3: return solve_fixed<3>(l, x.data());
      case 4: return solve_fixed<4>(l, x.data());
      case 5: return solve_fixed<5>(l, x.data());
      default: return solve_fixed<6>(l, x.data());
    }
  }
  // W0 entry for entry equal to the one factorized (== on every entry, as
  // Eigen's operator==).
  bool same_base(const Square& base) const {
    if (base.rows() != base_.rows()) return false;
    const Eigen::Index size = base.size();
    for (Eigen::Index k = 0; k < size; ++k)
      if (base.data()[k] != base_.data()[k]) return false;
    return true;
  }
  // y -= c z, entry by entry (as Eigen's y -= c * z).
  static void subtract_scaled(CoordinateVector& y, double c, const CoordinateVector& z) {
    const Eigen::Index n = y.size();
    for (Eigen::Index i = 0; i < n; ++i) y[i] -= c * z[i];
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
