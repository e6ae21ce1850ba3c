// Stiffness detection for the explicit Runge-Kutta engine (explicit_rk.hpp),
// Hairer's test of DOPRI5 (Hairer & Wanner, Solving ODE II, IV.2, and the
// code dopri5.f) for any tableau with two evaluations at the node c = 1: the
// last stage at c = 1 whose argument Y_j is not y_n+1, and f(t_n+1, y_n+1)
// (dopri5: stages 6 and 7; Verner 6(5): stage 8 and the next step's first
// stage). Both lie at t_n + h, so
//
//     h lambda ~ h |f(t_n+1, y_n+1) - f(t_n+1, Y_j)| / |y_n+1 - Y_j|
//
// estimates h times the dominant eigenvalue of the Jacobian at no cost
// beyond a difference of the stages already taken (y_n+1 - Y_j =
// h sum_l (b_l - a_jl) k_l). Where h lambda stays near the method's
// stability boundary on the negative real axis, the step size is held by
// stability, not by accuracy: the problem is stiff for this method. Tested
// every kStiffnessInterval accepted steps, and at every step once suspected.
#pragma once

namespace leadscrew::integrate {

struct ButcherTableau;

// Accepted steps between two tests (Hairer's NSTIFF default), the tested
// steps in a row near the boundary that make a problem stiff, and those
// away from it that clear a suspicion (dopri5.f: 15 and 6).
constexpr long kStiffnessInterval = 1000;
constexpr int kStiffSteps = 15;
constexpr int kNonStiffSteps = 6;
// The share of the stability boundary at which a step counts as held by it
// (dopri5.f: 3.25 of DOPRI5's 3.3066).
constexpr double kStiffShareOfBoundary = 0.98;

// The method's stability boundary on the negative real axis: the largest x
// with |R(-x')| <= 1 for every x' in (0, x], R(z) = 1 + z b^T (I - z A)^-1 1
// (explicit: a polynomial of degree `stages`). DOPRI5: 3.3066.
double real_stability_boundary(const ButcherTableau& tableau);

// The last stage at c = 1 whose row of A is not b (-1: none, no test).
int stiffness_stage(const ButcherTableau& tableau);

class StiffnessTest {
 public:
  void reset() {
    suspected_ = 0, non_stiff_ = 0, h_lambda_ = 0.0, stiff_since_ = 0;
    countdown_ = kStiffnessInterval;
  }
  // Whether the step just accepted is tested: every kStiffnessInterval-th,
  // and every one while suspected (inline: one decrement per step).
  bool due() {
    if (suspected_ > 0) return true;
    if (--countdown_ > 0) return false;
    countdown_ = kStiffnessInterval;
    return true;
  }
  // After the `accepted`-th accepted step (one that is due), with its
  // stages k (stage-major, n states each) and f_end = f(t + h, y_new): true
  // where the problem has now looked stiff for kStiffSteps tested steps in a
  // row.
  bool stiff_after(const ButcherTableau& tableau, long accepted, int n, const double* k,
                   const double* f_end);
  // The last estimate of h lambda (tableau.stiffness_threshold: where a step
  // counts as held by stability).
  double h_lambda() const { return h_lambda_; }
  // The accepted steps since the problem was found stiff (kStiffSteps
  // tested steps in a row), at the `accepted`-th.
  long stiff_steps(long accepted) const { return accepted - stiff_since_; }

 private:
  int suspected_ = 0;
  int non_stiff_ = 0;
  double h_lambda_ = 0.0;
  long stiff_since_ = 0;
  long countdown_ = kStiffnessInterval;
};

}  // namespace leadscrew::integrate
