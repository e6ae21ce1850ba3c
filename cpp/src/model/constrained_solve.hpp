// DriveDynamics's constrained solve (drive_dynamics.cpp, drive_dynamics_solve.cpp):
// the accelerations and multipliers of M x = f + B lambda, C x = r with at most
// kMaxConstraints rows, in fixed-capacity matrices (no allocation on the
// right-hand side's path). Inline: each file's callers keep it in line.
#pragma once

#include <cmath>

#include <Eigen/Dense>

#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model::detail {

using ConstraintMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxConstraints, kMaxCoordinates>;
using ColumnMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCoordinates, kMaxConstraints>;
using SmallMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxConstraints, kMaxConstraints>;
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxConstraints, 1>;

// Solves M x = f + B lambda, C x = r for x and lambda (M diagonal, given as
// its inverse). Returns false if C M^-1 B is singular.
inline bool solve_constrained(const CoordinateVector& inverse_mass, const CoordinateVector& f,
                       const ColumnMatrix& B, const ConstraintMatrix& C, const SmallVector& r,
                       CoordinateVector& x, SmallVector& lambda) {
  const int nc = static_cast<int>(r.size());
  const int n = static_cast<int>(f.size());
  if (nc == 0) {
    x = inverse_mass.cwiseProduct(f);
    lambda.resize(0);
    return true;
  }
  if (nc == n && r.isZero(0.0)) {
    // The constraints lock every coordinate (the rigid drive in stick): the
    // motion is exactly zero, and the multipliers balance the forces,
    // B lambda = -f. Solving the Schur complement instead would leave
    // round-off accelerations that let a stuck drive creep.
    Eigen::FullPivLU<SmallMatrix> lu(B);
    if (!lu.isInvertible()) return false;
    lambda = lu.solve(SmallVector(-f));
    x.setZero(n);
    return lambda.allFinite();
  }
  ColumnMatrix weighted = inverse_mass.asDiagonal() * B;
  if (nc == 1) {  // one constraint: the Schur complement is a number
    const double schur = C.row(0).dot(weighted.col(0));
    if (schur == 0.0) return false;
    lambda.resize(1);
    lambda[0] = (r[0] - C.row(0).dot(inverse_mass.cwiseProduct(f))) / schur;
    x = inverse_mass.cwiseProduct(f) + weighted.col(0) * lambda[0];
    return std::isfinite(lambda[0]) && x.allFinite();
  }
  SmallMatrix schur = C * weighted;
  SmallVector rhs = r - C * inverse_mass.cwiseProduct(f);
  if (nc == 2) {  // Cramer's rule, with the same singularity test as the LU
    const double det = schur(0, 0) * schur(1, 1) - schur(0, 1) * schur(1, 0);
    const double scale = schur.cwiseAbs().maxCoeff();
    if (!(std::abs(det) > 1e-14 * scale * scale)) return false;
    lambda.resize(2);
    lambda[0] = (rhs[0] * schur(1, 1) - schur(0, 1) * rhs[1]) / det;
    lambda[1] = (schur(0, 0) * rhs[1] - schur(1, 0) * rhs[0]) / det;
  } else {
    Eigen::FullPivLU<SmallMatrix> lu(schur);
    if (!lu.isInvertible()) return false;
    lambda = lu.solve(rhs);
  }
  x = inverse_mass.cwiseProduct(f) + weighted * lambda;
  return x.allFinite() && lambda.allFinite();
}

}  // namespace leadscrew::model::detail
