// Lemke's complementary pivoting method (Lemke 1965; Cottle, Pang & Stone,
// "The Linear Complementarity Problem", sec. 4.4) with the covering vector
// d = (1, ..., 1) and the lexicographic minimum-ratio test, so that degenerate
// problems cannot cycle.
//
// A condensed tableau holds the n + 1 nonbasic columns of B^-1 [I, -M, -d | q]
// (basic columns are unit vectors and are not stored: n (n + 2) entries
// updated per pivot instead of n (2n + 2)). The rows of [rhs, B^-1] break ties
// in the ratio test; B^-1's column j is the stored column of w_j, or a unit
// vector while w_j is basic. When the artificial variable z0 is among the tied
// candidates it leaves first (that ends the method with a solution).
// The answer is verified: w = M z + q is recomputed and the residual checked;
// if it misses tol, the basic values are refined twice against the original
// data (x_B += B^-1 (q - B x_B)) and verified again.
//
// With q >= 0 the method stops before its first pivot: z = 0 (verified).
// For n <= kMaxFixedLemkeSize the same code runs on a tableau of fixed size on
// the stack (dispatch on n once; loops unrolled; the workspace is used only
// by the final polish), larger n on the workspace. Columns are updated
// lazily, when read (same numbers as updating every column at every pivot).
// The ratio test runs the lexicographic comparison only when the two
// smallest ratios tie.
//
// Finds a solution for every P-matrix and for every feasible LCP with a
// copositive-plus M (e.g. positive semidefinite); ray_termination on such an M
// proves that the LCP has no solution. Warm start is ignored.
#pragma once

#include "leadscrew/lcp/lcp.hpp"

namespace leadscrew::lcp {

// Largest n solved on a fixed-size (stack) tableau.
constexpr int kMaxFixedLemkeSize = 8;

Result solve_lemke(const Eigen::Ref<const Eigen::MatrixXd>& M,
                   const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
                   Eigen::Ref<Eigen::VectorXd> w, const Options& options,
                   Workspace& workspace);

// Without the scan of M and q for NaN and inf (see solve_unchecked in lcp.hpp).
Result solve_lemke_unchecked(const Eigen::Ref<const Eigen::MatrixXd>& M,
                             const Eigen::Ref<const Eigen::VectorXd>& q,
                             Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::VectorXd> w,
                             const Options& options, Workspace& workspace);

// solve_lemke_unchecked on the size-generic code path (runtime n, workspace
// memory) for every n, also n <= kMaxFixedLemkeSize: the reference that the
// fixed-size paths are tested against, and the benchmark's comparison.
Result solve_lemke_generic(const Eigen::Ref<const Eigen::MatrixXd>& M,
                           const Eigen::Ref<const Eigen::VectorXd>& q,
                           Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::VectorXd> w,
                           const Options& options, Workspace& workspace);

}  // namespace leadscrew::lcp
