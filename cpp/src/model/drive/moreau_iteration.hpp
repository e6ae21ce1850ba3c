// The Moreau-Jean step's iteration matrix and its solves (DriveMoreau,
// moreau.hpp). Internal to cpp/src/model.
#pragma once

#include <Eigen/Cholesky>

#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model::drive {

// W = W0 + s g g^T: W0 = M + theta h C + theta^2 h^2 K (with a DC motor's
// implicit back-EMF on the rotor), s g g^T a penalty flank's force at v+
// (s = h theta (h S' + c), g = grad e). W0 is factorized (Cholesky) only
// where it changed, entry for entry, from the one factorized last: while
// the step length, theta, the engaged penalty stops and the springs'
// stiffness along the nut hold, every step reuses it (the position-holding
// benchmark's flexible nut: one factorization for the run instead of 2.2 a
// step). The flank's rank-one term enters the solves by Sherman-Morrison
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
      llt_.compute(base_);
      z_ = llt_.solve(g_);
      tangent_ = llt_.solve(t_);
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
  }

  // W^-1 x for a vector or the columns of a matrix.
  template <class Matrix>
  Matrix solve(const Matrix& x) const {
    Matrix y = llt_.solve(x);
    if (s_ != 0.0) y.noalias() -= z_ * (scale_ * (g_.transpose() * y));
    return y;
  }
  // W^-1 W_T.
  CoordinateVector tangent_solve() const {
    if (s_ == 0.0) return tangent_;
    return tangent_ - (scale_ * g_.dot(tangent_)) * z_;
  }
  long factorizations() const { return factorizations_; }

 private:
  Eigen::LLT<Square> llt_;
  Square base_;
  CoordinateVector g_, t_, z_, tangent_;
  double gz_ = 0.0, s_ = 0.0, scale_ = 0.0;
  bool factorized_ = false;
  long factorizations_ = 0;
};

}  // namespace leadscrew::model::drive
