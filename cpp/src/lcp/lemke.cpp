#include "leadscrew/lcp/lemke.hpp"

#include <algorithm>
#include <cmath>

#include "detail.hpp"
#include "leadscrew/lcp/workspace.hpp"

namespace leadscrew::lcp {

namespace {

// Entries of the entering column below kPivotRelTol * max|column| are not
// pivoted on; ratios within kTieRelTol (relative) count as tied. Tied ratios
// carry the cancellation errors of earlier pivots (1 - 213/214 after two), so
// the tolerance must be well above round-off; a near-tie that the
// lexicographic rule then resolves the wrong way leaves a basis infeasible by
// ~1e-13, which the final polish corrects.
constexpr double kPivotRelTol = 1e-11;
constexpr double kTieRelTol = 1e-11;

// The floor of 1 makes ratios at zero (degenerate q) tie with their round-off
// neighbours, which the lexicographic rule needs; a near-tie it resolves the
// wrong way is caught by the final polish.
bool nearly_equal(double a, double b) {
  return std::abs(a - b) <= kTieRelTol * std::max({1.0, std::abs(a), std::abs(b)});
}

// The condensed tableau: the basic variables x_B (one per row) satisfy
//     x_B = rhs - sum_k T(:, k) x_N[k]
// over the n + 1 nonbasic variables x_N (one per column). Its columns are
// those of the full tableau B^-1 [I, -M, -d | q] that belong to nonbasic
// variables; a basic variable's full column is a unit vector and is not
// stored, which halves the work per pivot.
//
// Variables: w_j = j, z_j = n + j, z0 = 2n. location[v] >= 0 is the row of a
// basic v, location[v] < 0 encodes the column -location[v] - 1 of a nonbasic v.
class Tableau {
 public:
  Tableau(Workspace& ws, int n)
      : n_(n),
        ld_(static_cast<int>(ws.tableau.outerStride())),
        t_(ws.tableau.data()),
        basic_(ws.indices.data()),
        nonbasic_(ws.indices.data() + n),
        location_(ws.indices.data() + 2 * n + 1),
        factor_(ws.vectors.col(0).data()),
        ratio_(ws.vectors.col(3).data()) {}

  int n() const { return n_; }
  int artificial() const { return 2 * n_; }
  double& at(int i, int k) { return t_[i + static_cast<std::ptrdiff_t>(ld_) * k]; }
  double at(int i, int k) const { return t_[i + static_cast<std::ptrdiff_t>(ld_) * k]; }
  const double* column(int k) const { return t_ + static_cast<std::ptrdiff_t>(ld_) * k; }
  double rhs(int i) const { return at(i, n_ + 1); }
  int basic(int i) const { return basic_[i]; }
  int column_of(int v) const { return -location_[v] - 1; }

  // [I, -M, -d | q] with the w's basic: columns z_0..z_{n-1}, z0, rhs.
  void start(const Eigen::Ref<const Eigen::MatrixXd>& M,
             const Eigen::Ref<const Eigen::VectorXd>& q) {
    for (int j = 0; j < n_; ++j) {
      const double* m = M.data() + static_cast<std::ptrdiff_t>(M.outerStride()) * j;
      double* column = &at(0, j);
      for (int i = 0; i < n_; ++i) column[i] = -m[i];
      nonbasic_[j] = n_ + j;
      location_[n_ + j] = -(j + 1);
    }
    for (int i = 0; i < n_; ++i) {
      at(i, n_) = -1.0;
      at(i, n_ + 1) = q[i];
      basic_[i] = i;
      location_[i] = i;
    }
    nonbasic_[n_] = artificial();
    location_[artificial()] = -(n_ + 1);
  }

  // Entry (i, j) of B^-1: the full tableau's column of w_j.
  double inverse_basis(int i, int j) const {
    const int where = location_[j];
    return where >= 0 ? (where == i ? 1.0 : 0.0) : at(i, -where - 1);
  }

  // Exchange the basic variable of row r with the nonbasic one of column k;
  // returns the variable that left the basis.
  int pivot(int r, int k) {
    const double inverse_pivot = 1.0 / at(r, k);
    for (int i = 0; i < n_; ++i) factor_[i] = at(i, k);
    for (int j = 0; j < n_ + 2; ++j) {
      if (j == k) continue;
      const double trj = at(r, j) * inverse_pivot;
      if (trj != 0.0) {
        double* __restrict column = &at(0, j);
        const double* __restrict factor = factor_;
        for (int i = 0; i < n_; ++i) column[i] -= factor[i] * trj;  // row r too: set next
      }
      at(r, j) = trj;
    }
    double* column = &at(0, k);
    for (int i = 0; i < n_; ++i) column[i] = -factor_[i] * inverse_pivot;
    column[r] = inverse_pivot;
    const int entering = nonbasic_[k], leaving = basic_[r];
    basic_[r] = entering;
    location_[entering] = r;
    nonbasic_[k] = leaving;
    location_[leaving] = -(k + 1);
    return leaving;
  }

  // Lexicographic comparison of rows i and k for the entering column c:
  // (rhs_i, B^-1_i.) / T(i, c)  <  (rhs_k, B^-1_k.) / T(k, c) ?
  // The rows of [rhs, B^-1] are linearly independent, so exact ties cannot
  // persist to the last component; numerically tied rows keep the incumbent.
  bool lexicographically_smaller(int i, int k, int c) const {
    const double ci = at(i, c), ck = at(k, c);
    const double ri = rhs(i) / ci, rk = rhs(k) / ck;
    if (!nearly_equal(ri, rk)) return ri < rk;
    for (int j = 0; j < n_; ++j) {
      const double a = inverse_basis(i, j) / ci, b = inverse_basis(k, j) / ck;
      if (!nearly_equal(a, b)) return a < b;
    }
    return false;
  }

  // Leaving row for the entering column c, or -1 if the column has no
  // positive entry (a secondary ray). z0 leaves when it is among the rows
  // tied at the minimum ratio (that ends the method with a solution).
  int ratio_test(int c) {
    double column_max = 0.0;
    for (int i = 0; i < n_; ++i) column_max = std::max(column_max, std::abs(at(i, c)));
    const double pivot_floor = kPivotRelTol * column_max;
    // Minimum ratio first (one division per candidate, ratios kept); the
    // lexicographic comparison only among the rows tied with it.
    int best = -1;
    double best_ratio = 0.0;
    for (int i = 0; i < n_; ++i) {
      if (!(at(i, c) > pivot_floor)) continue;
      ratio_[i] = rhs(i) / at(i, c);
      if (best < 0 || ratio_[i] < best_ratio) best = i, best_ratio = ratio_[i];
    }
    if (best < 0) return -1;
    int ties = 0, artificial_row = -1;
    for (int i = 0; i < n_; ++i) {
      if (!(at(i, c) > pivot_floor) || !nearly_equal(ratio_[i], best_ratio)) continue;
      ++ties;
      if (basic_[i] == artificial()) artificial_row = i;
    }
    if (artificial_row >= 0) return artificial_row;
    if (ties == 1) return best;
    int lexico_best = -1;
    for (int i = 0; i < n_; ++i) {
      if (!(at(i, c) > pivot_floor) || !nearly_equal(ratio_[i], best_ratio)) continue;
      if (lexico_best < 0 || lexicographically_smaller(i, lexico_best, c)) lexico_best = i;
    }
    return lexico_best;
  }

  // z from the basic values `value` (one per row).
  void extract(const double* value, Eigen::Ref<Eigen::VectorXd> z) const {
    z.setZero();
    for (int i = 0; i < n_; ++i)
      if (basic_[i] >= n_ && basic_[i] < artificial()) z[basic_[i] - n_] = std::max(value[i], 0.0);
  }

  // One step of iterative refinement of the basic values against the
  // original data: residual = q - B x_B with B's columns e_j (w_j), -M_.j
  // (z_j), -d (z0); then x_B += B^-1 residual.
  void refine(const Eigen::Ref<const Eigen::MatrixXd>& M,
              const Eigen::Ref<const Eigen::VectorXd>& q, double* value,
              double* residual) const {
    for (int i = 0; i < n_; ++i) residual[i] = q[i];
    for (int i = 0; i < n_; ++i) {
      const int v = basic_[i];
      if (v < n_) {
        residual[v] -= value[i];
      } else if (v < artificial()) {
        for (int k = 0; k < n_; ++k) residual[k] += M(k, v - n_) * value[i];
      } else {
        for (int k = 0; k < n_; ++k) residual[k] += value[i];
      }
    }
    for (int j = 0; j < n_; ++j) {
      const double rj = residual[j];
      if (rj == 0.0) continue;
      const int where = location_[j];
      if (where >= 0) {
        value[where] += rj;
      } else {
        const double* column = this->column(-where - 1);
        for (int i = 0; i < n_; ++i) value[i] += column[i] * rj;
      }
    }
  }

 private:
  int n_, ld_;
  double* t_;
  int* basic_;
  int* nonbasic_;
  int* location_;
  double* factor_;
  double* ratio_;
};

}  // namespace

Result solve_lemke(const Eigen::Ref<const Eigen::MatrixXd>& M,
                   const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
                   Eigen::Ref<Eigen::VectorXd> w, const Options& options,
                   Workspace& workspace) {
  const int n = detail::validate(M, q, z, w, options, Method::lemke);
  workspace.reserve(n);
  if (n == 0 || q.minCoeff() >= 0.0) {  // z = 0 solves it
    z.setZero();
    return detail::finish(M, q, z, w, Status::solved, 0, options.tol);
  }
  const int max_pivots =
      options.max_iter > 0 ? options.max_iter : default_max_iterations(Method::lemke, n);

  Tableau tableau(workspace, n);
  tableau.start(M, q);
  const int artificial = tableau.artificial();

  // z0 enters at the lexicographic minimum of (q_i, e_i) / d_i, which makes
  // every row of [rhs, B^-1] lexicographically positive (ties in q: the
  // largest index, whose unit row e_i is the smallest).
  int r = 0;
  for (int i = 1; i < n; ++i)
    if (q[i] < q[r] || nearly_equal(q[i], q[r])) r = i;
  int leaving = tableau.pivot(r, tableau.column_of(artificial));
  int pivots = 1;
  Status status = Status::max_iterations;
  while (true) {
    if (leaving == artificial) {
      status = Status::solved;
      break;
    }
    if (pivots >= max_pivots) break;
    const int entering = leaving < n ? leaving + n : leaving - n;  // the complement
    const int column = tableau.column_of(entering);
    r = tableau.ratio_test(column);
    if (r < 0) {
      status = Status::ray_termination;
      break;
    }
    leaving = tableau.pivot(r, column);
    ++pivots;
  }

  double* value = workspace.vectors.col(1).data();
  double* residual = workspace.vectors.col(2).data();
  for (int i = 0; i < n; ++i) value[i] = tableau.rhs(i);
  tableau.extract(value, z);
  Result result = detail::finish(M, q, z, w, status, pivots, options.tol);
  // A complementary basis whose rounded values miss tol: refine them twice
  // against the original data and verify again.
  if (status == Status::solved && result.status != Status::solved) {
    for (int sweep = 0; sweep < 2; ++sweep) tableau.refine(M, q, value, residual);
    tableau.extract(value, z);
    result = detail::finish(M, q, z, w, status, pivots, options.tol);
  }
  // Still off by round-off: near a degenerate point (a friction reserve at
  // zero, a stick-slip boundary) the lexicographic rule can end on the
  // neighbouring basis, infeasible by ~1e-14. Solve the basis the answer
  // points to (z_i > w_i) exactly and keep it if it verifies.
  if (status == Status::solved && result.status != Status::solved) {
    auto z_trial = workspace.vectors.col(7).head(n);
    auto w_trial = workspace.vectors.col(4).head(n);
    if (detail::polish(M, q, z.data(), w.data(), n, workspace, z_trial, w_trial) &&
        complementarity_residual(z_trial, w_trial) <= options.tol) {
      z = z_trial;
      result = detail::finish(M, q, z, w, Status::solved, pivots, options.tol);
    }
  }
  return result;
}

}  // namespace leadscrew::lcp
