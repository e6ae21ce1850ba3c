// DriveHybrid (hybrid.hpp): dynamic jamming. Exact Coulomb's Painleve
// paradox (no consistent sign of the flank normal force, or two), eq.
// (3.15)'s ambiguity located by bisection, and the regularized law's fold
// (the branch's denominator reaching zero), followed in the time s.
#include "hybrid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/integrate/ode.hpp"

namespace leadscrew::model::drive {

// The regularized law's Painleve margin at the state set: min over sigma of
// G_NN - sigma kappa G_NT, relative to G_NN (<= 0: both signs of the flank
// normal force consistent, or neither).
double DriveHybrid::fold_margin() const {
  const double kappa = current_kappa();
  return std::min(dynamics_.thread_denominator(1, kappa),
                  dynamics_.thread_denominator(-1, kappa)) /
         dynamics_.delassus_normal();
}

void DriveHybrid::jam_regularized(const std::string& what) const {
  throw JammingError(dynamics_.time(),
                     "dynamic jamming: " + what + "; " +
                         dynamics_.jamming_report(std::abs(current_kappa())),
                     "the drive self-locks dynamically (Painleve paradox of the regularized "
                     "friction law); reduce the friction or change the inertia ratio");
}

// The drive's equations in the time s with dt/ds = S (approach_fold).
class DriveHybrid::FoldApproach final : public integrate::OdeSystem {
 public:
  explicit FoldApproach(DriveHybrid& drive) : drive_(drive) {}
  int size() const override { return drive_.size() + 1; }
  double time() const { return time_; }  // t of the last right-hand side
  void rhs(double /*s*/, const double* z, double* dz) override {
    time_ = z[0];
    drive_.rhs(z[0], z + 1, dz + 1);
    const double denominator = branch();
    dz[0] = denominator;
    for (int k = 1; k < size(); ++k) dz[k] *= denominator;
  }
  int root_count() const override { return 3; }
  void roots(double /*s*/, const double* z, double* g) override {
    drive_.set(z[0], z + 1);
    drive_.solve_current();
    const double relative = branch() / drive_.dynamics_.delassus_normal();
    // The onset, within round-off of G_NN: a branch that approaches it
    // asymptotically in s (reaching it only as t tends to a limit) took a
    // million steps and ended at an 's' of 1178 'seconds'.
    g[0] = relative - 64.0 * std::numeric_limits<double>::epsilon();
    g[1] = 2.0 * kFoldWatch - relative;    // the branch recovers
    g[2] = drive_.t_end_ - z[0];           // the end of the simulation
  }

 private:
  double branch() const {
    return drive_.dynamics_.thread_denominator(drive_.sigma_guess_, drive_.current_kappa());
  }
  DriveHybrid& drive_;
  double time_ = 0.0;
};

// The denominator S of the current branch fell below kFoldWatch G_NN. If it
// reaches zero, the slip velocity stays finite while the acceleration grows
// like 1/S: the trajectory ends there in finite time with a square-root
// singularity, the onset of jamming, which no step in t can cross or
// resolve. In the time s with dt/ds = S the same trajectory is smooth
// through it (dz/ds = S (1, f(t, y)), S f finite), and S = 0 is an ordinary
// root: integrate it from (t, y) until S = 0 (JammingError at that time and
// state, to the integration tolerance), S back above 2 kFoldWatch G_NN or
// t_end (the main integration then continues: no event).
void DriveHybrid::approach_fold(double t, const double* y) {
  // The branch's denominator at or below zero here: the onset is now (in
  // the time s, t would run backwards from here: a JammingError 0.23 s
  // before the run began).
  if (!(dynamics_.thread_denominator(sigma_guess_, current_kappa()) > 0.0))
    jam_regularized("the branch of the flank normal force ends here (its denominator "
                    "G_NN - sigma kappa G_NT is not positive)");
  FoldApproach fold(*this);
  integrate::IntegratorOptions options;
  options.rtol = integrator_options_.rtol;
  options.atol = integrator_options_.atol;
  options.max_steps = integrator_options_.max_steps;
  options.stop_when_stiff = false;  // (s_end below is a bound, not an end)
  std::unique_ptr<integrate::Integrator> integrator =
      integrate::make_integrator("rk_verner6", options);
  Eigen::VectorXd z(size() + 1);
  z[0] = t;
  for (int k = 0; k < size(); ++k) z[k + 1] = y[k];
  const int saved_sigma = sigma_guess_;
  integrator->initialize(fold, 0.0, z);
  // dt/ds >= S, which stays above zero until the onset: every s beyond
  // (t_end - t) / S_min reaches t_end; S_min is only bounded by the root.
  const double s_end = 1e12 * (t_end_ - t + 1.0) / dynamics_.delassus_normal();
  integrate::AdvanceResult step;
  try {
    step = integrator->advance(s_end, z);
  } catch (const JammingError&) {
    throw;
  } catch (const SimulationError& e) {
    // The integrator's time is s: report the drive's own, t.
    throw SimulationError(fold.time(), e.reason(),
                          "while following the regularized law toward its Painleve regime");
  }
  if (step.status == integrate::AdvanceStatus::root_found && integrator->root_info()[0] != 0) {
    set(z[0], z.data() + 1);
    solve_current();
    jam_regularized("the branch of the flank normal force ends (its denominator "
                    "G_NN - sigma kappa G_NT reaches zero, the acceleration grows without "
                    "bound)");
  }
  sigma_guess_ = saved_sigma;
  set(t, y);
}

// Eq. (3.15) has `count` consistent flank forces at the state set. For the
// rigid drive (no springs, no dampers) they depend on the time alone (the
// loads; the law does not depend on the velocity), so the onset of the
// ambiguity lies between the last time with one solution and now: located
// by bisection on the count, to round-off. (A flexible drive's depend on
// its state: raised where first seen, at the integrator's resolution.)
void DriveHybrid::jam_acceleration_law(int count) {
  double onset = dynamics_.time();
  if (model_.elements().forces.empty() && last_unique_time_ < onset) {
    const CoordinateVector q = q_, v = v_;
    double low = last_unique_time_, high = onset;
    for (int iteration = 0; iteration < 200 && high - low > 2.0 * std::numeric_limits<double>::epsilon() * std::abs(high); ++iteration) {
      const double middle = 0.5 * (low + high);
      dynamics_.set_state(middle, q, v);
      const int n = dynamics_.solve(spec(sigma_guess_)).consistent_solutions;
      (n == 1 ? low : high) = middle;
      if (n != 1) count = n;
    }
    onset = high;
    dynamics_.set_state(onset, q, v);
  }
  throw JammingError(
      onset,
      "dynamic jamming: eq. (3.15) admits " + std::to_string(count) +
          " consistent flank forces from here: its friction factor kappa = (2/pi) mu' "
          "atan(k_V gamma_T') depends on the slip acceleration it produces, so a solution "
          "always exists, and it is unique unless mu' |G_NT| >= G_NN (the exact law's "
          "Painleve condition; then several exist where |kappa| exceeds G_NN / |G_NT| "
          "between them); " + dynamics_.jamming_report(),
      "the drive self-locks dynamically (Painleve paradox of the acceleration-dependent "
      "friction law); reduce the friction or change the inertia ratio");
}

// At the state set: a JammingAtState, which an integrator retries where a
// right-hand side meets it at a trial state (core/errors.hpp).
void DriveHybrid::jam(const std::string& what) const {
  throw JammingAtState(dynamics_.time(),
                     "dynamic jamming: " + what + "; " + dynamics_.jamming_report(),
                     "the drive self-locks dynamically (Painleve paradox); reduce the "
                     "friction or change the inertia ratio");
}

}  // namespace leadscrew::model::drive
