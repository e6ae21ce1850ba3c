// Element: a gear stage between the rotor and the driven part (issue 19,
// item 2; scene section `gear`; docs/physics/gear.md).
//
// The rotor turns n times per turn of the driven part (n = gear.ratio,
// finite and nonzero; n < 0 is a reversing stage: the driven part turns the
// other way). Type "ideal": a kinematic ratio that stores and dissipates
// nothing.
//
// Layout: the drive's rotating coordinate (DriveModel::rotor(), named
// phi_rotor as without a gear) is the gear's output, the driven part's
// angle phi; the rotor's own angle is n phi. Through the ideal gear the
// rotor and its motor act on phi as
//   inertia    n^2 J_rotor                  (rotor.inertia J_rotor)
//   torque     n T                          (T the motor's torque on the rotor:
//                                            loads.drive_torque, a DC motor's k_t i)
//   speed      phi' = omega_rotor(t) / n    (a speed-controlled motor, loads.drive_speed)
//   back-EMF   k_e n phi'                   (a DC motor: its constants reflected,
//                                            k_t -> n k_t, k_e -> n k_e; its
//                                            current and voltage are its own)
// so the kinetic energy n^2 J phi'^2 / 2 = J omega_rotor^2 / 2 and the
// drive's work n T phi' = T omega_rotor are the rotor's: the energy account
// keeps its form. The thread pair, the springs and the bodies of the driven
// side see phi as they see the rotor's angle without a gear. The result
// channels phi_drive, omega_drive and drive_torque stay the rotor's (n phi,
// n phi', the torque on the rotor; rotor_angle / rotor_speed in
// `initial` are the rotor's too).
//
// Without a gear n = 1: every product above is exact in floating point, so a
// drive without a gear runs bit-identically.
#pragma once

namespace leadscrew::model::elements {

// The smallest |gear.ratio|; the largest is its inverse (beyond them the
// reflected inertia n^2 J spans more than 16 decades against the driven
// side's).
constexpr double kSmallestGearRatio = 1e-4;

struct Gear {
  double ratio = 1.0;  // n: rotor turns per turn of the driven part

  // The rotor's angle [rad] and speed [rad/s] at the coordinate's phi, phi'.
  double rotor_angle(double phi) const noexcept { return ratio * phi; }
  double rotor_speed(double phi_rate) const noexcept { return ratio * phi_rate; }
  // The coordinate's speed [rad/s] where the rotor turns at omega_rotor.
  double driven_speed(double rotor_speed) const noexcept { return rotor_speed / ratio; }
  // The torque on the coordinate [N m] of a torque T on the rotor, and back.
  double driven_torque(double rotor_torque) const noexcept { return ratio * rotor_torque; }
  double rotor_torque(double driven_torque) const noexcept { return driven_torque / ratio; }
  // The rotor's inertia [kg m^2] as the coordinate feels it.
  double reflected_inertia(double rotor_inertia) const noexcept {
    return ratio * ratio * rotor_inertia;
  }
};

}  // namespace leadscrew::model::elements
