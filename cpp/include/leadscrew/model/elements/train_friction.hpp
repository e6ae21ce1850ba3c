// Element: the drive train's friction stages besides the thread (issue 19,
// items 1 and 2): the motor's own Coulomb friction (motor.friction_torque)
// and a lossy or worm gear stage (gear.type = "lossy", "worm";
// docs/physics/gear.md, "Friction stages").
//
// The event-driven scheme runs it on the rigid drive without play: there
// every contact slips with the one speed phi' (rotor, stage, thread), so
// the train is one degree of freedom whose friction contacts stick and slip
// together (DriveHybrid::TrainSolver, cpp/src/model/drive/train_solver.cpp);
// on the flexible concepts and with exact or penalty play as the rotor's
// friction contact, a mode and roots of its own
// beside the thread's (DriveHybrid::RotorContact,
// cpp/src/model/drive/hybrid_rotor_contact.cpp; a flank's impact through
// it: hybrid_rotor_impact.cpp);
// and behind a prescribed rotor speed on every concept and play, where the
// frictions change the motor's torque alone (friction_torque_at_speed,
// DriveHybrid::ConstrainedSolver).
// Moreau-Jean runs it on every concept, with exact play too: the rotor's
// contact (the motor's friction and the stage, slipping with the rotor's
// speed) is a second friction contact of its step beside the thread's
// (cpp/src/model/drive/moreau.cpp; docs/physics/gear.md, "Moreau-Jean").
//
// On the driven part's coordinate phi (the stage's output, gear.hpp) the
// rotor (reflected inertia R = n^2 J_rotor) and its motor (torque U = n T on
// the coordinate) act through the stage:
//   rotor   R phi'' = U - |n| T_c s - x              (s = sign phi')
//   stage   x = k tau_b                              (x = n tau_a: the rotor's
//                                                     torque into the stage on
//                                                     the coordinate; tau_b:
//                                                     the stage's torque on the
//                                                     driven part)
// with k = 1 / eta where the power flows from the rotor to the driven part
// (tau_b s > 0, "forward") and k = eta_b where it flows back (tau_b s < 0).
// The stage's loss torque is x - tau_b = (k - 1) tau_b, its power
// (k - 1) tau_b phi' >= 0 for eta, eta_b <= 1. A worm is the same law with
// eta = tan(gamma) / tan(gamma + rho'), eta_b = tan(gamma - rho') / tan(gamma),
// rho' = atan(mu / cos(beta_w / 2)) (beta_w the included flank angle, as the
// thread's; mu_static at breakaway): a thread
// pair whose contact is massless, so its two sides' torques keep the ratio
// of its raise or lower torque.
#pragma once

#include <cmath>
#include <string>

namespace leadscrew::model::elements {

struct TrainFriction {
  double ratio = 1.0;            // n (gear.ratio; 1 without a stage)
  double rotor_inertia = 0.0;    // R = n^2 J_rotor [kg m^2]: the rotor's inertia on phi
  double motor_friction = 0.0;   // T_c [N m] on the rotor (0: none)
  bool stage = false;            // a lossy or worm stage
  bool worm = false;
  // The stage's efficiencies forward and backward, in slip and at
  // breakaway (a worm's from mu_static; a lossy stage's are the same).
  double efficiency = 1.0, efficiency_backdrive = 1.0;
  double efficiency_static = 1.0, efficiency_backdrive_static = 1.0;
  // Why the event-driven scheme cannot run it ("": it can; the concept,
  // play, the thread's law): elements::train_event_driven_obstacle.
  std::string event_driven_obstacle;
  // Moreau-Jean the default where both schemes run it (those the
  // event-driven scheme took in issue 32: a prescribed rotor speed, a static
  // coefficient on the thread; their results of before unchanged).
  bool moreau_default = false;

  bool motor_friction_present() const noexcept { return motor_friction > 0.0; }
  // The motor's friction bound on the coordinate, |n| T_c [N m].
  double motor_friction_bound() const noexcept { return std::abs(ratio) * motor_friction; }
  // k = x / tau_b for the power's direction (stage_sign > 0: forward).
  double torque_ratio(int stage_sign, bool breakaway) const noexcept {
    if (!stage) return 1.0;
    if (stage_sign > 0) return 1.0 / (breakaway ? efficiency_static : efficiency);
    return breakaway ? efficiency_backdrive_static : efficiency_backdrive;
  }
  // The stage's loss where it passes the work (or power) W to the driven
  // part: the rotor's side puts k W in (k by the power flow, W's sign:
  // forward where W >= 0), so the stage loses (k - 1) W >= 0 (eta, eta_b <= 1).
  double stage_loss(double transmitted_work) const noexcept {
    return (torque_ratio(transmitted_work >= 0.0 ? 1 : -1, false) - 1.0) * transmitted_work;
  }
  // A prescribed rotor speed (loads.drive_speed): the drive's motion does
  // not depend on the frictions ahead of the stage's output, only the
  // motor's torque does. With tau_b the torque the stage passes to the
  // driven part and w the coordinate's speed, the motor's torque on the
  // coordinate exceeds tau_b + R w' by s |n| T_c + (k - 1) tau_b (s = sign w,
  // k by the sign of tau_b w); at rest nothing slips and the static sets
  // contain 0 (docs/physics/gear.md, "A prescribed rotor speed").
  double friction_torque_at_speed(double transmitted, double speed) const noexcept {
    if (speed == 0.0) return 0.0;
    const int s = speed > 0.0 ? 1 : -1;
    return s * motor_friction_bound() +
           (torque_ratio(transmitted * speed >= 0.0 ? 1 : -1, false) - 1.0) * transmitted;
  }
  // The stage holds a back-driving load on its own (eta_b <= 0).
  bool self_locking() const noexcept { return stage && efficiency_backdrive_static <= 0.0; }

  // A worm's efficiencies from its lead angle gamma [rad] and its
  // coefficient on the flank mu' = mu / cos(beta_w / 2).
  static double worm_efficiency(double lead_angle, double mu_flank) {
    return std::tan(lead_angle) / std::tan(lead_angle + std::atan(mu_flank));
  }
  static double worm_efficiency_backdrive(double lead_angle, double mu_flank) {
    return std::tan(lead_angle - std::atan(mu_flank)) / std::tan(lead_angle);
  }
};

}  // namespace leadscrew::model::elements
