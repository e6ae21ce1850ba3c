// The core's own explicit embedded Runge-Kutta engine: allocation-free after
// initialize, with a continuous extension (dense output) and event location
// to near machine precision.
//
// Why it exists next to ARKODE: the event-driven schemes restart the
// integrator at every stick/slip transition and integrate tiny systems
// (2..10 states). SUNDIALS spends ~0.7-1.3 us per step and 13-22 us per
// restart on a 2-state problem (benchmarks/integrate); this engine spends a
// few ns per stage beyond the right-hand side itself and keeps the step size
// across restarts.
//
// Event location. Root functions g are evaluated at every step end; a sign
// change between step ends brackets a root. As in CVODE, a function that is
// exactly 0 at a (re)start takes the sign it has just after it along the
// solution, so a restart on the switching surface does not report that root
// again but sees the next crossing; if it is 0 there too it stays inactive
// for the step. A function that starts the step after a (re)start at 0 or
// at its round-off level (after an event its sign there is noise) may leave
// its surface and cross back within that step, which the step ends do not
// show: that first step samples its dense output for the opposite sign and,
// if found, is retried up to the sample (hidden_crossing). The root is
// found in two stages:
//   1. on the dense output (no right-hand-side calls): Illinois iteration for
//      every bracketed function; the earliest root is the initial guess;
//   2. on the exact continuation phi(tau) = g(t_n + tau, Phi_tau(y_n)), where
//      Phi_tau is one step of the method of size tau (as accurate as the
//      method itself, unlike an interpolant): safeguarded Newton iteration
//      with the slope from the dense output, bracketed, with an Illinois step
//      whenever Newton leaves the bracket or stalls. Phi_h(y_n) is y_n+1
//      exactly, so the bracket from the step ends stays consistent.
// The returned time is the bracket end where g has already changed sign (or
// is 0), within a few ulp of t of the root of the computed solution.
//
// Failures raise SimulationError with flag names in SUNDIALS' style:
//   RK_TOO_MUCH_WORK  max_steps steps since initialize
//   RK_STIFF          the step size held by the method's stability (Hairer's
//                     stiffness test, rk_stiffness.hpp) for 1,000 steps, and
//                     the rest to t_out beyond what max_steps leaves at it
//   RK_ERR_FAILURE    the step fell to the roundoff level of t, or 100 error
//                     test failures in a row
//   RK_RHSFUNC_FAIL   f not finite at the current state, or in 64 trial steps
//                     since the last (re)start despite step reduction, or with
//                     a fixed step
//   RK_RTFUNC_FAIL    a root function not finite
#pragma once

#include <Eigen/Core>
#include <exception>
#include <string>
#include <vector>

#include "leadscrew/integrate/ode.hpp"
#include "leadscrew/integrate/rk_stiffness.hpp"

namespace leadscrew::integrate {

// An explicit embedded pair with its continuous extension.
struct ButcherTableau {
  std::string name;
  int stages = 0;
  int order = 0;           // of the propagated solution
  int embedded_order = 0;  // of the error estimator's companion
  // The last stage is f(t_n + h, y_n+1) (first same as last): it becomes the
  // first stage of the next step.
  bool fsal = false;
  std::vector<double> a;  // stages x stages, row-major, strictly lower triangular
  std::vector<double> b;  // weights of the propagated solution
  std::vector<double> e;  // b - b_embedded: the local error estimate is h sum e_j k_j
  std::vector<double> c;  // nodes
  // Continuous extension on [t_n, t_n + h], theta in [0, 1]:
  //   y(t_n + theta h) = y_n + h (sum_j w_j(theta) k_j + w_end(theta) f(t_n + h, y_n+1)).
  // Fills w[0..stages) and *w_end.
  void (*dense_weights)(double theta, const ButcherTableau& tableau, double* w,
                        double* w_end) = nullptr;
  // Hairer's stiffness test (rk_stiffness.hpp), set by checked_tableau: the
  // stage it compares with f(t_n+1, y_n+1) (-1: none, no test) and the h
  // lambda beyond which a step counts as held by stability (0.98 of the
  // stability boundary on the negative real axis).
  int stiffness_stage = -1;
  double stiffness_threshold = 0.0;
};

// Cubic Hermite interpolation between (y_n, f_n) and (y_n+1, f_n+1): a
// continuous extension of order 3 for any tableau (f_n is stage 1).
void hermite_dense_weights(double theta, const ButcherTableau& tableau, double* w,
                           double* w_end);

// Throws InvalidArgument if the tableau is inconsistent (sizes, explicitness,
// row sums a_i. = c_i, sum b = 1, sum e = 0, FSAL rows).
void check_tableau(const ButcherTableau& tableau);
// The tableau, after check_tableau, with its stiffness test's data.
ButcherTableau checked_tableau(ButcherTableau tableau);

class ExplicitRungeKutta final : public Integrator {
 public:
  // Throws InvalidArgument for max_order != 0 (a fixed-order method). The
  // tableau is kept by reference (the methods' tableaux are static): it
  // must outlive the integrator, and have passed check_tableau (the
  // methods' factories, dopri5_tableau() and verner6_tableau(), check theirs
  // once when they build them, not per integrator).
  ExplicitRungeKutta(const ButcherTableau& tableau, const IntegratorOptions& options);
  // The constructor's checks of `options` for `tableau`, without building it.
  static void check_options(const ButcherTableau& tableau, const IntegratorOptions& options);

  std::string name() const override { return tableau_.name; }
  void initialize(OdeSystem& system, double t0,
                  const Eigen::Ref<const Eigen::VectorXd>& y0) override;
  void reinitialize(double t0, const Eigen::Ref<const Eigen::VectorXd>& y0) override;
  AdvanceResult advance(double t_out, Eigen::Ref<Eigen::VectorXd> y,
                        bool one_step = false) override;
  const std::vector<int>& root_info() const override { return root_info_; }
  IntegratorStats stats() const override { return stats_; }

  // The continuous extension of the last accepted step.
  void dense_output(double t, Eigen::Ref<Eigen::VectorXd> y) override;

 private:
  enum class StepOutcome { accepted, rejected, nonfinite };

  void start(double t0, const Eigen::Ref<const Eigen::VectorXd>& y0);
  double initial_step();
  // mean of (v_i / (atol + rtol max(|y_a,i|, |y_b,i|)))^2
  double weighted_mean_square(const double* v, const double* y_a, const double* y_b) const;
  // Stages 2..s of a step of size h from (t, y) with stage 1 in k[0..n);
  // y_out = y + h sum b_j k_j. Returns false if a value is not finite.
  bool stages(double t, const double* y, double h, double* k, double* y_out);
  StepOutcome attempt(double h, double* error_square);
  StepOutcome attempt_stages(double h, double* error_square);  // attempt without the catch
  // Chooses the fixed-size kernels for (n_, s_), if there are any, and the
  // system's own stage loop (OdeSystem::explicit_rk_stages), if it has one.
  void select_kernels(const OdeSystem& system);
  // out = base + h sum_j coefficients_j k_j over all stages (base null: 0).
  void combine_stages(const double* base, double h, const double* coefficients, const double* k,
                      double* out) const;
  void interpolate(double theta, double* y_out);
  void roots_at(double t, const double* y, double* g);
  void activate_zero_roots();
  // In the first step after a (re)start: the fraction theta of the step at
  // which a root function that started on its surface has left it to the
  // side opposite to its sign at the step end (crossed twice), 0 if none.
  double hidden_crossing();
  // After an accepted step with a sign change of some root function between
  // g_start_ and g_end_: locates the earliest root; y_ and t_ move there
  // (explicit_rk_roots.cpp: on the dense output, then on the step's exact
  // continuation, in a RootBracket).
  void locate_root();
  struct RootBracket;
  double dense_root(RootBracket& bracket, int& active, double& slope);
  void exact_root(RootBracket& bracket, double tau_dense, int active, double slope);
  void settle_at_root(const RootBracket& bracket);
  // Sign change of a root function from g0 (start of the interval) to g1: g0
  // exactly 0 means inactive (a restart on the switching surface).
  static bool crosses(double g0, double g1) noexcept {
    return (g0 < 0.0 && g1 >= 0.0) || (g0 > 0.0 && g1 <= 0.0);
  }
  // advance's parts: the step budget and first stage, the next step's
  // size, a rejected step, an accepted one (false: retried up to a hidden
  // crossing), the PI controller's next step size.
  void prepare_first_stage();
  double next_step_size(double t_out, bool fixed, double& wanted, bool& to_end);
  void reject_step(StepOutcome outcome, double h, bool fixed, float exponent, float log_error,
                   int& rejections);
  bool accept_step(double h, double t_new, int& hidden_retries);
  void control_step_size(double h, float exponent, float log_error, int rejections,
                         bool to_end, double wanted);
  // Raises RK_STIFF where a stiff problem cannot get from t to t_out
  // within max_steps.
  void stop_if_stiff(double h, double t, double t_out) const;
  [[noreturn]] void fail(const std::string& flag, const std::string& meaning,
                         const std::string& hint) const;

  const ButcherTableau& tableau_;
  const IntegratorOptions options_;
  OdeSystem* system_ = nullptr;
  int n_ = 0;
  int m_ = 0;  // root functions
  int s_ = 0;

  double t_ = 0.0;
  // Proposal for the next step: options.first_step (or an estimate) at
  // initialize, then the controller's; kept across reinitialize.
  double h_ = 0.0;
  double t_step_ = 0.0;     // start of the last accepted step (dense output)
  double h_step_ = 0.0;     // its size
  double t_end_ = 0.0;      // its end (t_out exactly when it landed there)
  bool first_stage_valid_ = false;  // f_current_ = f(t_, y_)
  bool step_available_ = false;     // a step for dense_output exists
  bool probe_step_ = false;         // the next step is the first after a (re)start
  float log_error_old_ = 0.0f;      // log of the previous error norm (PI controller)
  int nonfinite_count_ = 0;
  StiffnessTest stiffness_;  // Hairer's test (rk_stiffness.hpp)
  // The last RefusedState a trial stage raised (null: none since the last
  // accepted step): rejected as a non-finite stage, raised where shorter
  // steps meet it too.
  std::exception_ptr outside_;

  // One allocation (initialize) holds every array below; the pointers are
  // swapped, never the data. y_start_, k_ (stages), y_new_ and
  // f_end_ = f(t_n+1, y_n+1) describe the last accepted step (dense
  // output); f_current_ = f(t_, y_) is the next step's first stage.
  std::vector<double> workspace_;
  double *y_ = nullptr, *y_start_ = nullptr, *y_new_ = nullptr, *y_stage_ = nullptr,
         *y_trial_ = nullptr, *k_ = nullptr, *k_trial_ = nullptr, *f_end_ = nullptr,
         *f_current_ = nullptr;
  double *g_start_ = nullptr, *g_end_ = nullptr, *g_lo_ = nullptr, *g_hi_ = nullptr,
         *g_trial_ = nullptr, *weights_ = nullptr;
  std::vector<int> root_info_;
  IntegratorStats stats_;
  // Unrolled kernels for the state size and stage count (select_kernels);
  // null: the generic loops.
  RkStageKernel stage_kernel_ = nullptr;
  void (*combine_kernel_)(const double* base, double h, const double* coefficients,
                          const double* k, double* out) = nullptr;
};

}  // namespace leadscrew::integrate
