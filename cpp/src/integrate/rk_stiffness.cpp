// Stiffness detection of the explicit Runge-Kutta engine (rk_stiffness.hpp).
#include "leadscrew/integrate/rk_stiffness.hpp"

#include <cmath>
#include <vector>

#include "leadscrew/integrate/explicit_rk.hpp"

namespace leadscrew::integrate {

namespace {
// R(-x) of the explicit method: the stages of y' = -x y from y = 1.
double stability_function(const ButcherTableau& t, double x, std::vector<double>& stage) {
  const int s = t.stages;
  double result = 1.0;
  for (int i = 0; i < s; ++i) {
    double sum = 0.0;
    for (int j = 0; j < i; ++j) sum += t.a[i * s + j] * stage[j];
    stage[i] = 1.0 - x * sum;
    result -= x * t.b[i] * stage[i];
  }
  return result;
}
}  // namespace

double real_stability_boundary(const ButcherTableau& tableau) {
  // Scanned in steps of 1e-3 (every explicit method's boundary lies below
  // 2 s^2 for s stages), then bisected to 1e-12.
  std::vector<double> stage(static_cast<std::size_t>(tableau.stages));
  const double limit = 2.0 * tableau.stages * tableau.stages;
  double inside = 0.0;
  while (inside < limit && std::abs(stability_function(tableau, inside + 1e-3, stage)) <= 1.0)
    inside += 1e-3;
  double outside = inside + 1e-3;
  for (int i = 0; i < 60 && outside - inside > 1e-12; ++i) {
    const double middle = 0.5 * (inside + outside);
    (std::abs(stability_function(tableau, middle, stage)) <= 1.0 ? inside : outside) = middle;
  }
  return inside;
}

int stiffness_stage(const ButcherTableau& t) {
  const int s = t.stages;
  for (int j = s - 1; j > 0; --j) {
    if (t.c[j] != 1.0) continue;
    for (int l = 0; l < s; ++l)
      if (t.a[j * s + l] != t.b[l]) return j;
  }
  return -1;
}

bool StiffnessTest::stiff_after(const ButcherTableau& t, long accepted, int n, const double* k,
                                const double* f_end) {
  const int j = t.stiffness_stage;
  if (j < 0) return false;
  const int s = t.stages;
  double rate = 0.0, distance = 0.0;
  for (int r = 0; r < n; ++r) {
    double d = 0.0;  // (y_n+1 - Y_j) / h
    for (int l = 0; l < s; ++l) d += (t.b[l] - t.a[j * s + l]) * k[l * n + r];
    const double f = f_end[r] - k[j * n + r];
    rate += f * f;
    distance += d * d;
  }
  if (!(distance > 0.0)) return false;
  // h |f_end - k_j| / |y_n+1 - Y_j| with y_n+1 - Y_j = h d.
  h_lambda_ = std::sqrt(rate / distance);
  if (h_lambda_ > t.stiffness_threshold) {
    non_stiff_ = 0;
    if (++suspected_ == kStiffSteps) stiff_since_ = accepted;
    return suspected_ >= kStiffSteps;
  }
  if (++non_stiff_ >= kNonStiffSteps) suspected_ = 0;
  return false;
}

}  // namespace leadscrew::integrate
