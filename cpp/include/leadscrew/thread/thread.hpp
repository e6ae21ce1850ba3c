// Thread geometry and the closed-form mechanics of a power screw.
//
// Sign and angle conventions (README, "Units and sign conventions"):
//  - flank_angle is the included thread angle beta (0 square, 29 deg Acme,
//    30 deg ISO metric trapezoidal); the flank normal force is scaled by
//    1 / cos(beta / 2), which the effective friction coefficient
//    mu' = mu / cos(beta / 2) expresses.
//  - lead_angle alpha = atan(lead / (pi d_m)).
//  - The thesis's bounds of static position holding and drivability
//    tan(alpha) < mu' < cot(alpha) are its eq. (3.5), (3.7), (3.8).
#pragma once

#include <string>

namespace leadscrew {

enum class Hand { right, left };

// Immutable thread parameters (SI units: m, rad).
class Thread {
 public:
  Thread(double pitch, double mean_diameter, int starts = 1, double flank_angle = 0.0,
         Hand hand = Hand::right);

  double pitch() const noexcept { return pitch_; }
  double mean_diameter() const noexcept { return mean_diameter_; }
  double mean_radius() const noexcept { return 0.5 * mean_diameter_; }
  int starts() const noexcept { return starts_; }
  double flank_angle() const noexcept { return flank_angle_; }
  Hand hand() const noexcept { return hand_; }

  // starts * pitch [m]
  double lead() const noexcept { return starts_ * pitch_; }
  // atan(lead / (pi d_m)) [rad]
  double lead_angle() const noexcept { return lead_angle_; }
  // lead / (2 pi) [m/rad]: the thesis's s / (2 pi) in eq. (4.1)
  double lead_per_radian() const noexcept;
  // +1 for a right-hand thread, -1 for a left-hand one: the sign of the screw
  // relation u_screw - u_nut = hand_sign * p (phi_screw - phi_nut).
  double hand_sign() const noexcept { return hand_ == Hand::right ? 1.0 : -1.0; }
  // 1 / cos(beta / 2): flank normal force per unit of normal force of a square thread
  double flank_factor() const noexcept;
  // mu' = mu / cos(beta / 2)
  double effective_mu(double mu) const;

 private:
  double pitch_;
  double mean_diameter_;
  int starts_;
  double flank_angle_;
  Hand hand_;
  double lead_angle_;
};

Hand parse_hand(const std::string& hand);
std::string hand_name(Hand hand);

// Torque [N m] to move an axial load [N] against its direction ("raise").
// Returns +inf where no torque can move it (mu' >= cot(alpha): not drivable).
double raise_torque(const Thread& thread, double mu, double load, double collar_mu = 0.0,
                    double collar_diameter = 0.0);

// Torque [N m] to move an axial load [N] with its direction ("lower").
// Negative where the thread back-drives (the load turns the screw by itself).
double lower_torque(const Thread& thread, double mu, double load, double collar_mu = 0.0,
                    double collar_diameter = 0.0);

// Forward efficiency load * lead / (2 pi raise_torque); 0 where not drivable.
// backdrive = true: the efficiency when the axial load drives the screw,
// -2 pi lower_torque / (load * lead), <= 0 where the thread is self-locking.
double efficiency(const Thread& thread, double mu, double collar_mu = 0.0,
                  double collar_diameter = 0.0, bool backdrive = false);

// Static position holding under a pure axial load, eq. (3.5): tan(alpha) < mu'.
bool is_self_locking(const Thread& thread, double mu);

// A pure torque can drive the thread, eq. (3.7): mu' < cot(alpha).
bool is_drivable(const Thread& thread, double mu);

}  // namespace leadscrew
