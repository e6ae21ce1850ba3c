#include "leadscrew/integrate/explicit_rk.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/run_monitor.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/integrate/integrator_checks.hpp"
#include "leadscrew/integrate/rk_stage_kernels.hpp"

namespace leadscrew::integrate {

namespace {
constexpr double eps = std::numeric_limits<double>::epsilon();
// Step size control (Hairer, Norsett & Wanner, Solving ODE I, II.4 and the
// PI stabilization of IV.2): safety factor, bounds of the step ratio and
// the PI weight of the previous error.
constexpr double safety = 0.9;
constexpr double shrink_limit = 0.2;
constexpr double growth_limit = 10.0;
constexpr float pi_beta = 0.04f;
constexpr int rejection_limit = 100;  // consecutive error-test failures
constexpr int nonfinite_limit = 64;   // non-finite stage values since the last (re)start
// Retries of the first step after a (re)start up to a hidden crossing
// (hidden_crossing, explicit_rk_roots.cpp).
constexpr int hidden_retry_limit = 8;
}  // namespace

void hermite_dense_weights(double theta, const ButcherTableau& tableau, double* w,
                           double* w_end) {
  // y(theta) = h00 y_n + h10 h f_n + h01 y_n+1 + h11 h f_n+1 with
  // y_n+1 = y_n + h sum b_j k_j and f_n = k_1; h00 + h01 = 1.
  const double t2 = theta * theta, t3 = t2 * theta;
  const double h10 = t3 - 2.0 * t2 + theta;
  const double h01 = -2.0 * t3 + 3.0 * t2;
  const double h11 = t3 - t2;
  for (int j = 0; j < tableau.stages; ++j) w[j] = h01 * tableau.b[j];
  w[0] += h10;
  *w_end = h11;
}

void check_tableau(const ButcherTableau& t) {
  const int s = t.stages;
  const std::string where = "Butcher tableau " + t.name + ": ";
  if (s < 1 || static_cast<int>(t.a.size()) != s * s || static_cast<int>(t.b.size()) != s ||
      static_cast<int>(t.e.size()) != s || static_cast<int>(t.c.size()) != s || !t.dense_weights ||
      t.order < 1 || t.embedded_order < 1)
    throw InvalidArgument(where + "sizes are invalid: must be stages x stages, stages, ...");
  double sum_b = 0.0, sum_e = 0.0;
  for (int i = 0; i < s; ++i) {
    double row = 0.0;
    for (int j = 0; j < s; ++j) {
      if (j >= i && t.a[i * s + j] != 0.0)
        throw InvalidArgument(where + "a is invalid: must be strictly lower triangular");
      row += t.a[i * s + j];
    }
    if (std::fabs(row - t.c[i]) > 1e-14)
      throw InvalidArgument(where + "row " + std::to_string(i) + " is invalid: must sum to c_i");
    sum_b += t.b[i];
    sum_e += t.e[i];
  }
  if (std::fabs(sum_b - 1.0) > 1e-14 || std::fabs(sum_e) > 1e-14)
    throw InvalidArgument(where + "weights are invalid: sum b must be 1, sum e 0");
  if (t.fsal) {
    for (int j = 0; j < s; ++j)
      if (t.a[(s - 1) * s + j] != t.b[j] || t.c[s - 1] != 1.0)
        throw InvalidArgument(where + "FSAL is invalid: last row of a must equal b, c_s = 1");
  }
}

ButcherTableau checked_tableau(ButcherTableau tableau) {
  check_tableau(tableau);
  tableau.stiffness_stage = stiffness_stage(tableau);
  tableau.stiffness_threshold = kStiffShareOfBoundary * real_stability_boundary(tableau);
  return tableau;
}

ExplicitRungeKutta::ExplicitRungeKutta(const ButcherTableau& tableau,
                                       const IntegratorOptions& options)
    : tableau_(tableau), options_(options), s_(tableau.stages) {
  check_options(tableau_, options);
}

void ExplicitRungeKutta::check_options(const ButcherTableau& tableau,
                                       const IntegratorOptions& options) {
  check_fixed_order(options, tableau.name, tableau.order);
}

void ExplicitRungeKutta::fail(const std::string& flag, const std::string& meaning,
                              const std::string& hint) const {
  throw SimulationError(t_, flag + ": " + meaning + " (" + tableau_.name + ")", hint);
}

void ExplicitRungeKutta::initialize(OdeSystem& system, double t0,
                                    const Eigen::Ref<const Eigen::VectorXd>& y0) {
  check_system(system);
  const int n = system.size();
  const int m = system.root_count();
  system_ = nullptr;
  n_ = n;
  m_ = m;
  const std::size_t states = static_cast<std::size_t>(n), stages = static_cast<std::size_t>(s_);
  select_kernels(system);
  workspace_.assign(7 * states + 2 * stages * states + 5 * static_cast<std::size_t>(m) + stages,
                    0.0);
  double* next = workspace_.data();
  auto take = [&next](std::size_t count) {
    double* block = next;
    next += count;
    return block;
  };
  for (double** v : {&y_, &y_start_, &y_new_, &y_stage_, &y_trial_, &f_end_, &f_current_})
    *v = take(states);
  k_ = take(stages * states);
  k_trial_ = take(stages * states);
  for (double** v : {&g_start_, &g_end_, &g_lo_, &g_hi_, &g_trial_}) *v = take(m);
  weights_ = take(stages);
  root_info_.assign(m, 0);
  stats_ = IntegratorStats{};
  stiffness_.reset();
  h_ = options_.first_step;  // 0: estimated at the first step
  system_ = &system;
  start(t0, y0);
}

void ExplicitRungeKutta::reinitialize(double t0, const Eigen::Ref<const Eigen::VectorXd>& y0) {
  check_initialized(system_ != nullptr, "reinitialize");
  start(t0, y0);
  ++stats_.restarts;
}

void ExplicitRungeKutta::start(double t0, const Eigen::Ref<const Eigen::VectorXd>& y0) {
  check_start(t0, y0, n_);
  for (int i = 0; i < n_; ++i) y_[i] = y0[i];
  t_ = t0;
  first_stage_valid_ = false;
  step_available_ = false;
  probe_step_ = true;
  log_error_old_ = std::log(1e-4f);
  nonfinite_count_ = 0;
  outside_ = nullptr;
  std::fill(root_info_.begin(), root_info_.end(), 0);
  // h_ is kept: after an event the previous step size is a better first
  // guess than a fresh estimate (the error test corrects it if not).
  if (m_ > 0) {
    roots_at(t_, y_, g_start_);
    activate_zero_roots();
  }
}

void ExplicitRungeKutta::activate_zero_roots() {
  // A root function exactly 0 here (a restart on its switching surface) gets
  // the sign it takes just after t along the solution, as in CVODE: from an
  // Euler step of 100 ulp. Otherwise it would stay inactive for the whole
  // next step, and a step that leaves and re-crosses the surface (a ball
  // bouncing off the ground) would miss the crossing.
  bool any_zero = false;
  for (int i = 0; i < m_ && !any_zero; ++i) any_zero = g_start_[i] == 0.0;
  if (!any_zero) return;
  if (!first_stage_valid_) {
    system_->rhs(t_, y_, f_current_);
    ++stats_.rhs_evaluations;
    if (!all_finite(f_current_, n_)) return;  // the next step reports it
    first_stage_valid_ = true;
  }
  const double delta = 100.0 * eps * std::max(std::fabs(t_), h_ > 0.0 ? h_ : 1.0);
  for (int i = 0; i < n_; ++i) y_trial_[i] = y_[i] + delta * f_current_[i];
  roots_at(t_ + delta, y_trial_, g_trial_);
  for (int i = 0; i < m_; ++i)
    if (g_start_[i] == 0.0) g_start_[i] = g_trial_[i];
}

void ExplicitRungeKutta::roots_at(double t, const double* y, double* g) {
  system_->roots(t, y, g);
  ++stats_.root_evaluations;
  if (!all_finite(g, m_))
    fail("RK_RTFUNC_FAIL", "a root (event) function returned a non-finite value (NaN or inf)",
         "check the root functions at this state");
}

double ExplicitRungeKutta::weighted_mean_square(const double* v, const double* y_a,
                                                const double* y_b) const {
  double sum = 0.0;
  for (int i = 0; i < n_; ++i) {
    const double scale =
        options_.atol + options_.rtol * std::max(std::fabs(y_a[i]), std::fabs(y_b[i]));
    const double r = v[i] / scale;
    sum += r * r;
  }
  return sum / n_;
}

double ExplicitRungeKutta::initial_step() {
  // Hairer, Norsett & Wanner, Solving ODE I, II.4: h0 from ||y0|| / ||f0||,
  // then from the second derivative estimated with one Euler step.
  const double* f0 = k_;
  const double d0 = std::sqrt(weighted_mean_square(y_, y_, y_));
  const double d1 = std::sqrt(weighted_mean_square(f0, y_, y_));
  double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  if (options_.max_step > 0.0) h0 = std::min(h0, options_.max_step);
  for (int i = 0; i < n_; ++i) y_trial_[i] = y_[i] + h0 * f0[i];
  double* f1 = k_trial_;
  system_->rhs(t_ + h0, y_trial_, f1);
  ++stats_.rhs_evaluations;
  if (!all_finite(f1, n_)) return h0;
  for (int i = 0; i < n_; ++i) y_stage_[i] = f1[i] - f0[i];
  const double d2 = std::sqrt(weighted_mean_square(y_stage_, y_, y_)) / h0;
  const double dmax = std::max(d1, d2);
  const double h1 = dmax <= 1e-15 ? std::max(1e-6, h0 * 1e-3)
                                  : std::pow(0.01 / dmax, 1.0 / (tableau_.order + 1));
  double h = std::min(100.0 * h0, h1);
  if (options_.max_step > 0.0) h = std::min(h, options_.max_step);
  return h;
}

namespace {
// out = base + h sum_j coefficients_j k_j over `count` stages of n states
// (base null: 0), for any sizes; the same arithmetic in the same order as
// rk_kernels::combine (fixed sizes): bit for bit the same values. Zero
// coefficients are not skipped, so that 0 * inf = NaN still flags a
// non-finite stage.
void combine(int n, const double* base, double h, const double* coefficients, int count,
             const double* k, double* out) {
  for (int r = 0; r < n; ++r) out[r] = base ? base[r] : 0.0;
  for (int j = 0; j < count; ++j) {
    const double w = h * coefficients[j];
    const double* kj = k + j * n;
    for (int r = 0; r < n; ++r) out[r] += w * kj[r];
  }
}
}  // namespace

// Kernels for a state size N and a stage count S fixed at compile time (the
// combinations were ~40 % of the engine's instructions for a 4-state
// system); the stages through the virtual rhs.
template <int N, int S>
struct FixedSizeKernels {
  static void combine_all(const double* base, double h, const double* coefficients,
                          const double* k, double* out) {
    rk_kernels::combine<N, S>(base, h, coefficients, k, out);
  }
  static constexpr RkStageKernel stages = &rk_kernels::stage_kernel<OdeSystem, N, S>;
};

void ExplicitRungeKutta::select_kernels(const OdeSystem& system) {
  // The engine's methods (7 stages: Dormand-Prince, 8: Verner 6(5)) on the
  // small systems of the event-driven models; anything else runs the
  // generic loops. A system's own stage loop (its rhs inlined) takes precedence.
  stage_kernel_ = nullptr;
  combine_kernel_ = nullptr;
  auto take = [this](auto kernels) {
    using K = decltype(kernels);
    stage_kernel_ = K::stages;
    combine_kernel_ = &K::combine_all;
  };
  if (n_ == 2 && s_ == 7) take(FixedSizeKernels<2, 7>{});
  if (n_ == 2 && s_ == 8) take(FixedSizeKernels<2, 8>{});
  if (n_ == 4 && s_ == 7) take(FixedSizeKernels<4, 7>{});
  if (n_ == 4 && s_ == 8) take(FixedSizeKernels<4, 8>{});
  if (const RkStageKernel own = system.explicit_rk_stages(s_)) stage_kernel_ = own;
}

void ExplicitRungeKutta::combine_stages(const double* base, double h, const double* coefficients,
                                        const double* k, double* out) const {
  if (combine_kernel_)
    combine_kernel_(base, h, coefficients, k, out);
  else
    combine(n_, base, h, coefficients, s_, k, out);
}


bool ExplicitRungeKutta::stages(double t, const double* y, double h, double* k, double* y_out) {
  // Stage i at y + h sum_j a_ij k_j.
  const int n = n_, s = s_;
  const double* a = tableau_.a.data();
  const double* c = tableau_.c.data();
  if (stage_kernel_) {
    stage_kernel_(*system_, a, c, t, y, h, k, y_stage_);
  } else {
    for (int i = 1; i < s; ++i) {
      combine(n, y, h, a + i * s, i, k, y_stage_);
      system_->rhs(t + c[i] * h, y_stage_, k + i * n);
    }
  }
  stats_.rhs_evaluations += s - 1;
  if (tableau_.fsal)
    std::copy_n(y_stage_, n, y_out);  // the last stage's argument is y + h sum b_j k_j
  else
    combine_stages(y, h, tableau_.b.data(), k, y_out);
  // A NaN or inf in any stage reaches y_out (b_j = 0 or not: 0 * inf is NaN)
  // or, for the last stage of an FSAL pair, the error estimate.
  return all_finite(y_out, n) && (!tableau_.fsal || all_finite(k + (s - 1) * n, n));
}

ExplicitRungeKutta::StepOutcome ExplicitRungeKutta::attempt(double h, double* error_square) {
  try {
    return attempt_stages(h, error_square);
  } catch (const RefusedState&) {
    // A trial state the model refuses (a stage of a step too long put the
    // nut beyond the screw's end, or left the flank no consistent normal
    // force: core/errors.hpp): rejected as a non-finite stage, and raised
    // only where shorter steps meet it too, as the SUNDIALS integrators do
    // (sundials_context.cpp). A fuzz run found flexible drives on
    // rk_verner6 ended at their first step's stage, the nut 15 mm off a
    // screw it never left, and a flexible LuGre drive on rk_dopri5 "jammed"
    // at its first step's last stage (t = 1e-4 s) at every rtol.
    outside_ = std::current_exception();
    return StepOutcome::nonfinite;
  }
}

ExplicitRungeKutta::StepOutcome ExplicitRungeKutta::attempt_stages(double h,
                                                                  double* error_square) {
  if (!stages(t_, y_, h, k_, y_new_)) return StepOutcome::nonfinite;
  *error_square = 0.0;
  if (options_.fixed_step <= 0.0) {
    combine_stages(nullptr, h, tableau_.e.data(), k_, y_trial_);
    // The squared RMS norm (Hairer's error measure, squared: no sqrt needed).
    *error_square = weighted_mean_square(y_trial_, y_, y_new_);
    // NaN: a non-finite stage that only the error estimate uses.
    if (std::isnan(*error_square)) return StepOutcome::nonfinite;
    if (!(*error_square <= 1.0)) return StepOutcome::rejected;
  }
  if (tableau_.fsal) {
    std::copy_n(k_ + (s_ - 1) * n_, n_, f_end_);
  } else {
    // Not wasted: it is the first stage of the next step.
    system_->rhs(t_ + h, y_new_, f_end_);
    ++stats_.rhs_evaluations;
  }
  return all_finite(f_end_, n_) ? StepOutcome::accepted : StepOutcome::nonfinite;
}

void ExplicitRungeKutta::interpolate(double theta, double* y_out) {
  double w_end = 0.0;
  tableau_.dense_weights(theta, tableau_, weights_, &w_end);
  // The same arithmetic as the step: at theta = 1 (w = b) this is y_n+1 bit
  // for bit.
  combine_stages(y_start_, h_step_, weights_, k_, y_out);
  if (w_end != 0.0) {
    const double w = h_step_ * w_end;
    for (int r = 0; r < n_; ++r) y_out[r] += w * f_end_[r];
  }
}

void ExplicitRungeKutta::dense_output(double t, Eigen::Ref<Eigen::VectorXd> y) {
  if (!step_available_ || !(t >= t_step_ && t <= t_step_ + h_step_))
    throw InvalidArgument("t = " + format_value(t) +
                          " is invalid: must lie in the last accepted step [" +
                          format_value(t_step_) + ", " + format_value(t_step_ + h_step_) + "]");
  check_state_size("y", y.size(), n_);
  interpolate((t - t_step_) / h_step_, y_trial_);
  for (int i = 0; i < n_; ++i) y[i] = y_trial_[i];
}

AdvanceResult ExplicitRungeKutta::advance(double t_out, Eigen::Ref<Eigen::VectorXd> y,
                                          bool one_step) {
  check_initialized(system_ != nullptr, "advance");
  check_output_time(t_out, t_);
  check_state_size("y", y.size(), n_);
  std::fill(root_info_.begin(), root_info_.end(), 0);
  const double time_resolution = 8.0 * eps * std::max(std::fabs(t_), std::fabs(t_out));
  if (t_out - t_ <= time_resolution) {
    // Nothing to integrate within the resolution of t (see sundials_integrator.cpp).
    for (int i = 0; i < n_; ++i) y[i] = y_[i];
    t_ = t_out;
    return {t_, AdvanceStatus::reached};
  }

  const bool fixed = options_.fixed_step > 0.0;
  const int q = std::min(tableau_.order, tableau_.embedded_order);
  const float exponent = 1.0f / (q + 1);
  int rejections = 0;  // consecutive
  int hidden_retries = 0;
  // Bounded: every pass either accepts a step (at most max_steps in total) or
  // rejects one (at most rejection_limit in a row, nonfinite_limit in all).
  for (;;) {
    poll_monitor(t_);
    prepare_first_stage();
    double wanted = 0.0;
    bool to_end = false;
    const double h = next_step_size(t_out, fixed, wanted, to_end);

    double error_square = 0.0;
    const StepOutcome outcome = attempt(h, &error_square);
    // log of the error norm for the controller; float precision is plenty for
    // a step-size factor and costs half of double exp/log.
    const float log_error = 0.5f * std::log(static_cast<float>(std::max(error_square, 1e-20)));
    if (outcome != StepOutcome::accepted) {
      reject_step(outcome, h, fixed, exponent, log_error, rejections);
      continue;
    }
    const double t_new = to_end ? t_out : t_ + h;
    if (!accept_step(h, t_new, hidden_retries)) continue;
    if (!fixed && options_.stop_when_stiff && stiffness_.due() &&
        stiffness_.stiff_after(tableau_, stats_.steps, n_, k_, f_end_))
      stop_if_stiff(h, t_new, t_out);
    if (!fixed) control_step_size(h, exponent, log_error, rejections, to_end, wanted);
    rejections = 0;
    outside_ = nullptr;  // (got past it)
    t_end_ = t_new;

    if (m_ > 0) {
      bool any = false;
      for (int i = 0; i < m_ && !any; ++i) any = crosses(g_start_[i], g_end_[i]);
      if (any) {
        locate_root();
        for (int i = 0; i < n_; ++i) y[i] = y_[i];
        return {t_, AdvanceStatus::root_found};
      }
      std::swap(g_start_, g_end_);
    }
    t_ = t_new;
    std::swap(y_, y_new_);
    std::copy_n(f_end_, n_, f_current_);
    if (t_ == t_out || one_step) {
      for (int i = 0; i < n_; ++i) y[i] = y_[i];
      return {t_, AdvanceStatus::reached};
    }
  }
}

// Before a step: the budget of max_steps, and the first stage f(t_, y_)
// (f_current_) where it is not known, copied into k_.
void ExplicitRungeKutta::prepare_first_stage() {
  if (stats_.steps >= options_.max_steps)
    fail("RK_TOO_MUCH_WORK",
         "the total number of internal steps reached max_steps = " +
             std::to_string(options_.max_steps),
         "increase max_steps or check whether the solution blows up; if the step size "
         "collapsed the problem may be stiff: use cvode_bdf (smooth_integrator = \"cvode_bdf\" "
         "inside integrator = \"event_driven\")");
  if (!first_stage_valid_) {
    system_->rhs(t_, y_, f_current_);
    ++stats_.rhs_evaluations;
    if (!all_finite(f_current_, n_))
      fail("RK_RHSFUNC_FAIL", "the right-hand side returned a non-finite value (NaN or inf) "
                              "at the current state",
           "check the model at this state");
    first_stage_valid_ = true;
  }
  std::copy_n(f_current_, n_, k_);
  step_available_ = false;  // k_ is about to be overwritten
}

// The size of the next step: the controller's (or the fixed one), at most
// max_step (wanted), landing exactly on t_out (to_end) where that stretches
// it by up to 1 % rather than leave a sliver.
double ExplicitRungeKutta::next_step_size(double t_out, bool fixed, double& wanted,
                                          bool& to_end) {
  if (h_ <= 0.0) h_ = fixed ? options_.fixed_step : initial_step();
  double h = fixed ? options_.fixed_step : h_;
  if (options_.max_step > 0.0) h = std::min(h, options_.max_step);
  wanted = h;
  to_end = t_ + 1.01 * h >= t_out;
  if (to_end) h = t_out - t_;
  if (h <= 4.0 * eps * std::fabs(t_))
    fail("RK_ERR_FAILURE", "the step size fell to the roundoff level of t",
         "the solution is probably singular or discontinuous here (a blow-up, or a switch "
         "that should be an event with a root function)");
  return h;
}

// A rejected step of size h: a quarter of it after non-finite stages, the
// controller's shrink after a failed error test; bounded in a row and in all.
void ExplicitRungeKutta::reject_step(StepOutcome outcome, double h, bool fixed, float exponent,
                                     float log_error, int& rejections) {
  ++stats_.error_test_failures;
  if (outcome == StepOutcome::nonfinite) {
    if (fixed || ++nonfinite_count_ >= nonfinite_limit) {
      if (outside_) std::rethrow_exception(std::exchange(outside_, nullptr));
      fail("RK_RHSFUNC_FAIL",
           "the right-hand side returned a non-finite value (NaN or inf) " +
               std::to_string(nonfinite_count_ + (fixed ? 1 : 0)) +
               " times, also with reduced step sizes",
           "check the model: it is undefined (NaN/inf) near this state");
    }
    h_ = 0.25 * h;
  } else {
    if (++rejections > rejection_limit)
      fail("RK_ERR_FAILURE",
           "the local error test failed " + std::to_string(rejection_limit) + " times in a row",
           "the solution is probably singular or discontinuous here");
    h_ = h * std::max(shrink_limit,
                      safety * static_cast<double>(std::exp(-exponent * log_error)));
  }
}

// A step of size h that passed the error test, ending at t_new: accepted
// (the dense output's step, the root functions at its end), unless a root
// function that started on its surface crossed it and came back inside the
// step (hidden_crossing): false, h_ set to retry up to the sample.
bool ExplicitRungeKutta::accept_step(double h, double t_new, int& hidden_retries) {
  std::copy_n(y_, n_, y_start_);
  t_step_ = t_;
  h_step_ = h;
  step_available_ = true;
  if (m_ > 0) {
    roots_at(t_new, y_new_, g_end_);
    if (probe_step_ && hidden_retries < hidden_retry_limit) {
      const double theta = hidden_crossing();
      if (theta > 0.0) {
        // Retry up to the sample: its end then shows the sign change.
        ++hidden_retries;
        h_ = theta * h;
        step_available_ = false;
        return false;
      }
    }
    probe_step_ = false;
  }
  ++stats_.steps;
  return true;
}

// PI control: h_new = h * safety * err^-(1/(q+1) - 0.75 beta) * err_old^beta.
void ExplicitRungeKutta::control_step_size(double h, float exponent, float log_error,
                                           int rejections, bool to_end, double wanted) {
  double factor = safety * static_cast<double>(std::exp(-(exponent - 0.75f * pi_beta) *
                                                            log_error +
                                                        pi_beta * log_error_old_));
  factor = std::min(growth_limit, std::max(shrink_limit, factor));
  if (rejections > 0) factor = std::min(factor, 1.0);
  log_error_old_ = std::max(log_error, std::log(1e-4f));
  h_ = h * factor;
  // A step shortened to land on t_out says little about the next one.
  if (to_end) h_ = std::max(h_, wanted);
}

// The problem looked stiff for kStiffSteps tested steps in a row (its step
// size h held by the method's stability, rk_stiffness.hpp): where the
// time from t to t_out at that step size takes more steps than
// max_steps leaves, and the stiffness has lasted for kStiffnessInterval
// steps (or 1 % of max_steps, if less: a short stiff phase is no reason to
// stop), the run would not finish at the step size stability allows: it
// stops now with the hint to use an implicit method, not after max_steps
// steps (a flexible drive on rk_verner6 took over a minute to reach
// RK_TOO_MUCH_WORK). One whose rest fits the budget goes on.
void ExplicitRungeKutta::stop_if_stiff(double h, double t, double t_out) const {
  const double remaining = t_out - t;
  const double steps_needed = remaining / h;
  const double steps_left = static_cast<double>(options_.max_steps - stats_.steps);
  const long lasting = std::min(kStiffnessInterval, options_.max_steps / 100);
  if (!(steps_needed > steps_left) || stiffness_.stiff_steps(stats_.steps) < lasting) return;
  fail("RK_STIFF",
       "the problem is stiff for this explicit method: its step size is held at h = " +
           format_value(h) + " s by the method's stability (h lambda = " +
           format_value(stiffness_.h_lambda()) + " against its stability boundary " +
           format_value(tableau_.stiffness_threshold / kStiffShareOfBoundary) + " over the last " +
           std::to_string(stiffness_.stiff_steps(stats_.steps) + kStiffSteps) +
           " steps), and the " +
           format_value(remaining) + " s left to t = " + format_value(t_out) +
           " would take some " + format_value(steps_needed) + " steps, beyond the " +
           format_value(steps_left) + " that max_steps leaves",
       "use an implicit method, whose step stiffness does not limit: cvode_bdf (simulate's "
       "integrator, or smooth_integrator inside integrator = \"event_driven\"; solve_ode's "
       "method)");
}

}  // namespace leadscrew::integrate
