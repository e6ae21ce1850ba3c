#include "leadscrew/lcp/enumerate.hpp"

#include <algorithm>
#include <string>

#include "detail.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/lcp/workspace.hpp"

namespace leadscrew::lcp {

namespace {
// A basis counts as sign-feasible when its z_a and w off a are >= -this *
// scale; feasible bases that still miss tol mark the problem as too
// ill-conditioned rather than unsolvable.
constexpr double kFeasibilityRelTol = 1e-9;
}  // namespace

namespace detail {

Result enumerate(const MatrixCRef& M, const VectorCRef& q, VectorRef& z, VectorRef& w,
                 const Options& options, Workspace& workspace) {
  const int n = static_cast<int>(q.size());
  if (n > kMaxEnumerateSize)
    throw InvalidArgument("M has size " + std::to_string(n) +
                          " is invalid for method enumerate: must be <= " +
                          std::to_string(kMaxEnumerateSize));
  workspace.reserve(n);
  const int bases = 1 << n;
  const int max_bases = options.max_iter > 0 ? std::min(options.max_iter, bases) : bases;
  const double feasibility_floor = -kFeasibilityRelTol * problem_scale(M, q);

  int* active = workspace.indices.data();
  auto best_z = workspace.vectors.col(0).head(n);
  auto x = workspace.vectors.col(1).head(n);
  auto correction = workspace.vectors.col(2).head(n);
  double best_residual = -1.0;  // < 0: no sign-feasible basis yet
  bool any_singular = false;

  int tried = 0;
  for (int mask = 0; mask < max_bases; ++mask) {
    ++tried;
    int k = 0;
    for (int i = 0; i < n; ++i)
      if (mask & (1 << i)) active[k++] = i;
    z.setZero();
    if (k > 0) {
      auto A = workspace.square.topLeftCorner(k, k);
      for (int c = 0; c < k; ++c)
        for (int r = 0; r < k; ++r) A(r, c) = M(active[r], active[c]);
      if (!lu_factor(A, workspace.permutation.data())) {
        any_singular = true;
        continue;
      }
      auto xa = x.head(k);
      auto ca = correction.head(k);
      for (int r = 0; r < k; ++r) xa[r] = -q[active[r]];
      lu_solve(A, workspace.permutation.data(), xa);
      for (int r = 0; r < k; ++r) {  // one step of iterative refinement
        double sum = -q[active[r]];
        for (int c = 0; c < k; ++c) sum -= M(active[r], active[c]) * xa[c];
        ca[r] = sum;
      }
      lu_solve(A, workspace.permutation.data(), ca);
      for (int r = 0; r < k; ++r) z[active[r]] = xa[r] + ca[r];
    }
    multiply_add(M, z, q, w);
    bool feasible = true;
    for (int i = 0; i < n && feasible; ++i)
      feasible = (mask & (1 << i)) ? z[i] >= feasibility_floor : w[i] >= feasibility_floor;
    if (!feasible) continue;
    for (int i = 0; i < n; ++i) z[i] = std::max(z[i], 0.0);
    multiply_add(M, z, q, w);
    const double residual = complementarity_residual(z, w);
    if (residual <= options.tol) return finish(M, q, z, w, Status::solved, tried, options.tol);
    if (best_residual < 0.0 || residual < best_residual) {
      best_residual = residual;
      best_z = z;
    }
  }

  Status status;
  if (best_residual >= 0.0) {  // feasible in sign, but not to tol
    z = best_z;
    status = Status::singular;
  } else {
    z.setZero();
    status = tried < bases ? Status::max_iterations
                           : (any_singular ? Status::singular : Status::no_solution);
  }
  return finish(M, q, z, w, status, tried, options.tol);
}

}  // namespace detail

Result solve_enumerate(const Eigen::Ref<const Eigen::MatrixXd>& M,
                       const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
                       Eigen::Ref<Eigen::VectorXd> w, const Options& options,
                       Workspace& workspace) {
  detail::validate(M, q, z, w, options, Method::enumerate);
  return detail::enumerate(M, q, z, w, options, workspace);
}

Result solve_enumerate_unchecked(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                 const Eigen::Ref<const Eigen::VectorXd>& q,
                                 Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::VectorXd> w,
                                 const Options& options, Workspace& workspace) {
  detail::validate_shapes(M, q, z, w, options);
  return detail::enumerate(M, q, z, w, options, workspace);
}

}  // namespace leadscrew::lcp
