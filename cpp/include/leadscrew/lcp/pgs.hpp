// Projected Gauss-Seidel with successive over-relaxation (projected SOR,
// Cryer 1971):
//   z_i <- max(0, z_i - relaxation (M z + q)_i / M_ii),   i = 1..n, per sweep,
// using the already updated z_j (j < i). Converges for symmetric positive
// definite M and relaxation in (0, 2), and for H-matrices with a positive
// diagonal at suitable relaxation; on other matrices it may not (status
// max_iterations).
// Starts from z = 0, or from max(z, 0) with options.warm_start. Stops when the
// residual of (z, M z + q), computed after every sweep, is <= options.tol.
// A diagonal entry M_ii <= 0 gives status singular without iterating.
#pragma once

#include "leadscrew/lcp/lcp.hpp"

namespace leadscrew::lcp {

Result solve_pgs(const Eigen::Ref<const Eigen::MatrixXd>& M,
                 const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
                 Eigen::Ref<Eigen::VectorXd> w, const Options& options, Workspace& workspace);

// Without the scan of M and q for NaN and inf (see solve_unchecked in lcp.hpp).
Result solve_pgs_unchecked(const Eigen::Ref<const Eigen::MatrixXd>& M,
                           const Eigen::Ref<const Eigen::VectorXd>& q,
                           Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::VectorXd> w,
                           const Options& options, Workspace& workspace);

}  // namespace leadscrew::lcp
