// Semismooth Newton method on the Fischer-Burmeister reformulation
// (De Luca, Facchinei & Kanzow 1996):
//   Phi_i(z) = sqrt(z_i^2 + w_i^2) - z_i - w_i = 0,   w = M z + q,
// which holds exactly at the LCP's solutions. Each step solves H d = -Phi with
// an element H = D_a + D_b M of the generalized Jacobian, falls back to the
// steepest descent d = -H^T Phi of the merit function Psi = |Phi|^2 / 2 when
// the Newton direction is unavailable or not a descent direction, and takes an
// Armijo backtracking step on Psi. Before each step the active set
// {i : z_i > w_i} of the iterate is tried: M_aa z_a = -q_a, z = 0 elsewhere
// (the Newton step of the piece the solution lies on, which ends the method
// as soon as the active set is right); that z is kept only if it meets tol.
// Starts from z = 0, or from the z passed in with options.warm_start.
// A stationary point of Psi that is not a solution gives status singular.
#pragma once

#include "leadscrew/lcp/lcp.hpp"

namespace leadscrew::lcp {

Result solve_newton_fb(const Eigen::Ref<const Eigen::MatrixXd>& M,
                       const Eigen::Ref<const Eigen::VectorXd>& q,
                       Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::VectorXd> w,
                       const Options& options, Workspace& workspace);

// Without the scan of M and q for NaN and inf (see solve_unchecked in lcp.hpp).
Result solve_newton_fb_unchecked(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                 const Eigen::Ref<const Eigen::VectorXd>& q,
                                 Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::VectorXd> w,
                                 const Options& options, Workspace& workspace);

}  // namespace leadscrew::lcp
