// Internals shared by the LCP methods (not installed, not public API).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "leadscrew/lcp/lcp.hpp"
#include "leadscrew/lcp/workspace.hpp"

namespace leadscrew::lcp::detail {

using MatrixCRef = Eigen::Ref<const Eigen::MatrixXd>;
using VectorCRef = Eigen::Ref<const Eigen::VectorXd>;
// The outputs z, w travel through the internal calls by reference (a Ref
// copied by value at every call costs more than a small solve's arithmetic).
using VectorRef = Eigen::Ref<Eigen::VectorXd>;

// Throws InvalidArgument naming the first argument or option out of range
// (out of line: builds the message; the check itself is validate_shapes).
[[noreturn]] void fail_shapes(const Eigen::Ref<const Eigen::MatrixXd>& M,
                              const Eigen::Ref<const Eigen::VectorXd>& q,
                              const Eigen::Ref<Eigen::VectorXd>& z,
                              const Eigen::Ref<Eigen::VectorXd>& w, const Options& options);

// Checks shapes and options: a few integer and scalar compares, kept by the
// unchecked entry points so that a wrong size never reads out of bounds.
// Returns n. Throws InvalidArgument naming the argument.
inline int validate_shapes(const Eigen::Ref<const Eigen::MatrixXd>& M,
                           const Eigen::Ref<const Eigen::VectorXd>& q,
                           const Eigen::Ref<Eigen::VectorXd>& z,
                           const Eigen::Ref<Eigen::VectorXd>& w, const Options& options) {
  const Eigen::Index n = M.rows();
  // One combined test (& rather than &&: no branch per condition); NaN
  // options fail their comparisons.
  const bool valid = (M.cols() == n) & (q.size() == n) & (z.size() == n) & (w.size() == n) &
                     (n <= (Eigen::Index{1} << 29)) & (options.tol > 0.0) &
                     (options.tol <= std::numeric_limits<double>::max()) &
                     (options.max_iter >= 0) & (options.relaxation > 0.0) &
                     (options.relaxation < 2.0);
  if (!valid) fail_shapes(M, q, z, w, options);
  return static_cast<int>(n);
}

// Checks that M, q (and a warm start z of pgs, newton_fb) hold no NaN or inf:
// the O(n^2) part of the validation, done only at the API boundary.
void validate_finite(const Eigen::Ref<const Eigen::MatrixXd>& M,
                     const Eigen::Ref<const Eigen::VectorXd>& q,
                     const Eigen::Ref<Eigen::VectorXd>& z, const Options& options, Method method);

// Both: the checked entry points. Returns n.
int validate(const Eigen::Ref<const Eigen::MatrixXd>& M,
             const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<Eigen::VectorXd>& z,
             const Eigen::Ref<Eigen::VectorXd>& w, const Options& options, Method method);

// w = M z + q, skipping zero entries of z (the methods' inner iterations).
void multiply_add(const Eigen::Ref<const Eigen::MatrixXd>& M,
                  const Eigen::Ref<const Eigen::VectorXd>& z,
                  const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> w);

// Lemke's pivot budget for max_iter = 0 (default_max_iterations), inline for
// the small solves: 1000 + 2^(min(n, 20) + 1) (Murty's problems need 2^n).
constexpr int default_lemke_pivots(int n) {
  return 1000 + (1 << (std::min(std::max(n, 0), 20) + 1));
}

// Loop bound of the size-generic (N = 0) and fixed-size (N > 0) code paths:
// a compile-time constant for N > 0, so that the loops unroll.
template <int N>
constexpr int size_of(int n) {
  return N > 0 ? N : n;
}

// complementarity_residual on raw arrays, for n = size_of<N>(n) entries;
// +infinity if any z_i or w_i is NaN or inf (std::max and std::min would drop
// a NaN; a non-finite pair is no solution).
template <int N>
inline double residual_of(const double* z, const double* w, int n) {
  constexpr double kLargest = std::numeric_limits<double>::max();
  double worst_pair = 0.0, min_z = 0.0, min_w = 0.0;
  bool finite = true;
  for (int i = 0; i < size_of<N>(n); ++i) {
    worst_pair = std::max(worst_pair, std::abs(std::min(z[i], w[i])));
    min_z = std::min(min_z, z[i]);
    min_w = std::min(min_w, w[i]);
    finite &= (std::abs(z[i]) <= kLargest) & (std::abs(w[i]) <= kLargest);
  }
  return finite ? worst_pair - min_z - min_w : std::numeric_limits<double>::infinity();
}

// M, q, z as Eigen maps of compile-time size N (N > 0; the loops over them
// unroll and vectorize) or of runtime size (N = 0).
template <int N>
constexpr int kEigenSize = (N > 0 ? N : Eigen::Dynamic);
template <int N>
using FixedVector = Eigen::Matrix<double, kEigenSize<N>, 1>;
template <int N>
using FixedMatrixMap = Eigen::Map<const Eigen::Matrix<double, kEigenSize<N>, kEigenSize<N>>,
                                  Eigen::Unaligned, Eigen::OuterStride<>>;
template <int N>
using FixedVectorMap = Eigen::Map<const FixedVector<N>>;

template <int N>
inline FixedMatrixMap<N> fixed_map(const MatrixCRef& M) {
  return FixedMatrixMap<N>(M.data(), M.rows(), M.cols(), Eigen::OuterStride<>(M.outerStride()));
}
template <int N>
inline FixedVectorMap<N> fixed_map(const VectorCRef& v) {
  return FixedVectorMap<N>(v.data(), v.size());
}

// The residual of z, w held in vector registers (N > 0): the same number as
// residual_of, whose min and max are exact, so that their order does not
// change the value (a zero's sign included: the comparisons against 0.0 keep
// +0.0). x - x is NaN exactly for a NaN or inf x, so the sum is NaN iff an
// entry is not finite.
template <int N>
inline double residual_of(const Eigen::Array<double, N, 1>& z, const Eigen::Array<double, N, 1>& w) {
  static_assert(N > 0, "fixed sizes only");
  const double poison = ((z - z) + (w - w)).sum();
  if (poison != poison) return std::numeric_limits<double>::infinity();
  const double worst_pair = std::max(0.0, z.min(w).abs().maxCoeff());
  return worst_pair - std::min(0.0, z.minCoeff()) - std::min(0.0, w.minCoeff());
}

template <int N>
inline Result verified(double residual, Status claimed, int iterations, double tol) {
  Result result;
  result.iterations = iterations;
  result.residual = residual;
  result.status = claimed;
  if (claimed == Status::solved && !(result.residual <= tol)) result.status = Status::singular;
  return result;
}

// verify for a z of fixed size N passed by value (in registers): writes it
// to z (unless nullptr), w = M z + q to w, and checks the residual without reading either
// back from memory (at these sizes the store-to-load round trips are a
// large part of the time).
template <int N>
inline Result verify_values(const MatrixCRef& M, const VectorCRef& q, const FixedVector<N>& z_value,
                            double* z, double* w, Status claimed, int iterations, double tol) {
  static_assert(N > 0, "fixed sizes only");
  const auto m = fixed_map<N>(M);
  // Column by column, in the order of multiply_add: w = q, then w += M_.j z_j.
  FixedVector<N> w_value = fixed_map<N>(q);
  for (int j = 0; j < N; ++j) w_value += m.col(j) * z_value[j];
  if (z != nullptr) Eigen::Map<FixedVector<N>>{z} = z_value;
  Eigen::Map<FixedVector<N>>{w} = w_value;
  return verified<N>(residual_of<N>(z_value.array(), w_value.array()), claimed, iterations, tol);
}

// Recomputes w = M z + q and checks complementarity_residual(z, w) <= tol for
// a claimed Status::solved (else Status::singular); other statuses pass through.
template <int N>
inline Result verify(const MatrixCRef& M, const VectorCRef& q, const VectorRef& z, VectorRef& w,
                     Status claimed, int iterations, double tol) {
  if constexpr (N > 0) {
    const FixedVector<N> z_value = FixedVectorMap<N>(z.data());
    return verify_values<N>(M, q, z_value, nullptr, w.data(), claimed, iterations, tol);
  } else {
    const int n = static_cast<int>(q.size());
    const auto m = fixed_map<N>(M);
    const FixedVectorMap<N> zf(z.data(), n);
    Eigen::Map<FixedVector<N>> wf(w.data(), n);
    // Column by column, in the order of multiply_add: w = q, then w += M_.j z_j.
    wf = fixed_map<N>(q);
    for (int j = 0; j < n; ++j) wf += m.col(j) * zf[j];
    return verified<N>(residual_of<N>(z.data(), w.data(), n), claimed, iterations, tol);
  }
}

// verify<0>: the size-generic ending the iterative methods use.
Result finish(const MatrixCRef& M, const VectorCRef& q, const VectorRef& z, VectorRef& w,
              Status claimed, int iterations, double tol);

// The methods themselves (one source file each), without validation: sizes
// equal, options in range, M and q possibly non-finite. The entry points
// solve_<method> and solve_<method>_unchecked validate and call these.
Result lemke(const MatrixCRef& M, const VectorCRef& q, VectorRef& z, VectorRef& w,
             const Options& options, Workspace& workspace);
Result pgs(const MatrixCRef& M, const VectorCRef& q, VectorRef& z, VectorRef& w,
           const Options& options, Workspace& workspace);
Result newton_fb(const MatrixCRef& M, const VectorCRef& q, VectorRef& z, VectorRef& w,
                 const Options& options, Workspace& workspace);
Result enumerate(const MatrixCRef& M, const VectorCRef& q, VectorRef& z, VectorRef& w,
                 const Options& options, Workspace& workspace);

// In-place LU factorization with partial pivoting of the square A (P A = L U,
// unit lower L). perm[k] is the row swapped with row k at step k. Returns
// false when a pivot is <= relative_pivot_tol * max|A| (numerically singular).
bool lu_factor(Eigen::Ref<Eigen::MatrixXd> A, int* perm, double relative_pivot_tol = 1e-13);

// Solves A x = b with the factors of lu_factor, overwriting b with x.
void lu_solve(const Eigen::Ref<const Eigen::MatrixXd>& LU, const int* perm,
              Eigen::Ref<Eigen::VectorXd> b);

// Solve M_aa z_a = -q_a on the active set a = {i : z_i > w_i} (z = 0 off it),
// with one step of iterative refinement: the exact answer of the
// complementary basis a near-solution points to. Writes the candidate into
// z_out and M z_out + q into w_out; false if M_aa is singular or z_a < 0.
// Uses the workspace's square, permutation, indices and vector columns 5, 6.
bool polish(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
            const double* z, const double* w, int n, Workspace& ws,
            Eigen::Ref<Eigen::VectorXd> z_out, Eigen::Ref<Eigen::VectorXd> w_out);

// Overall magnitude of the problem, max(1, max|M|, max|q|): scales the
// methods' internal feasibility tolerances (never the tol of "solved").
double problem_scale(const Eigen::Ref<const Eigen::MatrixXd>& M,
                     const Eigen::Ref<const Eigen::VectorXd>& q);

}  // namespace leadscrew::lcp::detail
