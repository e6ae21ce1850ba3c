#include "leadscrew/friction/flank_lcp.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

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
  // The inputs come from model values (a non-finite one gives a non-solved
  // status, which the caller reports), so the unchecked entry point.
  // The tolerance is relative to the problem: accelerations of 1e4 m/s^2 or
  // forces of 1e3 N carry round-off far above an absolute 1e-12.
  lcp::Options scaled = options;
  scaled.tol = options.tol * std::max(1e-300, offset.cwiseAbs().maxCoeff());
  const lcp::Result solved = lcp::solve_unchecked(matrix, offset, z, w, scaled, workspace);
  result.status = solved.status;
  result.lcp_iterations = solved.iterations;
  if (solved.status != lcp::Status::solved) return result;
  result.friction_force = (z[0] - mu * sigma * beta) / coupling;
  result.normal_force = beta + alpha * result.friction_force;
  // Complementarity decides from the basis: a positive friction reserve x+
  // (z[0] basic) forces y+ = 0, and a non-basic y- (z[1]) is exactly 0. Only
  // w is recomputed as M z + q and carries round-off, so it is used only
  // where x+ = 0.
  const double positive_part = z[0] > 0.0 ? 0.0 : std::max(w[0], 0.0);
  result.slip_acceleration = positive_part - z[1];
  result.consistent = sigma * result.normal_force >= 0.0;
  return result;
}

FlankLcpResult solve_flank_prescribed_slip(double c, bool slip_zero, double alpha, double beta,
                                           double mu, int sigma, double motor0, double motor1) {
  FlankLcpResult result;
  result.status = lcp::Status::solved;
  const double reserve = mu * sigma;  // lambda_T = -+ reserve lambda_N at the cone's edges
  if (!slip_zero) {
    // Slip in the direction c gives: lambda_T = -s mu sigma (beta + alpha lambda_T).
    const double s = c > 0.0 ? 1.0 : -1.0;
    const double coupling = 1.0 + s * reserve * alpha;
    if (!(coupling > 0.0)) return result;  // the friction force would drive its own normal force
    result.friction_force = -s * reserve * beta / coupling;
    result.normal_force = beta + alpha * result.friction_force;
    result.slip_acceleration = c;
    result.consistent = sigma * result.normal_force >= 0.0;
    return result;
  }
  // Stick: the cone |lambda_T| <= mu sigma (beta + alpha lambda_T) is the
  // interval between its two edges (each a linear equation in lambda_T).
  const double upper_coupling = 1.0 - reserve * alpha, lower_coupling = 1.0 + reserve * alpha;
  if (!(upper_coupling > 0.0) || !(lower_coupling > 0.0) || !(sigma * beta >= 0.0)) return result;
  const double high = reserve * beta / upper_coupling, low = -reserve * beta / lower_coupling;
  double friction = motor1 != 0.0 ? -motor0 / motor1 : 0.0;
  if (!std::isfinite(friction)) friction = 0.0;
  result.friction_force = std::min(high, std::max(low, friction));
  result.normal_force = beta + alpha * result.friction_force;
  result.slip_acceleration = 0.0;
  result.consistent = sigma * result.normal_force >= 0.0;
  return result;
}

FlankLcpResult flank_stick(double c, double d, double alpha, double beta, double mu, int sigma) {
  FlankLcpResult r;
  if (!(d > 0.0)) return r;
  r.status = lcp::Status::solved;
  r.friction_force = -c / d;
  r.normal_force = beta + alpha * r.friction_force;
  r.slip_acceleration = 0.0;
  r.consistent = (sigma == 0 || sigma * r.normal_force >= 0.0) &&
                 std::abs(r.friction_force) <= mu * std::abs(r.normal_force);
  return r;
}

}  // namespace leadscrew::friction
