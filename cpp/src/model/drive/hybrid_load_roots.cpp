// DriveHybrid (hybrid.hpp): the roots of the rigid drive's load-driven modes,
// planned from the loads alone (first_load_crossing, drive_rigid.hpp).
#include "hybrid.hpp"

#include <algorithm>
#include <limits>
#include <optional>

#include "driver_element.hpp"
#include "mode_solver.hpp"

namespace leadscrew::model::drive {

// True if the thread forces of the current mode depend on the loads alone
// (linearly): the rigid drive (no springs, no dampers) with a
// torque-driven rotor and exact Coulomb friction on the thread without play
// or a closed flank, in stick (every coordinate locked) or slip (the
// friction factor +-mu' is constant).
bool DriveHybrid::load_driven() const {
  // (An element whose forces depend on its own state, a DC motor's torque
  // k_t i: its roots are the state's; a base excitation's force is not a
  // drive torque or an axial force: the sampled margins decide.)
  // (The train's friction stages: the motor's friction is a constant term,
  // and the stage's sign a state's; their roots are sampled.)
  return train_ == nullptr && model_.elements().forces.empty() &&
         !model_.motor().speed_controlled &&
         std::all_of(elements_.begin(), elements_.end(),
                     [](const std::unique_ptr<Element>& element) {
                       return element->forces_from_loads_alone();
                     }) &&
         !model_.preloaded_nut() && dynamics_.plain_coulomb() &&
         (mode_.contact == ThreadContact::bilateral || mode_.contact == ThreadContact::closed) &&
         (mode_.friction == FrictionMode::stick || mode_.friction == FrictionMode::slip);
}

// At the start of a mode whose thread forces are load-driven, the stick
// cone's margin (stick) or the normal force on its side (slip) is a function
// of time alone: its first zero is found by first_load_crossing, and the
// root function becomes the time left until it, load_root_time_ - t, which
// falls through zero exactly there however short the excursion beyond it.
// (The margin sampled at the integrator's steps missed a 13 ms excursion out
// of the cone with steps of 21 ms.)
void DriveHybrid::plan_load_roots(double t) {
  load_root_ = -1;
  load_root_time_ = std::numeric_limits<double>::infinity();
  if (!load_driven()) return;
  const double torque = p_.drive_torque(t), force = p_.axial_force(t);
  LoadCoefficients functions[2];
  int count = 0, slot = -1;
  if (mode_.friction == FrictionMode::stick) {
    // |T| <= mu' |N| as the two factors mu' s N -+ T, with s the side of N
    // at the start: before N could change sides, |T| would have to fall to
    // zero with it, so one factor crosses first.
    const RigidModeCoefficients c = solver_->coefficients(1);
    int side = sign_of(c.normal_force(torque, force));
    if (side == 0)
      side = sign_of(c.normal_force(p_.drive_torque.derivative(t), p_.axial_force.derivative(t)));
    if (side == 0) return;  // no load on the thread: the sampled margin decides
    const double mu = stick_mu();
    for (int s : {1, -1})
      functions[count++] = {mu * side * c.normal_force.per_torque - s * c.friction_force.per_torque,
                            mu * side * c.normal_force.per_force - s * c.friction_force.per_force};
    slot = 0;
  } else {
    // The normal force leaving its side: a flank change (bilateral) or the
    // flank opening (closed).
    const int side = mode_.contact == ThreadContact::closed ? mode_.flank : normal_side_;
    if (side == 0) return;  // not left zero yet (flank_change_root)
    const RigidModeCoefficients c = solver_->coefficients(side);
    functions[count++] = {side * c.normal_force.per_torque, side * c.normal_force.per_force};
    slot = 1;
  }
  const std::optional<LoadCrossing> crossing =
      first_load_crossing(p_.drive_torque, p_.axial_force, functions, count, t, t_end_);
  if (!crossing) return;  // a callable load: no curvature bound
  load_root_ = slot;
  load_root_time_ = crossing->time;
  // No crossing before the scan's horizon: its root falls through zero
  // there too, and the scan goes on from it, the mode unchanged
  // (load_scan_horizon).
  load_root_horizon_ = !crossing->found;
}

// The load-driven root fired at the scan's horizon alone (no crossing of
// the mode's own): the scan goes on from there, no event.
bool DriveHybrid::load_scan_horizon(double t, const std::vector<int>& root_info) {
  if (load_root_ < 0 || !load_root_horizon_ || root_info[load_root_] == 0) return false;
  for (std::size_t i = 0; i < root_info.size(); ++i)
    if (root_info[i] != 0 && static_cast<int>(i) != load_root_) return false;
  plan_load_roots(t);
  return true;
}

}  // namespace leadscrew::model::drive
