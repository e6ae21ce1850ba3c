#include "leadscrew/lcp/newton_fb.hpp"

#include <algorithm>
#include <cmath>

#include "detail.hpp"
#include "leadscrew/lcp/workspace.hpp"

namespace leadscrew::lcp {

namespace {

constexpr double kArmijo = 1e-4;         // sufficient decrease of Psi
constexpr int kMaxBacktracks = 60;       // step lengths 1, 1/2, ..., 2^-60
constexpr double kDescentRho = 1e-10;    // Newton direction accepted if grad.d <= -rho |d|^2.1
constexpr double kDescentPower = 2.1;

// Fischer-Burmeister function s - a - b with s = sqrt(a^2 + b^2) = hypot(a, b)
// (passed in: the Jacobian needs s too), without the cancellation of the
// direct formula when a, b > 0.
double fischer_burmeister(double a, double b, double s) {
  if (a + b > 0.0) return -2.0 * a * b / (s + a + b);
  return s - a - b;
}

double fischer_burmeister(double a, double b) {
  return fischer_burmeister(a, b, std::hypot(a, b));
}

double merit(const double* z, const double* w, int n) {
  double psi = 0.0;
  for (int i = 0; i < n; ++i) {
    const double phi = fischer_burmeister(z[i], w[i]);
    psi += phi * phi;
  }
  return 0.5 * psi;
}

// The semismooth Newton step's data at (z, w): Phi (phi), the generalized
// Jacobian H = D_a + D_b M (at the kink an element of the B-subdifferential)
// and grad Psi = H^T Phi (gradient, its squared norm gradient_norm2).
// Returns Psi = |Phi|^2 / 2 (the sum of merit(), in its order).
template <class Square>
double fb_linearization(const detail::MatrixCRef& M, const double* z, const double* w, int n,
                        Square& H, double* phi, double* da, double* db, double* gradient,
                        double& gradient_norm2) {
  const double inverse_sqrt2 = 1.0 / std::sqrt(2.0);
  double phi_norm2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double s = std::hypot(z[i], w[i]);
    phi[i] = fischer_burmeister(z[i], w[i], s);
    phi_norm2 += phi[i] * phi[i];
    if (s > 0.0) {
      da[i] = z[i] / s - 1.0;
      db[i] = w[i] / s - 1.0;
    } else {  // the kink: any (xi - 1, rho - 1) with xi^2 + rho^2 <= 1
      da[i] = db[i] = inverse_sqrt2 - 1.0;
    }
  }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) H(i, j) = db[i] * M(i, j) + (i == j ? da[i] : 0.0);
  gradient_norm2 = 0.0;
  for (int j = 0; j < n; ++j) {
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += H(i, j) * phi[i];
    gradient[j] = sum;
    gradient_norm2 += sum * sum;
  }
  return 0.5 * phi_norm2;
}

// Newton's direction H d = -Phi (into direction; H factored in place):
// true if H is regular and d a descent direction of Psi,
// grad.d <= -rho |d|^2.1.
template <class Square>
bool newton_direction(Square& H, int* permutation, const double* phi, const double* gradient,
                      double* direction, int n) {
  if (!detail::lu_factor(H, permutation)) return false;
  Eigen::Map<Eigen::VectorXd> d(direction, n);
  for (int i = 0; i < n; ++i) d[i] = -phi[i];
  detail::lu_solve(H, permutation, d);
  double slope = 0.0, norm2 = 0.0;
  for (int i = 0; i < n; ++i) slope += gradient[i] * d[i], norm2 += d[i] * d[i];
  return std::isfinite(slope) &&
         slope <= -kDescentRho * std::pow(std::sqrt(norm2), kDescentPower);
}

// Armijo backtracking on Psi from (z, w) along Newton's direction (newton),
// else along -grad Psi (then written to direction): true with the point
// accepted in z_trial, w_trial.
template <class Trial>
bool armijo_step(const detail::MatrixCRef& M, const double* z, const double* w, int n,
                 double psi, const double* gradient, double* direction, double* m_direction,
                 Trial& z_trial, Trial& w_trial, bool newton) {
  for (int attempt = newton ? 0 : 1; attempt < 2; ++attempt) {
    if (attempt == 1)
      for (int i = 0; i < n; ++i) direction[i] = -gradient[i];
    double slope = 0.0;
    for (int i = 0; i < n; ++i) slope += gradient[i] * direction[i];
    if (!(slope < 0.0)) continue;
    for (int i = 0; i < n; ++i) m_direction[i] = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) m_direction[i] += M(i, j) * direction[j];
    double t = 1.0;
    for (int backtrack = 0; backtrack <= kMaxBacktracks; ++backtrack, t *= 0.5) {
      for (int i = 0; i < n; ++i) {
        z_trial[i] = z[i] + t * direction[i];
        w_trial[i] = w[i] + t * m_direction[i];
      }
      if (merit(z_trial.data(), w_trial.data(), n) <= psi + kArmijo * t * slope) return true;
    }
  }
  return false;
}

}  // namespace

namespace detail {

Result newton_fb(const MatrixCRef& M, const VectorCRef& q, VectorRef& z, VectorRef& w,
                 const Options& options, Workspace& workspace) {
  const int n = static_cast<int>(q.size());
  workspace.reserve(n);
  if (!options.warm_start) z.setZero();
  const int max_steps =
      options.max_iter > 0 ? options.max_iter : default_max_iterations(Method::newton_fb, n);

  Workspace& ws = workspace;
  double* phi = ws.vectors.col(0).data();
  double* direction = ws.vectors.col(1).data();
  double* gradient = ws.vectors.col(2).data();
  auto z_trial = ws.vectors.col(3).head(n);
  auto w_trial = ws.vectors.col(4).head(n);
  double* m_direction = ws.vectors.col(5).data();
  double* da = ws.vectors.col(6).data();  // diagonal of D_a
  double* db = ws.vectors.col(7).data();  // diagonal of D_b
  auto H = ws.square.topLeftCorner(n, n);

  Status status = Status::max_iterations;
  int steps = 0;
  while (true) {
    multiply_add(M, z, q, w);
    if (complementarity_residual(z, w) <= options.tol) {
      status = Status::solved;
      break;
    }
    // Polishing reuses columns 5 and 6 and the square; done before they hold
    // this step's data.
    if (polish(M, q, z.data(), w.data(), n, ws, z_trial, w_trial) &&
        complementarity_residual(z_trial, w_trial) <= options.tol) {
      z = z_trial;
      status = Status::solved;
      break;
    }
    if (steps >= max_steps) break;

    // Phi, Psi and grad Psi; Newton's direction if H is regular and it
    // descends; Armijo backtracking on Psi, the gradient's if Newton's fails.
    double gradient_norm2 = 0.0;
    const double psi =
        fb_linearization(M, z.data(), w.data(), n, H, phi, da, db, gradient, gradient_norm2);
    const bool newton = newton_direction(H, ws.permutation.data(), phi, gradient, direction, n);
    const bool stepped = armijo_step(M, z.data(), w.data(), n, psi, gradient, direction,
                                     m_direction, z_trial, w_trial, newton);
    if (!stepped || gradient_norm2 == 0.0) {  // a stationary point of Psi, no solution
      status = Status::singular;
      break;
    }
    z = z_trial;
    ++steps;
  }
  return finish(M, q, z, w, status, steps, options.tol);
}

}  // namespace detail

Result solve_newton_fb(const Eigen::Ref<const Eigen::MatrixXd>& M,
                       const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z,
                       Eigen::Ref<Eigen::VectorXd> w, const Options& options,
                       Workspace& workspace) {
  detail::validate(M, q, z, w, options, Method::newton_fb);
  return detail::newton_fb(M, q, z, w, options, workspace);
}

Result solve_newton_fb_unchecked(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                 const Eigen::Ref<const Eigen::VectorXd>& q,
                                 Eigen::Ref<Eigen::VectorXd> z, Eigen::Ref<Eigen::VectorXd> w,
                                 const Options& options, Workspace& workspace) {
  detail::validate_shapes(M, q, z, w, options);
  return detail::newton_fb(M, q, z, w, options, workspace);
}

}  // namespace leadscrew::lcp
