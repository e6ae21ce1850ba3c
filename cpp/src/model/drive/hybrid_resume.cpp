// DriveHybrid (hybrid.hpp): a run advanced in pieces, whose loads may
// change between them (model/drive_stepper.hpp).
#include "hybrid.hpp"

namespace leadscrew::model::drive {

void DriveHybrid::extend_horizon(double t, const double* y, double t_end) {
  if (!(t_end > t_end_)) return;
  t_end_ = t_end;
  plan_load_roots(t);  // a crossing beyond the old horizon was not looked for
  // The regularized law's look-ahead toward its Painleve regime ended at the
  // old horizon without a verdict: it goes on to the new one.
  if (watch_fold()) {
    set(t, y);
    solve_current();
    if (dynamics_.thread_denominator(sigma_guess_, current_kappa()) <
        kFoldWatch * dynamics_.delassus_normal())
      approach_fold(t, y);
  }
}

// The loads jumped at t: the forces of the current mode with them, so the
// mode is chosen from the state as at a start (a stick the new loads break
// slips at once). The energy account goes on from the run's start: its
// reference energies and the impact loss booked so far; the work and loss
// integrals are in y.
void DriveHybrid::resume(const DriveHybrid& before, double t, double* y) {
  t_end_ = before.t_end_;
  select_initial_mode(t, y);
  kinetic0_ = before.kinetic0_;
  stored0_ = before.stored0_;
  impact_loss_ = before.impact_loss_;
}

}  // namespace leadscrew::model::drive
