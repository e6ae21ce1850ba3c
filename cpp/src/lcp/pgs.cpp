#include "leadscrew/lcp/pgs.hpp"

#include <algorithm>
#include <cmath>

#include "detail.hpp"
#include "leadscrew/lcp/workspace.hpp"

namespace leadscrew::lcp {

namespace {
constexpr double kDivergenceFactor = 1e50;
}  // namespace

namespace detail {

Result pgs(const MatrixCRef& M, const VectorCRef& q, VectorRef& z, VectorRef& w,
           const Options& options, Workspace& workspace) {
  const int n = static_cast<int>(q.size());
  workspace.reserve(n);
  if (options.warm_start)
    for (int i = 0; i < n; ++i) z[i] = std::max(z[i], 0.0);
  else
    z.setZero();
  for (int i = 0; i < n; ++i)
    if (!(M(i, i) > 0.0)) return finish(M, q, z, w, Status::singular, 0, options.tol);

  const int max_sweeps =
      options.max_iter > 0 ? options.max_iter : default_max_iterations(Method::pgs, n);
  const double omega = options.relaxation;
  // 1 / M_ii, computed once.
  double* inverse_diagonal = workspace.vectors.col(0).data();
  for (int i = 0; i < n; ++i) inverse_diagonal[i] = 1.0 / M(i, i);

  int sweeps = 0;
  multiply_add(M, z, q, w);
  bool converged = complementarity_residual(z, w) <= options.tol;
  double* previous = workspace.vectors.col(1).data();
  // Iterates this far out have left every solution behind (PGS diverges on
  // some non-H-matrices); stopping here keeps z and M z finite.
  const double divergence = kDivergenceFactor * problem_scale(M, q);
  // w = M z + q is kept current through the sweep: a changed z_i adds its
  // column (contiguous), so row i reads its Gauss-Seidel residual from w and
  // a sweep costs one pass over M, not two. The update's round-off is
  // cleared by an exact M z + q wherever the sweep looks converged.
  while (!converged && sweeps < max_sweeps) {
    for (int i = 0; i < n; ++i) previous[i] = z[i];
    for (int i = 0; i < n; ++i) {
      const double updated = std::max(0.0, z[i] - omega * w[i] * inverse_diagonal[i]);
      const double change = updated - z[i];
      if (change != 0.0) {
        z[i] = updated;
        w += change * M.col(i);
      }
    }
    ++sweeps;
    double residual = complementarity_residual(z, w);
    if (!(residual <= divergence)) {  // diverged: report the previous iterate
      for (int i = 0; i < n; ++i) z[i] = previous[i];
      break;
    }
    if (residual <= options.tol) {
      multiply_add(M, z, q, w);
      residual = complementarity_residual(z, w);
    }
    converged = residual <= options.tol;
  }
  return finish(M, q, z, w, converged ? Status::solved : Status::max_iterations,
                        sweeps, options.tol);
}

}  // namespace detail

Result solve_pgs(const Eigen::Ref<const Eigen::MatrixXd>& M,
                 const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
                 Eigen::Ref<Eigen::VectorXd> w, const Options& options, Workspace& workspace) {
  detail::validate(M, q, z, w, options, Method::pgs);
  return detail::pgs(M, q, z, w, options, workspace);
}

Result solve_pgs_unchecked(const Eigen::Ref<const Eigen::MatrixXd>& M,
                           const Eigen::Ref<const Eigen::VectorXd>& q,
                           Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::VectorXd> w,
                           const Options& options, Workspace& workspace) {
  detail::validate_shapes(M, q, z, w, options);
  return detail::pgs(M, q, z, w, options, workspace);
}

}  // namespace leadscrew::lcp
