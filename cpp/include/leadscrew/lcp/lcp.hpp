// Linear complementarity problems: find z with
//   w = M z + q,  z >= 0,  w >= 0,  z^T w = 0      (thesis eq. 2.13)
// Common types and the dispatcher; one header per method beside this one
// (lemke.hpp, pgs.hpp, newton_fb.hpp, enumerate.hpp), all with the signature
// of solve().
//
// Solving never allocates once a Workspace has the capacity for the problem
// size (the integrators keep one per model).
#pragma once

#include <Eigen/Core>
#include <string>

namespace leadscrew::lcp {

// solved:          z, w satisfy the LCP within options.tol (verified on w = M z + q).
// ray_termination: Lemke left the problem on a secondary ray: for a copositive-plus M
//                  (e.g. positive semidefinite) the LCP has no solution.
// max_iterations:  the iteration budget ran out (or PGS diverged: residual above
//                  1e50 times the problem's scale; the previous iterate is returned).
// singular:        the method met linear algebra it cannot continue with (PGS: a
//                  diagonal entry <= 0; Newton: a stationary point of the merit
//                  function that is no solution; Lemke/enumerate: a complementary
//                  basis too ill-conditioned to meet tol; enumerate: no solution
//                  among the bases whose principal submatrix is regular).
// no_solution:     enumerate proved that no solution exists (every principal
//                  submatrix regular, no complementary basis feasible).
// Every status but solved leaves in z the method's last iterate, with w = M z + q.
// Each method has a checked entry point solve_<method> and an unchecked one
// solve_<method>_unchecked with the contracts of solve() and solve_unchecked().
enum class Status { solved, ray_termination, max_iterations, singular, no_solution };
enum class Method { lemke, pgs, newton_fb, enumerate };

std::string status_name(Status status);
std::string method_name(Method method);
Method parse_method(const std::string& name);  // InvalidArgument listing the allowed names

struct Options {
  Method method = Method::lemke;
  double tol = 1e-12;        // absolute bound on complementarity_residual(z, w), > 0
  int max_iter = 0;          // 0: the method's default (default_max_iterations)
  double relaxation = 1.0;   // PGS/SOR relaxation in (0, 2)
  bool warm_start = false;   // start from the z passed in (pgs, newton_fb)
};

struct Result {
  Status status = Status::singular;
  int iterations = 0;    // pivots (lemke), sweeps (pgs), Newton steps, bases tried
  double residual = 0.0; // complementarity_residual(z, w) of the returned z
};

class Workspace;  // defined in workspace.hpp; preallocated scratch for every method

// Solve the LCP (M, q). z (size n) receives the solution (and carries the warm
// start when options.warm_start); w (size n) receives M z + q.
// Never reports Status::solved for a z whose residual exceeds options.tol.
// Throws InvalidArgument for non-square M, size mismatch, NaN or inf, options
// out of range.
Result solve(const Eigen::Ref<const Eigen::MatrixXd>& M,
             const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
             Eigen::Ref<Eigen::VectorXd> w, const Options& options, Workspace& workspace);

// solve() without the O(n^2) scan of M and q for NaN and inf: for callers that
// build M and q themselves (the integrators, the benchmark), where that scan
// costs as much as a small solve. Shapes and options are still checked
// (InvalidArgument). A NaN or inf in M or q (or a non-finite warm start) is
// not reported as an error but can never give Status::solved: the final
// verification forms M z + q over every column, so any non-finite entry
// makes the residual infinite; the status is then one of the others
// (singular, ray_termination, max_iterations or no_solution) and
// Result::residual is +infinity.
Result solve_unchecked(const Eigen::Ref<const Eigen::MatrixXd>& M,
                       const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
                       Eigen::Ref<Eigen::VectorXd> w, const Options& options,
                       Workspace& workspace);

// max_i |min(z_i, w_i)| + max(0, -min z) + max(0, -min w); +infinity if an
// entry of z or w is NaN or inf. InvalidArgument if the sizes differ.
double complementarity_residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                                const Eigen::Ref<const Eigen::VectorXd>& w);

// The iteration budget options.max_iter = 0 stands for:
//   lemke      1000 + 2^(min(n, 20) + 1) pivots (Murty's problems need 2^n)
//   pgs        10000 sweeps
//   newton_fb  100 Newton steps
//   enumerate  2^n bases (all of them)
int default_max_iterations(Method method, int n);

}  // namespace leadscrew::lcp
