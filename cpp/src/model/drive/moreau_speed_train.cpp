// DriveMoreau (moreau.hpp): the train's friction stages (the motor's
// Coulomb friction, a lossy or worm stage: elements/train_friction.hpp)
// with a speed-controlled rotor (loads.drive_speed; docs/physics/gear.md,
// "The smooth thread laws and a prescribed rotor speed").
//
// The rotor's speed is prescribed, so the drive's motion does not depend
// on the frictions ahead of the stage's output: the step is solved without
// the rotor's friction row, and its constraint impulse Lambda on the rotor
// is what motor and frictions together give it. The rotor's reflected
// inertia R takes R (w+ - w0) of it; the rest, P_b = Lambda - R (w+ - w0),
// is what the stage passes to the driven part. The stage's power flow
// (the sign of P_b w) picks the efficiency: forward (the motor drives) the
// stage takes X = P_b / eta in, backward (the load drives) X = eta_b P_b;
// its loss impulse is X - P_b, the motor's friction s h |n| T_c with s the
// rotor's sign of motion, and the motor's impulse Lambda + Q with
// Q = s h |n| T_c + X - P_b. Both losses are booked at w_theta, where the
// motor's impulse works, so the account closes step by step (each loss
// >= 0: X - P_b has the sign of w for either flow, eta <= 1, eta_b <= 1).
// At rest (w_theta = 0) nothing slips: no loss, the motor's torque the
// transmitted one (the stage's static set contains it).
#include "moreau.hpp"

namespace leadscrew::model::drive {

DriveMoreau::Impulses DriveMoreau::solve_speed_train(
    double t, double h, double theta, const CoordinateVector& v0, double normal_target,
    double rotor_target, int sigma_fixed, bool contact_at_start, bool& contact, bool& stick,
    moreau_contacts::RotorMode& mode) {
  rotor_row_ = false;
  Impulses impulses;
  contact = contact_at_start;
  stick = false;
  if (contact)
    impulses = solve_thread(t, h, theta, v0, normal_target, rotor_target, sigma_fixed, contact,
                            stick);
  if (!contact) impulses = solve(false, 0.0, rotor_target, 0.0);
  const elements::TrainFriction& train = *model_.train_friction();
  const int r = model_.rotor();
  const double w_theta = (1.0 - theta) * v0[r] + theta * rotor_target;
  const double transmitted = impulses.rotor - train.rotor_inertia * (rotor_target - v0[r]);
  mode = moreau_contacts::RotorMode{};
  mode.slip = w_theta > 0.0 ? 1 : w_theta < 0.0 ? -1 : 0;
  double q = 0.0;
  if (mode.slip != 0) {
    // (A stage that transmits nothing flows forward: no loss either way.)
    mode.flow = mode.slip * transmitted >= 0.0 ? 1 : -1;
    const double k = train.torque_ratio(mode.flow, false);
    q = mode.slip * h * train.motor_friction_bound() + (k - 1.0) * transmitted;
  }
  impulses.train = q;
  impulses.rotor += q;
  return impulses;
}

}  // namespace leadscrew::model::drive
