#include "leadscrew/lcp/lemke.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

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
  return std::abs(a - b) <= kTieRelTol * std::max(1.0, std::max(std::abs(a), std::abs(b)));
}

// The first index of the smallest of v[0], ..., v[n - 1], that value and the
// second smallest (+inf for n = 1). nearly_equal grows with the distance
// (|x - a| rises at rate 1, its bound at rate kTieRelTol), so when the
// second smallest is not nearly equal to the smallest, no other value is.
struct Smallest {
  int index;
  double value, second;
};

template <int N>
Smallest smallest_two(const double* v, int n) {
  Smallest s{0, v[0], std::numeric_limits<double>::infinity()};
  for (int i = 1; i < detail::size_of<N>(n); ++i) {
    s.second = std::min(s.second, std::max(v[i], s.value));
    if (v[i] < s.value) s.index = i, s.value = v[i];
  }
  return s;
}

bool tied(const Smallest& s) {
  return s.second < std::numeric_limits<double>::infinity() && nearly_equal(s.second, s.value);
}

// Memory of the condensed tableau and its bookkeeping. N > 0: a problem of
// exactly N unknowns in Eigen matrices of fixed size (on the stack: the
// compiler unrolls and vectorizes every loop, no workspace traffic); N = 0:
// any size, mapped onto the Workspace. Besides the tableau: the pending
// pivots ("etas", see Tableau::bring_current), at most max_etas of them.
template <int N>
struct TableauMemory {
  static constexpr int kEtas = N + 2;
  Eigen::Matrix<double, N, N + 2> t;
  Eigen::Matrix<double, N, 1> ratio, value, residual;
  Eigen::Matrix<double, N, kEtas> eta_factor;
  double eta_inverse[kEtas];
  int eta_row[kEtas], version[N + 2];
  int basic[N], nonbasic[N + 1], location[2 * N + 1];
  TableauMemory(Workspace& /*unused*/, int /*n*/) {}
  static constexpr int max_etas() { return kEtas; }
};

template <>
struct TableauMemory<0> {
  using Matrix = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
  using Vector = Eigen::Map<Eigen::VectorXd>;
  Matrix t;
  Vector ratio, value, residual;
  Matrix eta_factor;
  double* eta_inverse;
  int *eta_row, *version;
  int *basic, *nonbasic, *location;
  int max_etas_;
  TableauMemory(Workspace& ws, int n)
      : t(ws.tableau.data(), n, n + 2, Eigen::OuterStride<>(ws.tableau.outerStride())),
        ratio(ws.vectors.col(3).data(), n),
        value(ws.vectors.col(1).data(), n),
        residual(ws.vectors.col(2).data(), n),
        eta_factor(ws.square.data(), n, n, Eigen::OuterStride<>(ws.square.outerStride())),
        eta_inverse(ws.vectors.col(4).data()),
        eta_row(ws.indices.data() + 4 * n + 2),
        version(ws.indices.data() + 5 * n + 2),
        basic(ws.indices.data()),
        nonbasic(ws.indices.data() + n),
        location(ws.indices.data() + 2 * n + 1),
        max_etas_(n) {}
  int max_etas() const { return max_etas_; }
};

// The condensed tableau: the basic variables x_B (one per row) satisfy
//     x_B = rhs - sum_k T(:, k) x_N[k]
// over the n + 1 nonbasic variables x_N (one per column). Its columns are
// those of the full tableau B^-1 [I, -M, -d | q] that belong to nonbasic
// variables; a basic variable's full column is a unit vector and is not
// stored, which halves the work per pivot.
//
// Variables: w_j = j, z_j = n + j, z0 = 2n. location[v] >= 0 is the row of a
// basic v, location[v] < 0 encodes the column -location[v] - 1 of a nonbasic v.
//
// The columns are updated lazily: a pivot stores its eta (row r, 1 / pivot,
// the pivot column with row r zeroed) and rewrites only its own column; a
// column receives the etas it has missed, in order, when it is read
// (bring_current): the entering column and the rhs at each ratio test, the
// columns of B^-1 for a lexicographic tie-break or a refinement. The
// arithmetic per column is that of an eager update at every pivot, so the
// numbers are the same to the bit, but a column that never enters is never
// updated (the last pivot, which ends the method, updates only the rhs).
// When max_etas are pending, every column is brought up to date and the
// etas are dropped (bounded memory on Murty's 2^n pivots).
// One implementation for every size; N as in TableauMemory.
template <int N>
class Tableau {
 public:
  Tableau(Workspace& ws, int n) : n_(n), m_(ws, n) {}

  int n() const { return detail::size_of<N>(n_); }
  int artificial() const { return 2 * n(); }
  double at(int i, int k) const { return m_.t(i, k); }
  const double* column(int k) const { return m_.t.col(k).data(); }
  double rhs(int i) const { return at(i, n() + 1); }  // after bring_current(n() + 1)
  int column_of(int v) const { return -m_.location[v] - 1; }
  double* value() { return m_.value.data(); }
  double* residual() { return m_.residual.data(); }

  // The tableau after Lemke's first pivot, written out: [I, -M, -d | q] with
  // the w's basic, then z0 entering in row r (where the column -d = -1 has
  // pivot -1). That pivot maps row r to (M_r., w_r: -1 | -q_r) and every other
  // row i to (M_r. - M_i., w_r: -1 | q_i - q_r): the same numbers the general
  // pivot computes (-M_ij - (-M_rj) = M_rj - M_ij exactly), one pass cheaper.
  void start(const Eigen::Ref<const Eigen::MatrixXd>& M,
             const Eigen::Ref<const Eigen::VectorXd>& q, int r) {
    const int n = this->n();
    const auto m = detail::fixed_map<N>(M);
    auto& t = m_.t;
    for (int j = 0; j < n; ++j) {
      const double m_rj = m(r, j);
      t.col(j).array() = m_rj - m.col(j).array();
      t(r, j) = m_rj;
      m_.nonbasic[j] = n + j;
      m_.location[n + j] = -(j + 1);
    }
    const double q_r = q[r];
    t.col(n).setConstant(-1.0);
    t.col(n + 1).array() = detail::fixed_map<N>(q).array() - q_r;
    t(r, n + 1) = -q_r;
    for (int i = 0; i < n; ++i) {
      m_.basic[i] = i;
      m_.location[i] = i;
    }
    m_.basic[r] = artificial();
    m_.location[artificial()] = r;
    m_.nonbasic[n] = r;
    m_.location[r] = -(n + 1);
    for (int c = 0; c < n + 2; ++c) m_.version[c] = 0;
    etas_ = 0;
  }

  // Apply to column c the etas it has not received, in order: row r is
  // divided by the pivot, every other row i loses factor_i times it (the
  // factor's row r is 0, so row r is set afterwards).
  //
  // Row r is selected in the same pass rather than stored after it: a store
  // of one entry behind the vector stores of the column would keep the next
  // vector load of the column (the next eta, the ratio test) from being
  // forwarded the stored data, and stall it until the stores retire.
  void bring_current(int c) {
    double* column = m_.t.col(c).data();
    for (int e = m_.version[c]; e < etas_; ++e) {
      const int r = m_.eta_row[e];
      const double trc = column[r] * m_.eta_inverse[e];
      const double* factor = m_.eta_factor.col(e).data();
      if constexpr (N > 0) {
        for (int i = 0; i < N; ++i) column[i] = i == r ? trc : column[i] - factor[i] * trc;
      } else {  // the same numbers; Eigen's loop is the faster one at runtime sizes
        auto column_map = m_.t.col(c);
        column_map -= m_.eta_factor.col(e) * trc;
        column[r] = trc;
      }
    }
    m_.version[c] = etas_;
  }

  // The columns of B^-1 (those of the nonbasic w_j) up to date.
  void bring_inverse_current() {
    for (int j = 0; j < n(); ++j)
      if (m_.location[j] < 0) bring_current(-m_.location[j] - 1);
  }

  // Entry (i, j) of B^-1: the full tableau's column of w_j.
  double inverse_basis(int i, int j) const {
    const int where = m_.location[j];
    return where >= 0 ? (where == i ? 1.0 : 0.0) : at(i, -where - 1);
  }

  // Exchange the basic variable of row r with the nonbasic one of column k
  // (current: the ratio test brought it up to date); returns the variable
  // that left the basis. Stores the eta and writes column k anew for the
  // leaving variable: -T(i, k) / pivot, and 1 / pivot in row r.
  int pivot(int r, int k) {
    if (etas_ == m_.max_etas()) {  // full: every column up to date, drop the etas
      for (int c = 0; c < n() + 2; ++c) bring_current(c);
      for (int c = 0; c < n() + 2; ++c) m_.version[c] = 0;
      etas_ = 0;
    }
    auto& t = m_.t;
    auto factor = m_.eta_factor.col(etas_);
    const double inverse_pivot = 1.0 / t(r, k);
    if constexpr (N > 0) {  // row r selected in the pass, as in bring_current
      for (int i = 0; i < N; ++i) {
        const double factor_i = i == r ? 0.0 : t(i, k);
        factor[i] = factor_i;
        t(i, k) = i == r ? inverse_pivot : -inverse_pivot * factor_i;
      }
    } else {
      factor = t.col(k);
      factor[r] = 0.0;
      t.col(k) = -inverse_pivot * factor;
      t(r, k) = inverse_pivot;
    }
    m_.eta_inverse[etas_] = inverse_pivot;
    m_.eta_row[etas_] = r;
    ++etas_;
    m_.version[k] = etas_;
    const int entering = m_.nonbasic[k], leaving = m_.basic[r];
    m_.basic[r] = entering;
    m_.location[entering] = r;
    m_.nonbasic[k] = leaving;
    m_.location[leaving] = -(k + 1);
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
    for (int j = 0; j < n(); ++j) {
      const double a = inverse_basis(i, j) / ci, b = inverse_basis(k, j) / ck;
      if (!nearly_equal(a, b)) return a < b;
    }
    return false;
  }

  // Leaving row for the entering column c, or -1 if the column has no
  // positive entry (a secondary ray). z0 leaves when it is among the rows
  // tied at the minimum ratio (that ends the method with a solution).
  int ratio_test(int c) {
    const int n = this->n();
    bring_current(c);
    bring_current(n + 1);
    const auto t_column = m_.t.col(c).array();
    const auto rhs_column = m_.t.col(n + 1).array();
    const double pivot_floor = kPivotRelTol * t_column.abs().maxCoeff();
    // All ratios at once (independent divisions, no branch; +inf for the rows
    // that cannot pivot), then the smallest and the second smallest.
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    Smallest smallest;
    if constexpr (N > 0) {
      // A local array indexed by constants only stays in registers (the
      // search would otherwise store every ratio and load it back).
      const Eigen::Array<double, N, 1> ratio =
          (t_column > pivot_floor).select(rhs_column / t_column, kInfinity);
      smallest = smallest_two<N>(ratio.data(), N);
      if (!(smallest.value < kInfinity)) return -1;
      if (!tied(smallest)) return smallest.index;  // the usual case
      m_.ratio = ratio.matrix();
    } else {
      auto ratio = m_.ratio.array();
      ratio = (t_column > pivot_floor).select(rhs_column / t_column, kInfinity);
      smallest = smallest_two<N>(ratio.data(), n);
      if (!(smallest.value < kInfinity)) return -1;
      if (!tied(smallest)) return smallest.index;  // the usual case
    }
    return tie_break(c, smallest.value);
  }

  // The leaving row among the rows whose ratio (in m_.ratio) is tied with
  // best_ratio: the artificial variable's, else the lexicographic minimum.
  int tie_break(int c, double best_ratio) {
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    const int n = this->n();
    const auto ratio = m_.ratio.array();
    bring_inverse_current();
    int artificial_row = -1;
    for (int i = 0; i < n; ++i)
      if (ratio[i] < kInfinity && nearly_equal(ratio[i], best_ratio) &&
          m_.basic[i] == artificial())
        artificial_row = i;
    if (artificial_row >= 0) return artificial_row;
    int lexico_best = -1;
    for (int i = 0; i < n; ++i) {
      if (!(ratio[i] < kInfinity) || !nearly_equal(ratio[i], best_ratio)) continue;
      if (lexico_best < 0 || lexicographically_smaller(i, lexico_best, c)) lexico_best = i;
    }
    return lexico_best;
  }

  // The same z as extract(value) for a fixed size, gathered into registers:
  // z_j from the row of a basic z_j (location >= 0), else 0.
  detail::FixedVector<N> extracted(const double* value) const {
    static_assert(N > 0, "fixed sizes only");
    detail::FixedVector<N> z;
    for (int j = 0; j < N; ++j) {
      const int row = m_.location[N + j];
      z[j] = row >= 0 ? std::max(value[row], 0.0) : 0.0;
    }
    return z;
  }

  // z from the basic values `value` (one per row); a NaN stays NaN (std::max
  // returns its first argument), so that the verification sees it.
  void extract(const double* value, detail::VectorRef& z) const {
    const int n = this->n();
    double* zd = z.data();
    for (int i = 0; i < n; ++i) zd[i] = 0.0;
    for (int i = 0; i < n; ++i) {
      const int v = m_.basic[i];
      if (v >= n && v < artificial()) zd[v - n] = std::max(value[i], 0.0);
    }
  }

  // One step of iterative refinement of the basic values against the
  // original data: residual = q - B x_B with B's columns e_j (w_j), -M_.j
  // (z_j), -d (z0); then x_B += B^-1 residual. Needs bring_inverse_current().
  void refine(const Eigen::Ref<const Eigen::MatrixXd>& M,
              const Eigen::Ref<const Eigen::VectorXd>& q, double* value,
              double* residual) const {
    const int n = this->n();
    for (int i = 0; i < n; ++i) residual[i] = q[i];
    for (int i = 0; i < n; ++i) {
      const int v = m_.basic[i];
      if (v < n) {
        residual[v] -= value[i];
      } else if (v < artificial()) {
        for (int k = 0; k < n; ++k) residual[k] += M(k, v - n) * value[i];
      } else {
        for (int k = 0; k < n; ++k) residual[k] += value[i];
      }
    }
    for (int j = 0; j < n; ++j) {
      const double rj = residual[j];
      if (rj == 0.0) continue;
      const int where = m_.location[j];
      if (where >= 0) {
        value[where] += rj;
      } else {
        const double* column = this->column(-where - 1);
        for (int i = 0; i < n; ++i) value[i] += column[i] * rj;
      }
    }
  }

 private:
  int n_;
  int etas_ = 0;  // pending etas
  TableauMemory<N> m_;
};

// Lemke's pivoting on the tableau from the covering vector's start to a
// complementary basis (z0 leaves: solved), a ray, or max_pivots; pivots
// counts them, the start's one included.
template <int N>
Status lemke_pivots(Tableau<N>& tableau, const detail::MatrixCRef& M,
                    const detail::VectorCRef& q, int n, int max_pivots, int& pivots) {
  const int artificial = tableau.artificial();
  // z0 enters at the lexicographic minimum of (q_i, e_i) / d_i, which makes
  // every row of [rhs, B^-1] lexicographically positive (ties in q: the
  // largest index, whose unit row e_i is the smallest).
  // Without a tie at the minimum that rule ends on the (unique) minimum.
  const Smallest smallest = smallest_two<N>(q.data(), n);
  int r = smallest.index;
  if (tied(smallest)) {
    r = 0;
    for (int i = 1; i < n; ++i)
      if (q[i] < q[r] || nearly_equal(q[i], q[r])) r = i;
  }
  tableau.start(M, q, r);
  int leaving = r;  // w_r
  pivots = 1;
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
  return status;
}

// z of the basis Lemke ended on, verified against the original data;
// refined and, failing that, polished where a complementary basis's
// rounded values miss tol.
template <int N>
Result verified_lemke_solution(Tableau<N>& tableau, const detail::MatrixCRef& M,
                               const detail::VectorCRef& q, detail::VectorRef& z,
                               detail::VectorRef& w, const Options& options,
                               Workspace& workspace, int n, Status status, int pivots) {
  double* value = tableau.value();
  tableau.bring_current(n + 1);
  Result result;
  if constexpr (N > 0) {
    // Straight from the tableau's rhs into registers and on to the
    // verification (no copy of the rhs, no store and reload of z).
    result = detail::verify_values<N>(M, q, tableau.extracted(tableau.column(n + 1)), z.data(),
                                      w.data(), status, pivots, options.tol);
  } else {
    for (int i = 0; i < n; ++i) value[i] = tableau.rhs(i);
    tableau.extract(value, z);
    result = detail::verify<N>(M, q, z, w, status, pivots, options.tol);
  }
  // A complementary basis whose rounded values miss tol: refine them twice
  // against the original data and verify again.
  if (status == Status::solved && result.status != Status::solved) {
    if constexpr (N > 0)
      for (int i = 0; i < n; ++i) value[i] = tableau.rhs(i);
    tableau.bring_inverse_current();
    for (int sweep = 0; sweep < 2; ++sweep) tableau.refine(M, q, value, tableau.residual());
    tableau.extract(value, z);
    result = detail::verify<N>(M, q, z, w, status, pivots, options.tol);
  }
  // Still off by round-off: near a degenerate point (a friction reserve at
  // zero, a stick-slip boundary) the lexicographic rule can end on the
  // neighbouring basis, infeasible by ~1e-14. Solve the basis the answer
  // points to (z_i > w_i) exactly and keep it if it verifies.
  if (status == Status::solved && result.status != Status::solved) {
    workspace.reserve(n);
    auto z_trial = workspace.vectors.col(7).head(n);
    auto w_trial = workspace.vectors.col(4).head(n);
    if (detail::polish(M, q, z.data(), w.data(), n, workspace, z_trial, w_trial) &&
        complementarity_residual(z_trial, w_trial) <= options.tol) {
      z = z_trial;
      result = detail::verify<N>(M, q, z, w, Status::solved, pivots, options.tol);
    }
  }
  return result;
}

// Lemke's method on the tableau of TableauMemory<N>, then the verification.
template <int N>
Result run_lemke(const detail::MatrixCRef& M, const detail::VectorCRef& q, detail::VectorRef& z,
                 detail::VectorRef& w, const Options& options, Workspace& workspace) {
  const int n = detail::size_of<N>(static_cast<int>(q.size()));
  // Pre-check, part of the method: with q >= 0 the covering vector's first
  // ratio test would bring z0 in at level max(-q) <= 0, i.e. z = 0 is the
  // answer before any pivot (Siconos' lcp_lexicolemke checks the same). A NaN
  // fails the comparison and goes to the pivoting, whose verification
  // rejects it.
  bool q_nonnegative = true;
  for (int i = 0; i < n; ++i) q_nonnegative &= q[i] >= 0.0;
  if (q_nonnegative) {
    if constexpr (N > 0) {
      return detail::verify_values<N>(M, q, detail::FixedVector<N>::Zero(), z.data(), w.data(),
                                      Status::solved, 0, options.tol);
    } else {
      for (int i = 0; i < n; ++i) z[i] = 0.0;
      return detail::verify<N>(M, q, z, w, Status::solved, 0, options.tol);
    }
  }
  const int max_pivots =
      options.max_iter > 0 ? options.max_iter : detail::default_lemke_pivots(n);

  if constexpr (N == 0) workspace.reserve(n);
  Tableau<N> tableau(workspace, n);
  int pivots = 0;
  const Status status = lemke_pivots<N>(tableau, M, q, n, max_pivots, pivots);
  return verified_lemke_solution<N>(tableau, M, q, z, w, options, workspace, n, status, pivots);
}

}  // namespace

namespace detail {

Result lemke(const MatrixCRef& M, const VectorCRef& q, VectorRef& z, VectorRef& w,
             const Options& options, Workspace& workspace) {
  // One dispatch on n: the fixed-size code paths for n <= kMaxFixedLemkeSize.
  switch (q.size()) {
    case 1: return run_lemke<1>(M, q, z, w, options, workspace);
    case 2: return run_lemke<2>(M, q, z, w, options, workspace);
    case 3: return run_lemke<3>(M, q, z, w, options, workspace);
    case 4: return run_lemke<4>(M, q, z, w, options, workspace);
    case 5: return run_lemke<5>(M, q, z, w, options, workspace);
    case 6: return run_lemke<6>(M, q, z, w, options, workspace);
    case 7: return run_lemke<7>(M, q, z, w, options, workspace);
    case 8: return run_lemke<8>(M, q, z, w, options, workspace);
    default: return run_lemke<0>(M, q, z, w, options, workspace);
  }
  static_assert(kMaxFixedLemkeSize == 8, "the cases above cover 1..kMaxFixedLemkeSize");
}

}  // namespace detail

Result solve_lemke(const Eigen::Ref<const Eigen::MatrixXd>& M,
                   const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
                   Eigen::Ref<Eigen::VectorXd> w, const Options& options,
                   Workspace& workspace) {
  detail::validate(M, q, z, w, options, Method::lemke);
  return detail::lemke(M, q, z, w, options, workspace);
}

Result solve_lemke_unchecked(const Eigen::Ref<const Eigen::MatrixXd>& M,
                             const Eigen::Ref<const Eigen::VectorXd>& q,
                             Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::VectorXd> w,
                             const Options& options, Workspace& workspace) {
  detail::validate_shapes(M, q, z, w, options);
  return detail::lemke(M, q, z, w, options, workspace);
}

Result solve_lemke_generic(const Eigen::Ref<const Eigen::MatrixXd>& M,
                           const Eigen::Ref<const Eigen::VectorXd>& q,
                           Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::VectorXd> w,
                           const Options& options, Workspace& workspace) {
  detail::validate_shapes(M, q, z, w, options);
  return run_lemke<0>(M, q, z, w, options, workspace);
}

}  // namespace leadscrew::lcp
