// Internals shared by the LCP methods (not installed, not public API).
#pragma once

#include <Eigen/Core>

#include "leadscrew/lcp/lcp.hpp"
#include "leadscrew/lcp/workspace.hpp"

namespace leadscrew::lcp::detail {

// Checks shapes, finiteness and options; returns n. Throws InvalidArgument
// naming the argument. Builds no string unless it throws (no allocation).
int validate(const Eigen::Ref<const Eigen::MatrixXd>& M,
             const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<Eigen::VectorXd>& z,
             const Eigen::Ref<Eigen::VectorXd>& w, const Options& options, Method method);

// w = M z + q, skipping zero entries of z.
void multiply_add(const Eigen::Ref<const Eigen::MatrixXd>& M,
                  const Eigen::Ref<const Eigen::VectorXd>& z,
                  const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> w);

// The common ending of every method: w = M z + q, residual, and the status.
// A method's `claimed` solved is downgraded to singular when the verified
// residual exceeds tol (a basis too ill-conditioned to meet it); any other
// status is reported as given.
Result finish(const Eigen::Ref<const Eigen::MatrixXd>& M,
              const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<Eigen::VectorXd>& z,
              Eigen::Ref<Eigen::VectorXd> w, Status claimed, int iterations, double tol);

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
