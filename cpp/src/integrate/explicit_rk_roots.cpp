// ExplicitRungeKutta's root functions (integrate/explicit_rk.hpp): the
// crossing hidden inside the first step after a (re)start, and the location
// of the earliest root in an accepted step, on the dense output and then on
// the exact continuation of the step (RootBracket, dense_root, exact_root).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "leadscrew/integrate/explicit_rk.hpp"

namespace leadscrew::integrate {

namespace {
constexpr double eps = std::numeric_limits<double>::epsilon();
constexpr int root_iterations = 60;
// The first step after a (re)start samples the dense output here for sign
// changes of root functions that started on their surface (hidden_crossing);
// 1/16 catches an excursion off the surface of a sixteenth of the step.
constexpr double hidden_samples[] = {0.0625, 0.25, 0.5, 0.75};
// |g| at the start below this fraction of |g| at the step end: the start
// value is at the level of the function's round-off, its sign unreliable.
constexpr double surface_fraction = 1e-6;
}  // namespace

double ExplicitRungeKutta::hidden_crossing() {
  // A root function whose value at the start of the step is 0 (inactive) or
  // at the level of its round-off (|g| tiny against its value at the step
  // end) has no reliable sign there. After an event that is typical: a gap
  // that closed to rounding error on either side, a normal force that just
  // fell to zero; RootGuard (event_driven.cpp) maps exact zeros to +-1e-200.
  // Such a function can leave its surface and come back within one step (a
  // nut that lifts off a flank and hits it again), and with the same sign at
  // both ends of the step the crossing back is missed: the nut passes through
  // the flank. Small first steps hide this (CVODE, ARKODE), the step size
  // kept across restarts does not. So the first step after a (re)start looks
  // inside for the sign opposite to the one at its end; found at theta, the
  // step is retried up to theta, whose end then shows the sign change (a
  // function that started at exactly 0 then starts the next step with the
  // sign it took, as activate_zero_roots would have given it).
  auto on_surface = [&](int i) {
    const double g0 = g_start_[i], g1 = g_end_[i];
    if (g1 == 0.0) return false;
    if (g0 == 0.0) return true;
    return (g0 > 0.0) == (g1 > 0.0) && std::fabs(g0) <= surface_fraction * std::fabs(g1);
  };
  bool any = false;
  for (int i = 0; i < m_ && !any; ++i) any = on_surface(i);
  if (!any) return 0.0;
  for (const double theta : hidden_samples) {
    interpolate(theta, y_trial_);
    roots_at(t_step_ + theta * h_step_, y_trial_, g_trial_);
    for (int i = 0; i < m_; ++i)
      if (on_surface(i) && g_trial_[i] != 0.0 && (g_trial_[i] > 0.0) != (g_end_[i] > 0.0))
        return theta;
  }
  return 0.0;
}

// The bracket [lo, hi] (offsets from the step's start t_n) of locate_root,
// with all root functions' values at its ends (g_lo, g_hi: the integrator's
// arrays, whose pointers are swapped with g_trial, never the data); a
// function counts if it was active at t_n and changes sign in it. Illinois:
// the value kept at an end is halved when that end is kept twice.
struct ExplicitRungeKutta::RootBracket {
  double*& g_lo;
  double*& g_hi;
  double*& g_trial;
  const double* g_start;
  const double* g_end;
  int m;
  double h, tolerance;
  double lo = 0.0, hi = 0.0;
  double scale_lo = 1.0, scale_hi = 1.0;
  int last_side = 0;

  bool crossing(int i, const double* g_a, const double* g_b) const {
    return g_start[i] != 0.0 && crosses(g_a[i], g_b[i]);
  }
  // The whole step, its ends' values g_start, g_end.
  void reset() {
    std::copy_n(g_start, m, g_lo);
    std::copy_n(g_end, m, g_hi);
    lo = 0.0;
    hi = h;
    scale_lo = scale_hi = 1.0;
    last_side = 0;
  }
  // The earliest secant root among the bracketed functions, and which one.
  double earliest_secant(int* which) const {
    double best = hi;
    *which = -1;
    for (int i = 0; i < m; ++i) {
      if (!crossing(i, g_lo, g_hi)) continue;
      const double a = scale_lo * g_lo[i], b = scale_hi * g_hi[i];
      const double estimate = (b == a) ? 0.5 * (lo + hi) : lo - a * (hi - lo) / (b - a);
      if (*which < 0 || estimate < best) {
        best = estimate;
        *which = i;
      }
    }
    return best;
  }
  // Moves one end of the bracket to tau (values in g_trial); true if hi moved.
  bool update(double tau) {
    bool left = false;
    for (int i = 0; i < m && !left; ++i) left = crossing(i, g_lo, g_trial);
    if (left) {
      hi = tau;
      std::swap(g_hi, g_trial);
      scale_hi = 1.0;
      scale_lo = last_side == 1 ? 0.5 * scale_lo : 1.0;
      last_side = 1;
    } else {
      lo = tau;
      std::swap(g_lo, g_trial);
      scale_lo = 1.0;
      scale_hi = last_side == -1 ? 0.5 * scale_hi : 1.0;
      last_side = -1;
    }
    return left;
  }
  double clamp(double tau) const {
    return std::min(hi - 0.5 * tolerance, std::max(lo + 0.5 * tolerance, tau));
  }
};

void ExplicitRungeKutta::locate_root() {
  const double t_n = t_step_;
  const double h = h_step_;
  const double tolerance = 4.0 * eps * std::max(std::fabs(t_n + h), h);
  RootBracket bracket{g_lo_, g_hi_, g_trial_, g_start_, g_end_, m_, h, tolerance};
  int active = -1;
  double slope = 0.0;
  const double tau_dense = dense_root(bracket, active, slope);
  exact_root(bracket, tau_dense, active, slope);
  settle_at_root(bracket);
}

// 1. On the dense output (no rhs calls): Illinois until the bracket is
// below 1e-6 of the step; the exact stage takes over from its secant
// root. (Down to 1e-10 of the step, as before, Illinois took three to
// four more evaluations per root and Newton on the exact continuation
// none fewer: the same rhs evaluations and event times in the block and
// rigid benchmarks; 15k of the block's 416k instructions in its event
// loop, 47k of the rigid drive's 1,168k; issue 17's benchmark.)
// Returns the secant root, its function (active) and its slope there.
double ExplicitRungeKutta::dense_root(RootBracket& b, int& active, double& slope) {
  const double t_n = t_step_;
  const double h = b.h;
  const double tolerance = b.tolerance;
  b.reset();
  active = -1;
  const double dense_tolerance = std::max(tolerance, 1e-6 * h);
  // A secant that lands on an end of the bracket moves a tenth of it inside
  // (as CVODE's root finder does). A function that starts on its surface
  // starts at +-1e-200 (RootGuard, event_driven.cpp): against its value at
  // the other end the secant stays at that end, the bracket shrank by half a
  // tolerance per iteration, and Illinois's halving needs some 600 of them
  // to make up 190 orders of magnitude; with 60 the step's end was taken for
  // the root (a rigid nut's flight off a flank and back within one step:
  // the impact 1.3 ms late, 0.27 um inside the flank).
  auto inside = [&](double tau) {
    const double width = b.hi - b.lo;
    const double fraction = width > 5.0 * dense_tolerance ? 0.1 : 0.5 * dense_tolerance / width;
    if (tau - b.lo < 0.5 * dense_tolerance) return b.lo + fraction * width;
    if (b.hi - tau < 0.5 * dense_tolerance) return b.hi - fraction * width;
    return tau;
  };
  for (int iteration = 0; iteration < root_iterations && b.hi - b.lo > dense_tolerance;
       ++iteration) {
    const double tau = b.clamp(inside(b.earliest_secant(&active)));
    interpolate(tau / h, y_trial_);
    roots_at(t_n + tau, y_trial_, g_trial_);
    b.update(tau);
  }
  const double tau_dense = b.earliest_secant(&active);
  // Its slope there, by central differences on the dense output.
  slope = 0.0;
  {
    const double delta = std::max(1e-7 * h, 16.0 * tolerance);
    const double a = std::max(0.0, tau_dense - delta), c = std::min(h, tau_dense + delta);
    interpolate(a / h, y_trial_);
    roots_at(t_n + a, y_trial_, g_trial_);
    const double g_a = g_trial_[active];
    interpolate(c / h, y_trial_);
    roots_at(t_n + c, y_trial_, g_trial_);
    slope = (g_trial_[active] - g_a) / (c - a);
  }
  return tau_dense;
}

// 2. On the exact continuation phi(tau) = g(t_n + tau, Phi_tau(y_n)):
// Newton from the dense root (slope from the dense output, then secants
// through the last two exact values), aimed a tolerance past the root so
// that it lands where g has changed sign; done when such a point is within
// two tolerances of Newton's root. Kept inside the bracket, Illinois when
// Newton leaves it, is for another function, or takes too long. Usually
// two evaluations of phi.
// Safeguard: where an iteration does not halve the bracket twice in a row
// (a function that starts on its surface at +-1e-200 pins the secant to
// that end, and the bracket shrank by half a tolerance per iteration: a
// slip that reversed 7 ns into a 0.28 ms step was located at the step's
// end, and friction did positive work for the whole step), the next point
// is the dense bracket's far end widened by its width, then bisection: the
// bracket then halves at least every other iteration, and the loop's
// bound (far above the ~2 log2(h / tolerance) this needs) is never reached
// with a bracket wider than the tolerance (checked: an error, never an
// event at the wrong time). A Newton step whose correction at least halves
// is progress although the bracket stays wide (Newton approaches from one
// side, the far end does not move): counted as a stall, it was cut off by
// bisection after two steps, and each slip->stick of a rigid drive took
// some 13 evaluations of phi (9 stages each) instead of 3 or 4.
void ExplicitRungeKutta::exact_root(RootBracket& b, double tau_dense, int active,
                                    double slope) {
  const double t_n = t_step_;
  const double tolerance = b.tolerance;
  const double dense_far = b.hi + std::max(b.hi - b.lo, tolerance);
  bool dense_far_tried = false;
  b.reset();
  std::copy_n(y_new_, n_, y_);    // the state at hi
  std::copy_n(k_, n_, k_trial_);  // stage 1: f(t_n, y_n)
  double tau = tau_dense;
  double previous_tau = -1.0, previous_g = 0.0;
  constexpr int newton_iterations = 8;
  constexpr int exact_iterations = 400;
  int stalled = 0;
  double last_width = b.hi - b.lo;
  double last_correction = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < exact_iterations && b.hi - b.lo > tolerance; ++iteration) {
    tau = b.clamp(tau);
    if (!stages(t_n, y_start_, tau, k_trial_, y_trial_))
      fail("RK_RHSFUNC_FAIL",
           "the right-hand side returned a non-finite value (NaN or inf) while locating a root",
           "check the model near the event");
    roots_at(t_n + tau, y_trial_, g_trial_);
    const double g_tau = g_trial_[active];
    const bool hi_moved = b.update(tau);
    if (hi_moved) std::copy_n(y_trial_, n_, y_);
    int earliest = -1;
    double next = b.earliest_secant(&earliest);
    if (earliest < 0) break;  // not reached: the bracket always holds a crossing
    bool newton_progress = false;
    if (earliest == active && iteration < newton_iterations) {
      const double local_slope = previous_tau >= 0.0 && tau != previous_tau
                                     ? (g_tau - previous_g) / (tau - previous_tau)
                                     : slope;
      if (local_slope != 0.0 && std::isfinite(local_slope)) {
        const double correction = -g_tau / local_slope;
        if (hi_moved && std::fabs(correction) <= 2.0 * tolerance) return;  // converged
        const double newton = tau + correction + tolerance;
        if (newton > b.lo && newton < b.hi) {
          next = newton;
          newton_progress = std::fabs(correction) <= 0.5 * last_correction;
        }
        last_correction = std::fabs(correction);
      }
    }
    previous_tau = tau;
    previous_g = g_tau;
    if (earliest != active) previous_tau = -1.0;  // that secant would mix two functions
    active = earliest;
    const double width = b.hi - b.lo;
    stalled = width > 0.5 * last_width && !newton_progress ? stalled + 1 : 0;
    last_width = width;
    if (stalled >= 2) {
      next = !dense_far_tried && dense_far > b.lo && dense_far < b.hi ? dense_far
                                                                      : 0.5 * (b.lo + b.hi);
      dense_far_tried = true;
      stalled = 0;
      previous_tau = -1.0;  // a secant through the last point would pull back to the end
    }
    tau = next;
  }
  if (b.hi - b.lo > tolerance)
    fail("RK_ROOT_FAIL",
         "an event could not be located: the bracket of its root function is still " +
             std::to_string(b.hi - b.lo) + " s wide",
         "tighten rtol and atol, and please report the scene");
}

// The root: the bracket end where g has changed sign (or is 0); y_ holds
// the state there (exact_root), t_ moves there.
void ExplicitRungeKutta::settle_at_root(const RootBracket& b) {
  for (int i = 0; i < m_; ++i)
    root_info_[i] = b.crossing(i, g_lo_, g_hi_) ? (g_start_[i] < 0.0 ? 1 : -1) : 0;
  if (b.hi == b.h) {
    t_ = t_end_;  // exactly t_out when the step landed on it
    std::copy_n(f_end_, n_, f_current_);
    first_stage_valid_ = true;
  } else {
    t_ = t_step_ + b.hi;
    first_stage_valid_ = false;
  }
  std::copy_n(g_hi_, m_, g_start_);
  // A function that landed exactly on 0 at the root must not stay inactive
  // if the integration continues without a restart.
  activate_zero_roots();
  probe_step_ = true;
}

}  // namespace leadscrew::integrate
