// The state of a drive at t = 0 (initial.state).
//
// "relaxed": every spring relaxed (q = 0), the nut at initial.play_position,
// every body moving with the thread at initial.rotor_speed.
//
// "equilibrium": at rest in static equilibrium under the loads at t = 0 (the
// drive torque M and the axial force F):
//   f(q) + W_N lambda_N + W_T lambda_T = 0        (springs, loads, thread)
//   e(q) = e*                                     (the nut on its flank)
//   q_rotor = 0                                   (the rotor at initial.rotor_angle)
// The rigid-body rows (the rotor with what turns with it, the load with what
// translates with it) fix the thread forces lambda_N, lambda_T by the loads
// alone; the springs then take their deflections. The flank is the one the
// normal force presses the nut against: e* = -sign(lambda_N) c / 2 for an
// exact contact (lambda_N > 0 on the lower flank), a penalty flank penetrated
// as far as its elastic law carries |lambda_N| (beyond c / 2), e* = 0 without
// play. The thread sticks: the friction force must lie in the static cone,
// |lambda_T| <= mu_static' |lambda_N| (the law's stick limit, mu' for plain
// Coulomb); where it does not, no static equilibrium exists (NoEquilibrium:
// the loads drive the thread). A regularized law carries no friction at
// rest: its drive starts from the same state and slips from it at the small
// speed its friction needs. LuGre's bristles start relaxed (z = 0): their
// friction force builds up as they deflect, a presliding displacement.
//
// The screw's stiffness follows the nut (eq. 4.24), so the equations are
// solved by Newton's method with the spring matrix at the current nut
// position (the exact forces, those of DriveDynamics, in the residual), and
// the result is checked: every generalized force balanced to 1e-9 of the
// forces that meet there (with what the springs pass on from their other
// ends: a coordinate no load passes through, the rotor's coupling under a
// zero torque, has only round-off of its own), else SimulationError.
#pragma once

#include <Eigen/Core>

#include "leadscrew/model/drive.hpp"

namespace leadscrew::model {

struct DriveStart {
  Eigen::VectorXd q, v;         // every coordinate and velocity at t = 0
  double play = 0.0;            // e at t = 0 [m] (0 without play)
  double normal_force = 0.0;    // flank normal force holding the loads [N]
  double friction_force = 0.0;  // flank friction force holding them [N]
  int iterations = 0;           // Newton iterations (0 for a relaxed start)
};

// The start the model's initial.state asks for. Throws NoEquilibrium where
// the loads at t = 0 have no static equilibrium, SimulationError where the
// solve does not converge (or the nut would be off the screw).
DriveStart initial_state(const DriveModel& model);

}  // namespace leadscrew::model
