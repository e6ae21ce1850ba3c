#include "leadscrew/friction/flank_lcp.hpp"

#include <Eigen/Core>

namespace leadscrew::friction {

FlankLcpResult solve_flank_lcp(double c, double d, double alpha, double beta, double mu,
                               int sigma, lcp::Workspace& workspace,
                               const lcp::Options& options) {
  FlankLcpResult result;
  // lambda_T = (x+ - mu sigma beta) / D
  const double coupling = 1.0 + mu * sigma * alpha;
  if (!(coupling > 0.0)) return result;  // the friction force would drive its own normal force
  Eigen::Matrix2d matrix;
  matrix << d / coupling, 1.0, 2.0 * mu * sigma * alpha / coupling - 1.0, 0.0;
  const Eigen::Vector2d offset(c - d * mu * sigma * beta / coupling,
                               2.0 * mu * sigma * beta / coupling);
  Eigen::Vector2d z = Eigen::Vector2d::Zero(), w;
  const lcp::Result solved = lcp::solve(matrix, offset, z, w, options, workspace);
  result.status = solved.status;
  result.lcp_iterations = solved.iterations;
  if (solved.status != lcp::Status::solved) return result;
  result.friction_force = (z[0] - mu * sigma * beta) / coupling;
  result.normal_force = beta + alpha * result.friction_force;
  // y+ and y- are exactly zero when stuck (non-basic): no round-off slip.
  result.slip_acceleration = w[0] - z[1];
  result.consistent = sigma * result.normal_force >= 0.0;
  return result;
}

}  // namespace leadscrew::friction
