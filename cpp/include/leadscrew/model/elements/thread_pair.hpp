// Element: the thread pair between the screw's and the nut's contact bodies
// (unrolled at the mean radius, thesis Fig. 4.2), with the flank's friction
// law. With du = u_screw - u_nut and dphi = phi_screw - phi_nut the axial
// play is e = e_0 + du - h p dphi (h = +1 right hand, p = lead / 2 pi, eq.
// 4.1); normal W_N = cos(a) grad e, tangent W_T (gamma_T = sin(a) du' +
// h r_m cos(a) dphi'); a force lambda_N n + lambda_T t acts on the screw,
// its opposite on the nut.
//
// Without play it is a kinematic constraint e = 0 (one coordinate
// eliminated); with play the flanks at e = +-c_a / 2 are exact unilateral
// contacts (rows W_N and, in stick, W_T of the constrained solve) or
// penalty contacts (bistop, cubic: a force from the penetration, with
// their elastic energy and loss power in the energy account). Friction:
// |lambda_T| <= mu' |lambda_N|, mu' = mu / cos(beta / 2), from its
// friction::Law.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <memory>

#include "leadscrew/friction/law.hpp"

namespace leadscrew::model {
enum class BacklashContact;
struct DriveParameters;
}  // namespace leadscrew::model

namespace leadscrew::model::elements {

// Coordinates of the screw's and the nut's contact bodies: an index into q, or
// -1 where the support fixes that motion.
struct ContactCoordinates {
  int screw_u = -1, screw_phi = -1, nut_u = -1, nut_phi = -1;
};

class ThreadPair {
 public:
  // The thread pair of parameters `p` (its thread, play and contact law,
  // already checked) with the friction law `law` (make_law) between the
  // contact coordinates `c` of a model with n coordinates.
  ThreadPair(const DriveParameters& p, std::shared_ptr<const friction::Law> law,
             const ContactCoordinates& c, int n);
  // The flank's friction law of `p`: mu, k_v where the law takes it, and its
  // other parameters (friction::make_law checks them).
  static std::shared_ptr<const friction::Law> make_law(const DriveParameters& p);

  // The penalty flanks' force at the play e and its rate: the normal force
  // on the flank, each flank's penetration (0: none) and the loss power of
  // their damping.
  struct Penalty {
    double normal_force = 0.0;
    double penetration[2] = {0.0, 0.0};  // upper (e = +c/2) and lower flank
    double loss_power = 0.0;
  };

  BacklashContact contact() const noexcept { return contact_; }
  bool bilateral() const noexcept { return bilateral_; }    // no play: a constraint
  bool penalty() const noexcept { return penalty_; }        // bistop or cubic
  bool exact_play() const noexcept { return exact_play_; }  // unilateral exact flanks

  const Eigen::VectorXd& play_gradient() const noexcept { return play_gradient_; }
  const Eigen::VectorXd& normal() const noexcept { return normal_; }
  const Eigen::VectorXd& tangent() const noexcept { return tangent_; }
  const Eigen::VectorXd& nut_position_gradient() const noexcept { return position_gradient_; }
  // The coordinate the constraint e = 0 eliminates (-1 with play).
  int eliminated() const noexcept { return eliminated_; }

  const friction::Law& law() const noexcept { return *law_; }
  double flank_factor() const noexcept { return flank_factor_; }
  double effective_mu() const noexcept { return mu_eff_; }

  // The play e at positions q.
  template <class Vector>
  double play(const Vector& q) const {
    return play_position_ + play_gradient_.dot(q);
  }
  // The nut's centre's distance from the screw's drive (or load) end at q.
  double nut_position(const double* q) const {
    double a = nut_position_;
    for (Eigen::Index i = 0; i < position_gradient_.size(); ++i) a += position_gradient_[i] * q[i];
    return a;
  }

  void penalty_force(double play, double play_rate, Penalty& out) const;
  // The potential of penalty_force's elastic forces at the penetrations.
  double contact_energy(const double penetration[2]) const noexcept;
  // The penetration at which a penalty flank's elastic force is `force`
  // (its inverse; 0 for force <= 0).
  double penetration_for(double force) const;

  // The penalty flanks as functions of the play e (Moreau-Jean's step,
  // drive/moreau_flank.hpp): their potential U(e) (contact_energy), its
  // slope U'(e) (the elastic force along -grad e) and curvature U''(e), and
  // the damping coefficient of the flank e penetrates (0 in the play).
  double flank_potential(double play) const noexcept;
  double flank_slope(double play) const noexcept;
  double flank_curvature(double play) const noexcept;
  double flank_damping(double play) const noexcept;
  double cos_lead() const noexcept { return cos_lead_; }
  // A penalty flank's elastic force at the penetration d > 0 [N].
  double flank_force(double penetration) const noexcept;

 private:
  BacklashContact contact_;
  bool bilateral_ = true, penalty_ = false, exact_play_ = false, bistop_ = false;
  double clearance_ = 0.0, stiffness_ = 0.0, exponent_ = 1.5, damping_ = 0.0, depth_ = 1e-7;
  double play_position_ = 0.0, nut_position_ = 0.0, cos_lead_ = 1.0;
  Eigen::VectorXd play_gradient_, normal_, tangent_, position_gradient_;
  std::shared_ptr<const friction::Law> law_;
  double mu_eff_ = 0.0, flank_factor_ = 1.0;
  int eliminated_ = -1;
};

}  // namespace leadscrew::model::elements
