#include "leadscrew/lcp/lcp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "detail.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/lcp/enumerate.hpp"
#include "leadscrew/lcp/workspace.hpp"

namespace leadscrew::lcp {

std::string status_name(Status status) {
  switch (status) {
    case Status::solved: return "solved";
    case Status::ray_termination: return "ray_termination";
    case Status::max_iterations: return "max_iterations";
    case Status::singular: return "singular";
    case Status::no_solution: return "no_solution";
  }
  return "unknown";
}

std::string method_name(Method method) {
  switch (method) {
    case Method::lemke: return "lemke";
    case Method::pgs: return "pgs";
    case Method::newton_fb: return "newton_fb";
    case Method::enumerate: return "enumerate";
  }
  return "unknown";
}

Method parse_method(const std::string& name) {
  static const std::vector<std::string> names = {"lemke", "pgs", "newton_fb", "enumerate"};
  return static_cast<Method>(require_choice("method", name, names));
}

int default_max_iterations(Method method, int n) {
  switch (method) {
    case Method::lemke: return detail::default_lemke_pivots(n);
    case Method::pgs: return 10000;
    case Method::newton_fb: return 100;
    case Method::enumerate: return 1 << std::min(std::max(n, 0), kMaxEnumerateSize);
  }
  return 0;
}

namespace {
Result run(const detail::MatrixCRef& M, const detail::VectorCRef& q, detail::VectorRef& z,
           detail::VectorRef& w, const Options& options, Workspace& workspace) {
  switch (options.method) {
    case Method::lemke: return detail::lemke(M, q, z, w, options, workspace);
    case Method::pgs: return detail::pgs(M, q, z, w, options, workspace);
    case Method::newton_fb: return detail::newton_fb(M, q, z, w, options, workspace);
    case Method::enumerate: return detail::enumerate(M, q, z, w, options, workspace);
  }
  throw InvalidArgument(
      "options.method is invalid: must be one of lemke, pgs, newton_fb, enumerate");
}
}  // namespace

Result solve(const Eigen::Ref<const Eigen::MatrixXd>& M,
             const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
             Eigen::Ref<Eigen::VectorXd> w, const Options& options, Workspace& workspace) {
  detail::validate(M, q, z, w, options, options.method);
  return run(M, q, z, w, options, workspace);
}

Result solve_unchecked(const Eigen::Ref<const Eigen::MatrixXd>& M,
                       const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
                       Eigen::Ref<Eigen::VectorXd> w, const Options& options,
                       Workspace& workspace) {
  detail::validate_shapes(M, q, z, w, options);
  return run(M, q, z, w, options, workspace);
}

double complementarity_residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                                const Eigen::Ref<const Eigen::VectorXd>& w) {
  if (w.size() != z.size())
    throw InvalidArgument("w has size " + std::to_string(w.size()) +
                          " is invalid: must equal the size of z (" + std::to_string(z.size()) +
                          ")");
  return detail::residual_of<0>(z.data(), w.data(), static_cast<int>(z.size()));
}

namespace detail {

namespace {
[[noreturn]] void fail_size(const char* name, Eigen::Index size, Eigen::Index n) {
  throw InvalidArgument(std::string(name) + " has size " + std::to_string(size) +
                        " is invalid: must equal the size of M (" + std::to_string(n) + ")");
}
}  // namespace

void fail_shapes(const Eigen::Ref<const Eigen::MatrixXd>& M,
                 const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<Eigen::VectorXd>& z,
                 const Eigen::Ref<Eigen::VectorXd>& w, const Options& options) {
  const Eigen::Index n = M.rows();
  if (M.cols() != n)
    throw InvalidArgument("M has shape " + std::to_string(M.rows()) + "x" +
                          std::to_string(M.cols()) + " is invalid: must be square (n x n)");
  if (q.size() != n) fail_size("q", q.size(), n);
  if (z.size() != n) fail_size("z", z.size(), n);
  if (w.size() != n) fail_size("w", w.size(), n);
  if (!(std::isfinite(options.tol) && options.tol > 0.0)) require_positive("tol", options.tol);
  if (options.max_iter < 0)
    throw InvalidArgument("max_iter = " + std::to_string(options.max_iter) +
                          " is invalid: must be an integer >= 0 (0: the method's default)");
  if (!(options.relaxation > 0.0 && options.relaxation < 2.0))
    require_in_range("relaxation", options.relaxation, 0.0, 2.0, true, true);
  throw InvalidArgument("M has " + std::to_string(n) + " rows is invalid: too large");
}

void validate_finite(const Eigen::Ref<const Eigen::MatrixXd>& M,
                     const Eigen::Ref<const Eigen::VectorXd>& q,
                     const Eigen::Ref<Eigen::VectorXd>& z, const Options& options,
                     Method method) {
  const Eigen::Index n = q.size();
  // x * 0 is NaN exactly for x = NaN or +-inf, and 0 otherwise: the sum is
  // NaN iff an entry is not finite. Eigen's sum runs in vector registers with
  // several partial sums (no chain of n^2 dependent additions). Only if it is
  // NaN are the entries searched for the one to name.
  const double poison = (M.array() * 0.0).sum() + (q.array() * 0.0).sum();
  if (poison != poison) {
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index i = 0; i < n; ++i)
        if (!std::isfinite(M(i, j)))
          require_finite("M[" + std::to_string(i) + ", " + std::to_string(j) + "]", M(i, j));
    for (Eigen::Index i = 0; i < n; ++i)
      if (!std::isfinite(q[i])) require_finite("q[" + std::to_string(i) + "]", q[i]);
  }
  if (options.warm_start && (method == Method::pgs || method == Method::newton_fb))
    for (Eigen::Index i = 0; i < n; ++i)
      if (!std::isfinite(z[i])) require_finite("z0[" + std::to_string(i) + "]", z[i]);
}

int validate(const Eigen::Ref<const Eigen::MatrixXd>& M,
             const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<Eigen::VectorXd>& z,
             const Eigen::Ref<Eigen::VectorXd>& w, const Options& options, Method method) {
  const int n = validate_shapes(M, q, z, w, options);
  validate_finite(M, q, z, options, method);
  return n;
}

void multiply_add(const Eigen::Ref<const Eigen::MatrixXd>& M,
                  const Eigen::Ref<const Eigen::VectorXd>& z,
                  const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> w) {
  const Eigen::Index n = q.size();
  for (Eigen::Index i = 0; i < n; ++i) w[i] = q[i];
  for (Eigen::Index j = 0; j < n; ++j) {
    const double zj = z[j];
    if (zj == 0.0) continue;
    const double* column = M.data() + j * M.outerStride();
    for (Eigen::Index i = 0; i < n; ++i) w[i] += column[i] * zj;
  }
}

Result finish(const MatrixCRef& M, const VectorCRef& q, const VectorRef& z, VectorRef& w,
              Status claimed, int iterations, double tol) {
  return verify<0>(M, q, z, w, claimed, iterations, tol);
}

// Solve M_aa z_a = -q_a on the active set a = {i : z_i > w_i}, z = 0 off it,
// with one step of iterative refinement. Writes the candidate into z_out and
// M z_out + q into w_out; returns false if M_aa is singular or z_a < 0.
bool polish(const Eigen::Ref<const Eigen::MatrixXd>& M,
            const Eigen::Ref<const Eigen::VectorXd>& q, const double* z, const double* w,
            int n, Workspace& ws, Eigen::Ref<Eigen::VectorXd> z_out,
            Eigen::Ref<Eigen::VectorXd> w_out) {
  int* active = ws.indices.data();
  int k = 0;
  for (int i = 0; i < n; ++i)
    if (z[i] > w[i]) active[k++] = i;
  auto A = ws.square.topLeftCorner(k, k);
  for (int c = 0; c < k; ++c)
    for (int r = 0; r < k; ++r) A(r, c) = M(active[r], active[c]);
  if (!lu_factor(A, ws.permutation.data())) return false;
  auto x = ws.vectors.col(5).head(k);
  auto correction = ws.vectors.col(6).head(k);
  for (int r = 0; r < k; ++r) x[r] = -q[active[r]];
  lu_solve(A, ws.permutation.data(), x);
  for (int r = 0; r < k; ++r) {  // correction = -q_a - M_aa x
    double sum = -q[active[r]];
    for (int c = 0; c < k; ++c) sum -= M(active[r], active[c]) * x[c];
    correction[r] = sum;
  }
  lu_solve(A, ws.permutation.data(), correction);
  z_out.setZero();
  for (int r = 0; r < k; ++r) {
    const double value = x[r] + correction[r];
    if (value < 0.0) return false;
    z_out[active[r]] = value;
  }
  multiply_add(M, z_out, q, w_out);
  return true;
}


bool lu_factor(Eigen::Ref<Eigen::MatrixXd> A, int* perm, double relative_pivot_tol) {
  const Eigen::Index n = A.rows();
  double scale = 0.0;
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) scale = std::max(scale, std::abs(A(i, j)));
  const double pivot_floor = relative_pivot_tol * scale;
  if (!(scale > 0.0)) return n == 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::Index p = k;
    double best = std::abs(A(k, k));
    for (Eigen::Index i = k + 1; i < n; ++i)
      if (std::abs(A(i, k)) > best) best = std::abs(A(i, k)), p = i;
    perm[k] = static_cast<int>(p);
    if (!(best > pivot_floor)) return false;
    if (p != k) A.row(k).swap(A.row(p));
    const double inverse_pivot = 1.0 / A(k, k);
    for (Eigen::Index i = k + 1; i < n; ++i) A(i, k) *= inverse_pivot;
    for (Eigen::Index j = k + 1; j < n; ++j) {
      const double akj = A(k, j);
      if (akj == 0.0) continue;
      for (Eigen::Index i = k + 1; i < n; ++i) A(i, j) -= A(i, k) * akj;
    }
  }
  return true;
}

void lu_solve(const Eigen::Ref<const Eigen::MatrixXd>& LU, const int* perm,
              Eigen::Ref<Eigen::VectorXd> b) {
  const Eigen::Index n = LU.rows();
  for (Eigen::Index k = 0; k < n; ++k)
    if (perm[k] != k) std::swap(b[k], b[perm[k]]);
  for (Eigen::Index j = 0; j < n; ++j) {  // L y = P b (unit diagonal), column-oriented
    const double bj = b[j];
    if (bj == 0.0) continue;
    for (Eigen::Index i = j + 1; i < n; ++i) b[i] -= LU(i, j) * bj;
  }
  for (Eigen::Index j = n - 1; j >= 0; --j) {  // U x = y
    b[j] /= LU(j, j);
    const double bj = b[j];
    if (bj == 0.0) continue;
    for (Eigen::Index i = 0; i < j; ++i) b[i] -= LU(i, j) * bj;
  }
}

double problem_scale(const Eigen::Ref<const Eigen::MatrixXd>& M,
                     const Eigen::Ref<const Eigen::VectorXd>& q) {
  double scale = 1.0;
  for (Eigen::Index j = 0; j < M.cols(); ++j)
    for (Eigen::Index i = 0; i < M.rows(); ++i) scale = std::max(scale, std::abs(M(i, j)));
  for (Eigen::Index i = 0; i < q.size(); ++i) scale = std::max(scale, std::abs(q[i]));
  return scale;
}

}  // namespace detail
}  // namespace leadscrew::lcp
