#include "leadscrew/friction/coulomb_lcp.hpp"

#include <cmath>
#include <string>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::friction {

namespace {

// Checks build no string unless they throw: the builders run in integrators'
// right-hand sides and must not allocate.
void require_size(const char* name, Eigen::Index actual, Eigen::Index expected) {
  if (actual != expected)
    throw InvalidArgument(std::string(name) + " has size " + std::to_string(actual) +
                          " is invalid: must have size " + std::to_string(expected));
}

void require_shape(const char* name, Eigen::Index rows, Eigen::Index cols,
                   Eigen::Index expected_rows, Eigen::Index expected_cols) {
  if (rows != expected_rows || cols != expected_cols)
    throw InvalidArgument(std::string(name) + " has shape " + std::to_string(rows) + "x" +
                          std::to_string(cols) + " is invalid: must be " +
                          std::to_string(expected_rows) + "x" + std::to_string(expected_cols));
}

// require_nonnegative, with the name made a std::string only when it throws.
void require_nonnegative_scalar(const char* name, double value) {
  if (!(std::isfinite(value) && value >= 0.0)) require_nonnegative(name, value);
}

void require_finite_matrix(const char* name, const Eigen::Ref<const Eigen::MatrixXd>& m,
                           Eigen::Index rows, Eigen::Index cols) {
  require_shape(name, m.rows(), m.cols(), rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i)
      if (!std::isfinite(m(i, j)))
        require_finite(std::string(name) + "[" + std::to_string(i) + ", " +
                           std::to_string(j) + "]",
                       m(i, j));
}

void require_finite_vector(const char* name, const Eigen::Ref<const Eigen::VectorXd>& v,
                           Eigen::Index size) {
  require_size(name, v.size(), size);
  for (Eigen::Index i = 0; i < size; ++i)
    if (!std::isfinite(v[i])) require_finite(std::string(name) + "[" + std::to_string(i) + "]", v[i]);
}

void require_nonnegative_vector(const char* name, const Eigen::Ref<const Eigen::VectorXd>& v,
                                Eigen::Index size) {
  require_size(name, v.size(), size);
  for (Eigen::Index i = 0; i < size; ++i)
    if (!(std::isfinite(v[i]) && v[i] >= 0.0))
      require_nonnegative(std::string(name) + "[" + std::to_string(i) + "]", v[i]);
}

}  // namespace

SingleFrictionLcp single_friction_lcp(double delassus, double free_acceleration, double mu,
                                      double normal_force) {
  if (!(std::isfinite(delassus) && delassus > 0.0)) require_positive("delassus", delassus);
  if (!std::isfinite(free_acceleration)) require_finite("free_acceleration", free_acceleration);
  require_nonnegative_scalar("mu", mu);
  require_nonnegative_scalar("normal_force", normal_force);
  const double reserve = mu * normal_force;  // the friction bound mu lambda_N
  SingleFrictionLcp lcp;
  lcp.A << delassus, 0.0, 0.0, delassus;  // eq. (3.14): 1/m on the diagonal
  lcp.b << -(delassus * reserve + free_acceleration), -(delassus * reserve - free_acceleration);
  return lcp;
}

TangentialState single_friction_state(const Eigen::Ref<const Eigen::VectorXd>& z,
                                      const Eigen::Ref<const Eigen::VectorXd>& w, double mu,
                                      double normal_force) {
  require_finite_vector("z", z, 2);
  require_finite_vector("w", w, 2);
  require_nonnegative_scalar("mu", mu);
  require_nonnegative_scalar("normal_force", normal_force);
  const double reserve = mu * normal_force;
  // Row 1 holds for lambda_T = r - x1 unless the contact slides forwards
  // (g_T''+ = w2 > 0, x2 = 0, lambda_T = -r); when sticking both rows agree.
  const double friction = w[1] > w[0] ? z[1] - reserve : reserve - z[0];
  return {friction, w[1] - w[0]};
}

void friction_lcp(const Eigen::Ref<const Eigen::MatrixXd>& delassus,
                  const Eigen::Ref<const Eigen::VectorXd>& free_acceleration,
                  const Eigen::Ref<const Eigen::VectorXd>& mu,
                  const Eigen::Ref<const Eigen::VectorXd>& normal_force,
                  Eigen::Ref<Eigen::MatrixXd> A, Eigen::Ref<Eigen::VectorXd> b) {
  const Eigen::Index n = delassus.rows();
  require_finite_matrix("delassus", delassus, n, n);
  require_finite_vector("free_acceleration", free_acceleration, n);
  require_nonnegative_vector("mu", mu, n);
  require_nonnegative_vector("normal_force", normal_force, n);
  require_shape("A", A.rows(), A.cols(), 2 * n, 2 * n);
  require_size("b", b.size(), 2 * n);
  A.setZero();
  for (Eigen::Index i = 0; i < n; ++i) {
    double g_times_reserve = 0.0;  // (G r)_i
    for (Eigen::Index j = 0; j < n; ++j) {
      A(i, j) = delassus(i, j);
      g_times_reserve += delassus(i, j) * mu[j] * normal_force[j];
    }
    A(i, n + i) = 1.0;   // + g_T''+
    A(n + i, i) = -1.0;  // x2 = 2 r - x1
    b[i] = -(g_times_reserve + free_acceleration[i]);
    b[n + i] = 2.0 * mu[i] * normal_force[i];
  }
}

void friction_state(const Eigen::Ref<const Eigen::VectorXd>& z,
                    const Eigen::Ref<const Eigen::VectorXd>& w,
                    const Eigen::Ref<const Eigen::VectorXd>& mu,
                    const Eigen::Ref<const Eigen::VectorXd>& normal_force,
                    Eigen::Ref<Eigen::VectorXd> friction_force,
                    Eigen::Ref<Eigen::VectorXd> tangential_acceleration) {
  const Eigen::Index n = mu.size();
  require_nonnegative_vector("mu", mu, n);
  require_nonnegative_vector("normal_force", normal_force, n);
  require_finite_vector("z", z, 2 * n);
  require_finite_vector("w", w, 2 * n);
  require_size("friction_force", friction_force.size(), n);
  require_size("tangential_acceleration", tangential_acceleration.size(), n);
  for (Eigen::Index i = 0; i < n; ++i) {
    friction_force[i] = mu[i] * normal_force[i] - z[i];
    tangential_acceleration[i] = z[n + i] - w[i];
  }
}

void contact_lcp(const Eigen::Ref<const Eigen::MatrixXd>& delassus,
                 const Eigen::Ref<const Eigen::VectorXd>& free_acceleration,
                 const Eigen::Ref<const Eigen::VectorXd>& mu, Eigen::Ref<Eigen::MatrixXd> A,
                 Eigen::Ref<Eigen::VectorXd> b) {
  const Eigen::Index n = mu.size();
  require_finite_matrix("delassus", delassus, 2 * n, 2 * n);
  require_finite_vector("free_acceleration", free_acceleration, 2 * n);
  require_nonnegative_vector("mu", mu, n);
  require_shape("A", A.rows(), A.cols(), 3 * n, 3 * n);
  require_size("b", b.size(), 3 * n);
  // Blocks of G: NN = G(0:n, 0:n), NT = G(0:n, n:2n), TN = G(n:2n, 0:n), TT.
  A.setZero();
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < n; ++i) {
      // column block lambda_N: G_.N - G_.T mu  (lambda_T = x2 - mu lambda_N)
      A(i, j) = delassus(i, j) - delassus(i, n + j) * mu[j];
      A(n + i, j) = delassus(n + i, j) - delassus(n + i, n + j) * mu[j];
      // column block x2: G_.T
      A(i, n + j) = delassus(i, n + j);
      A(n + i, n + j) = delassus(n + i, n + j);
    }
    A(n + j, 2 * n + j) = 1.0;        // g_T''+ = ... + g_T''-
    A(2 * n + j, j) = 2.0 * mu[j];    // x1 = 2 mu lambda_N - x2
    A(2 * n + j, n + j) = -1.0;
    b[j] = free_acceleration[j];
    b[n + j] = free_acceleration[n + j];
    b[2 * n + j] = 0.0;
  }
}

void contact_state(const Eigen::Ref<const Eigen::VectorXd>& z,
                   const Eigen::Ref<const Eigen::VectorXd>& w,
                   const Eigen::Ref<const Eigen::VectorXd>& mu,
                   Eigen::Ref<Eigen::VectorXd> normal_force,
                   Eigen::Ref<Eigen::VectorXd> friction_force,
                   Eigen::Ref<Eigen::VectorXd> normal_acceleration,
                   Eigen::Ref<Eigen::VectorXd> tangential_acceleration) {
  const Eigen::Index n = mu.size();
  require_nonnegative_vector("mu", mu, n);
  require_finite_vector("z", z, 3 * n);
  require_finite_vector("w", w, 3 * n);
  require_size("normal_force", normal_force.size(), n);
  require_size("friction_force", friction_force.size(), n);
  require_size("normal_acceleration", normal_acceleration.size(), n);
  require_size("tangential_acceleration", tangential_acceleration.size(), n);
  for (Eigen::Index i = 0; i < n; ++i) {
    normal_force[i] = z[i];
    friction_force[i] = z[n + i] - mu[i] * z[i];
    normal_acceleration[i] = w[i];
    tangential_acceleration[i] = w[n + i] - z[2 * n + i];
  }
}

PlanarContactLcp planar_contact_lcp(const Eigen::Matrix2d& delassus,
                                    const Eigen::Vector2d& free_acceleration, double mu) {
  require_nonnegative_scalar("mu", mu);
  PlanarContactLcp lcp;
  const Eigen::Matrix<double, 1, 1> mu_vector(mu);
  contact_lcp(delassus, free_acceleration, mu_vector, lcp.A, lcp.b);
  return lcp;
}

ContactState planar_contact_state(const Eigen::Ref<const Eigen::VectorXd>& z,
                                  const Eigen::Ref<const Eigen::VectorXd>& w, double mu) {
  require_nonnegative_scalar("mu", mu);
  ContactState state;
  const Eigen::Matrix<double, 1, 1> mu_vector(mu);
  Eigen::Map<Eigen::VectorXd> normal_force(&state.normal_force, 1);
  Eigen::Map<Eigen::VectorXd> friction_force(&state.friction_force, 1);
  Eigen::Map<Eigen::VectorXd> normal_acceleration(&state.normal_acceleration, 1);
  Eigen::Map<Eigen::VectorXd> tangential_acceleration(&state.tangential_acceleration, 1);
  contact_state(z, w, mu_vector, normal_force, friction_force, normal_acceleration,
                tangential_acceleration);
  return state;
}

}  // namespace leadscrew::friction
