#include "leadscrew/integrate/rk_dopri5.hpp"

namespace leadscrew::integrate {

namespace {
// Weights of the continuous extension (Hairer, Norsett & Wanner, Solving ODE
// I, eq. (6.12) and the dense output of their code DOPRI5).
constexpr double d[7] = {-12715105075.0 / 11282082432.0, 0.0,
                         87487479700.0 / 32700410799.0,  -10690763975.0 / 1880347072.0,
                         701980252875.0 / 199316789632.0, -1453857185.0 / 822651844.0,
                         69997945.0 / 29380423.0};

// y(theta) = y_n + h [theta D + theta (1 - theta) (k1 - D)
//            + theta^2 (1 - theta) (2 D - k1 - k7) + theta^2 (1 - theta)^2 sum d_j k_j]
// with D = sum b_j k_j (so that y(1) = y_n+1, y'(0) = k1, y'(1) = k7).
void dopri5_dense_weights(double theta, const ButcherTableau& tableau, double* w,
                          double* w_end) {
  const double u = 1.0 - theta;
  const double p1 = theta, p2 = theta * u, p3 = theta * theta * u, p4 = p3 * u;
  for (int j = 0; j < 7; ++j) {
    const double b = tableau.b[j];
    const double e1 = j == 0 ? 1.0 : 0.0, e7 = j == 6 ? 1.0 : 0.0;
    w[j] = p1 * b + p2 * (e1 - b) + p3 * (2.0 * b - e1 - e7) + p4 * d[j];
  }
  *w_end = 0.0;  // f(t_n+1, y_n+1) is stage 7
}

ButcherTableau make_dopri5() {
  ButcherTableau t;
  t.name = "rk_dopri5";
  t.stages = 7;
  t.order = 5;
  t.embedded_order = 4;
  t.fsal = true;
  t.c = {0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0};
  t.a.assign(49, 0.0);
  const double rows[7][6] = {
      {},
      {1.0 / 5.0},
      {3.0 / 40.0, 9.0 / 40.0},
      {44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0},
      {19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0},
      {9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0},
      {35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0}};
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < i; ++j) t.a[i * 7 + j] = rows[i][j];
  t.b = {35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0, 0.0};
  const double b_embedded[7] = {5179.0 / 57600.0,    0.0,           7571.0 / 16695.0, 393.0 / 640.0,
                                -92097.0 / 339200.0, 187.0 / 2100.0, 1.0 / 40.0};
  t.e.resize(7);
  for (int j = 0; j < 7; ++j) t.e[j] = t.b[j] - b_embedded[j];
  t.dense_weights = &dopri5_dense_weights;
  return t;
}
}  // namespace

const ButcherTableau& dopri5_tableau() {
  static const ButcherTableau tableau = checked_tableau(make_dopri5());
  return tableau;
}

}  // namespace leadscrew::integrate
