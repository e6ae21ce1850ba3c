// Linear complementarity problems: find z with
//   w = M z + q,  z >= 0,  w >= 0,  z^T w = 0      (thesis eq. 2.13)
// Common types and the dispatcher; one header per method beside this one.
//
// Solving never allocates once a Workspace has the capacity for the problem
// size (the integrators keep one per model).
#pragma once

#include <Eigen/Core>
#include <string>

namespace leadscrew::lcp {

enum class Status { solved, ray_termination, max_iterations, singular };
enum class Method { lemke, pgs, newton_fb, enumerate };

std::string status_name(Status status);
std::string method_name(Method method);
Method parse_method(const std::string& name);  // InvalidArgument listing the allowed names

struct Options {
  Method method = Method::lemke;
  double tol = 1e-12;
  int max_iter = 0;          // 0: the method's default
  double relaxation = 1.0;   // PGS/SOR relaxation in (0, 2)
  bool warm_start = false;   // start from the z passed in (pgs, newton_fb)
};

struct Result {
  Status status = Status::singular;
  int iterations = 0;    // pivots (lemke), sweeps (pgs), Newton steps, bases tried
  double residual = 0.0; // max_i |min(z_i, w_i)| plus any negativity
};

class Workspace;  // defined in workspace.hpp; preallocated scratch for every method

// Solve the LCP (M, q). z (size n) receives the solution (and carries the warm
// start when options.warm_start); w (size n) receives M z + q.
// Never reports Status::solved for a z whose residual exceeds options.tol.
// Throws InvalidArgument for non-square M, size mismatch, NaN or inf.
Result solve(const Eigen::Ref<const Eigen::MatrixXd>& M,
             const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
             Eigen::Ref<Eigen::VectorXd> w, const Options& options, Workspace& workspace);

// max_i |min(z_i, w_i)| + max(0, -min z) + max(0, -min w)
double complementarity_residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                                const Eigen::Ref<const Eigen::VectorXd>& w);

}  // namespace leadscrew::lcp
