// DriveHybrid (hybrid.hpp): an exact flank's impact with the rotor's
// friction contact (the train's stages with a torque or DC motor; exact
// play, docs/physics/gear_rotor_impacts.md).
//
// On the impulse level the motor's friction (a finite torque) gives no
// impulse and the stage's law is Moreau-Jean's rotor row at h -> 0
// (moreau_contacts::RotorBalance with the rotor's momentum R w- as its
// start, no motor impulse, B = 0): stick w+ = 0, its impulse Q in the
// stage's static set; slip of sign s = sign w+ with the power flow's k,
// k Q - (k - 1) R (w- - w+) = 0, i.e. the rotor's coordinate of inverse
// mass k / (k J_s + R) through the impact. The modes are tried in
// Moreau-Jean's order (stick, the slips, the slips at breakaway), each with
// the thread's impact LCP, and the first consistent one is kept, as its
// step does; the restitution that would create energy is lowered as
// without the stages (flank_impact). The impact's loss: Q w+ >= 0 (a slip,
// booked at the end speed as Moreau-Jean does) is the stage's, the rest
// the impact's; with a plastic normal impact both are >= 0
// (T_loss = 1/2 dv M dv - P_T gamma_T+ + Q w+).
#include <algorithm>
#include <cmath>

#include "hybrid.hpp"

namespace leadscrew::model::drive {

bool DriveHybrid::flank_impulses(int flank, double restitution, const CoordinateVector& v_before,
                                 DriveDynamics::Impulses& impulses) {
  if (!rotor_train_) {
    v_ = v_before;
    ++lcp_solves_;
    return dynamics_.impact(flank, restitution, v_, impulses, lcp_workspace_, lcp_options_);
  }
  const int r = model_.rotor();
  moreau_contacts::RotorBalance balance;
  balance.inertia = rotor_train_->rotor_inertia;
  balance.w0 = v_before[r];
  for (const moreau_contacts::RotorMode& candidate : moreau_contacts::kRotorModes) {
    if (!rotor_train_->stage && candidate.flow < 0) continue;
    const moreau_contacts::RotorRow row = balance.row(*rotor_train_, candidate);
    ModeSpec::RotorRow contact;
    contact.active = true;
    contact.a_w = row.a_w;
    contact.a_q = row.a_q;
    contact.r = row.r;
    v_ = v_before;
    ++lcp_solves_;
    if (!dynamics_.impact(flank, restitution, v_, impulses, lcp_workspace_, lcp_options_,
                          contact))
      continue;
    const double other = std::abs(impulses.normal * model_.normal_direction()[r]) +
                         std::abs(impulses.tangential * model_.tangent_direction()[r]);
    if (!balance.consistent(*rotor_train_, candidate, v_[r], impulses.rotor_friction, other))
      continue;
    rotor_mode_ = candidate;
    rotor_mode_.breakaway = false;  // (after the impact the kinetic efficiencies)
    if (candidate.slip == 0) v_[r] = 0.0;  // (held: its round-off)
    return true;
  }
  return false;
}

double DriveHybrid::stage_impact_loss(const DriveDynamics::Impulses& impulses,
                                      double dissipated) const {
  if (!rotor_train_ || !rotor_train_->stage || rotor_mode_.slip == 0) return 0.0;
  const double share = impulses.rotor_friction * v_[model_.rotor()];
  return std::clamp(share, 0.0, std::max(0.0, dissipated));
}

}  // namespace leadscrew::model::drive
