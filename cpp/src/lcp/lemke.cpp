#include "leadscrew/lcp/lemke.hpp"

#include <algorithm>
#include <cmath>

#include "detail.hpp"
#include "leadscrew/lcp/workspace.hpp"

namespace leadscrew::lcp {

namespace {

// Variables are numbered w_0..w_{n-1} = 0..n-1, z_0..z_{n-1} = n..2n-1,
// z0 (the artificial variable) = 2n; the tableau's column of variable v is v
// and its last column (2n + 1) the right-hand side.
// Entries of the entering column below kPivotRelTol * max|column| are not
// pivoted on; ratios within kTieRelTol (relative) count as tied.
constexpr double kPivotRelTol = 1e-11;
constexpr double kTieRelTol = 1e-11;

using Tableau = Eigen::Block<Eigen::MatrixXd>;

bool nearly_equal(double a, double b) {
  return std::abs(a - b) <= kTieRelTol * std::max({1.0, std::abs(a), std::abs(b)});
}

// Lexicographic comparison of row i against row k for the entering column
// `col`: (rhs_i, B^-1_i.) / col_i  <  (rhs_k, B^-1_k.) / col_k ?
// The rows of [rhs, B^-1] are linearly independent, so exact ties cannot
// persist to the last component; numerically tied rows keep the incumbent.
bool lexicographically_smaller(const Tableau& T, int i, int k, int col, int n) {
  const int rhs = 2 * n + 1;
  const double ci = T(i, col), ck = T(k, col);
  const double ri = T(i, rhs) / ci, rk = T(k, rhs) / ck;
  if (!nearly_equal(ri, rk)) return ri < rk;
  for (int j = 0; j < n; ++j) {
    const double a = T(i, j) / ci, b = T(k, j) / ck;
    if (!nearly_equal(a, b)) return a < b;
  }
  return false;
}

// Leaving row for the entering column `col`, or -1 if the column has no
// positive entry (a secondary ray). z0 leaves when it is among the rows tied
// at the minimum ratio.
int ratio_test(const Tableau& T, const int* basic, int col, int n) {
  const int rhs = 2 * n + 1;
  const int artificial = 2 * n;
  double column_max = 0.0;
  for (int i = 0; i < n; ++i) column_max = std::max(column_max, std::abs(T(i, col)));
  const double pivot_floor = kPivotRelTol * column_max;
  int best = -1;
  int artificial_row = -1;
  for (int i = 0; i < n; ++i) {
    if (!(T(i, col) > pivot_floor)) continue;
    if (basic[i] == artificial) artificial_row = i;
    if (best < 0 || lexicographically_smaller(T, i, best, col, n)) best = i;
  }
  if (best >= 0 && artificial_row >= 0 && artificial_row != best &&
      nearly_equal(T(artificial_row, rhs) / T(artificial_row, col),
                   T(best, rhs) / T(best, col)))
    best = artificial_row;
  return best;
}

// Gauss-Jordan pivot on T(r, e); `factor` is scratch of size n.
void pivot(Tableau& T, int r, int e, int n, double* factor) {
  const int columns = 2 * n + 2;
  const double inverse_pivot = 1.0 / T(r, e);
  for (int i = 0; i < n; ++i) factor[i] = T(i, e);
  for (int j = 0; j < columns; ++j) {
    const double trj = T(r, j) * inverse_pivot;
    T(r, j) = trj;
    if (trj == 0.0) continue;
    double* column = &T(0, j);
    for (int i = 0; i < n; ++i)
      if (i != r) column[i] -= factor[i] * trj;
  }
  for (int i = 0; i < n; ++i) T(i, e) = 0.0;
  T(r, e) = 1.0;
}

}  // namespace

Result solve_lemke(const Eigen::Ref<const Eigen::MatrixXd>& M,
                   const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
                   Eigen::Ref<Eigen::VectorXd> w, const Options& options,
                   Workspace& workspace) {
  const int n = detail::validate(M, q, z, w, options, Method::lemke);
  workspace.reserve(n);
  z.setZero();
  if (n == 0 || q.minCoeff() >= 0.0)  // z = 0 solves it
    return detail::finish(M, q, z, w, Status::solved, 0, options.tol);

  const int max_pivots =
      options.max_iter > 0 ? options.max_iter : default_max_iterations(Method::lemke, n);
  const int artificial = 2 * n, rhs = 2 * n + 1;
  Tableau T = workspace.tableau.topLeftCorner(n, 2 * n + 2);
  int* basic = workspace.basis.data();
  double* factor = workspace.vectors.col(0).data();

  // T = [I, -M, -d, q] with d = (1, ..., 1); the w's are basic.
  T.setZero();
  for (int i = 0; i < n; ++i) {
    T(i, i) = 1.0;
    for (int j = 0; j < n; ++j) T(i, n + j) = -M(i, j);
    T(i, artificial) = -1.0;
    T(i, rhs) = q[i];
    basic[i] = i;
  }

  // z0 enters at the lexicographic minimum of (q_i, e_i) / d_i, which makes
  // every row of [rhs, B^-1] lexicographically positive (ties in q: the
  // largest index, whose unit row e_i is the smallest).
  int r = 0;
  for (int i = 1; i < n; ++i)
    if (q[i] < q[r] || nearly_equal(q[i], q[r])) r = i;
  int pivots = 0;
  Status status = Status::max_iterations;
  int leaving = basic[r];
  pivot(T, r, artificial, n, factor);
  basic[r] = artificial;
  ++pivots;
  while (true) {
    if (leaving == artificial) {
      status = Status::solved;
      break;
    }
    if (pivots >= max_pivots) break;
    const int entering = leaving < n ? leaving + n : leaving - n;  // the complement
    r = ratio_test(T, basic, entering, n);
    if (r < 0) {
      status = Status::ray_termination;
      break;
    }
    leaving = basic[r];
    pivot(T, r, entering, n, factor);
    basic[r] = entering;
    ++pivots;
  }

  // Basic values; for a solution refine them twice against the original data:
  // residual = q - B x_B with B's columns e_j (w_j), -M_.j (z_j), -d (z0), and
  // x_B += B^-1 residual, B^-1 being the tableau's first n columns.
  double* value = workspace.vectors.col(1).data();
  double* residual = workspace.vectors.col(2).data();
  for (int i = 0; i < n; ++i) value[i] = T(i, rhs);
  for (int sweep = 0; status == Status::solved && sweep < 2; ++sweep) {
    for (int i = 0; i < n; ++i) residual[i] = q[i];
    for (int i = 0; i < n; ++i) {
      const int v = basic[i];
      if (v < n) {
        residual[v] -= value[i];
      } else if (v < artificial) {
        for (int k = 0; k < n; ++k) residual[k] += M(k, v - n) * value[i];
      } else {
        for (int k = 0; k < n; ++k) residual[k] += value[i];
      }
    }
    for (int j = 0; j < n; ++j) {
      const double rj = residual[j];
      if (rj == 0.0) continue;
      for (int i = 0; i < n; ++i) value[i] += T(i, j) * rj;
    }
  }
  for (int i = 0; i < n; ++i)
    if (basic[i] >= n && basic[i] < artificial) z[basic[i] - n] = std::max(value[i], 0.0);
  return detail::finish(M, q, z, w, status, pivots, options.tol);
}

}  // namespace leadscrew::lcp
