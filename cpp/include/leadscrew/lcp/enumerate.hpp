// The reference method: try every complementary basis. For each index set a
// (all 2^n of them, in the order of the bit masks) solve M_aa z_a = -q_a, set
// z_i = 0 outside a and accept the first z whose residual of (z, M z + q) is
// <= tol. Exponential: limited to n <= kMaxEnumerateSize.
//
// Every solution of an LCP whose principal submatrices are all regular is such
// a basic solution, so for those problems "no basis is feasible" proves that no
// solution exists (status no_solution). When some principal submatrix was
// singular and no basis is feasible, the status is singular (a solution on a
// singular basis would be missed). Warm start is ignored.
#pragma once

#include "leadscrew/lcp/lcp.hpp"

namespace leadscrew::lcp {

constexpr int kMaxEnumerateSize = 12;

// InvalidArgument if n > kMaxEnumerateSize.
Result solve_enumerate(const Eigen::Ref<const Eigen::MatrixXd>& M,
                       const Eigen::Ref<const Eigen::VectorXd>& q,
                       Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::VectorXd> w,
                       const Options& options, Workspace& workspace);

// Without the scan of M and q for NaN and inf (see solve_unchecked in lcp.hpp).
Result solve_enumerate_unchecked(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                 const Eigen::Ref<const Eigen::VectorXd>& q,
                                 Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::VectorXd> w,
                                 const Options& options, Workspace& workspace);

}  // namespace leadscrew::lcp
