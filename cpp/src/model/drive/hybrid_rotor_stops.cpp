// DriveHybrid (hybrid.hpp): the rotor's friction contact (the train's
// stages with a torque or DC motor: hybrid_rotor_contact.cpp) beside an
// exact end stop (hybrid_end_stops.cpp), on the flexible concepts without
// play and with penalty play (docs/physics/gear.md, "Exact end stops and a
// preloaded nut on the rotor contact").
//
// A closed stop holds the load (ModeSpec::held_load): its reaction is one
// more sign of the mode's decision. The rotor's modes are tried as at rest
// or in slip (decide_rotor), each with the thread's decision at the held
// load, and a mode is consistent only where the stop still pushes the load
// off its face; where none is, the stop opens (release_held_load) and the
// modes are tried again with the load free.
//
// An impact through the thread (EndStopsElement::tied_impact) passes the
// stop's impulse to the rotor's coordinate. The motor's Coulomb friction is
// a finite torque: no impulse. The stage passes x = k P_b per impulse (k by
// the direction of the power flow, as in slip): with the rotor's impulse
// balance R dw = -x and the eliminated row's Q = -(k - 1) R dw / k, the
// stage's impulse on the driven part is P_b = -R dw / k, whose power flow
// flow s P_b >= 0 the mode must show. A stuck rotor keeps dw = 0, which
// the stage's static set holds (Q = -P_b between (eta_b,s - 1) P_b and
// (1 / eta_s - 1) P_b) only where eta_b,s <= 0: a self-locking stage holds
// any impulse from its output's side; every other stage lets the rotor
// slip away from rest the way the impulse drives it. A phase ends where the
// rotor's speed reaches zero (EndStopsElement::tied_impact), so each phase
// has one mode; the stage's loss in the impact is part of the kinetic
// energy's drop (impact_loss), which never rises.
#include <algorithm>
#include <cmath>
#include <limits>

#include "driver_element.hpp"

namespace leadscrew::model::drive {

bool DriveHybrid::held_stop_presses(const ModeSolution& s) const {
  if (held_load_ < 0) return true;
  // The closed stop: the one whose face the held load sits on.
  const elements::ExactEndStop* held = nullptr;
  for (const elements::ExactEndStop& stop : model_.elements().exact_stops)
    if (!held || std::abs(stop.gap(q_[held_load_])) < std::abs(held->gap(q_[held_load_])))
      held = &stop;
  return !held || -held->side * s.stop_force >= 0.0;
}

void DriveHybrid::release_held_load() {
  held_load_ = -1;
  for (const std::unique_ptr<Element>& element : elements_) element->release_hold();
}

// The rotor stalled with the load held: where every speed lies below
// kHeldResolution of atol (the integrator's resolution; the projection's
// round-off, 1e-51 m/s, at a drive at rest), they are its round-off, set to
// exactly zero. Left, the thread's slip velocity of 7e-53 m/s stood far
// above its noise (relative to the speeds, 1e-66 m/s): the thread's
// decision after the rotor's took a slip's sign where the rotor's had it
// stick, and the two chattered at one instant (100,000 events).
void DriveHybrid::rest_held_drive(double t, double* y) {
  if (held_load_ < 0 || v_.cwiseAbs().maxCoeff() > kHeldResolution * integrator_options_.atol)
    return;
  v_.setZero();
  layout_.compress(q_, v_, y);
  set(t, y);
}

// Half B's normal force (preload_normal) and the preload's friction at the
// slip's coefficient bound it: both halves bear about the preload and cancel
// to the net force, so their round-off (1e-18 N m at rest under zero loads
// with arctan_velocity) is the preload's, not the net force's.
double DriveHybrid::preload_torque_scale(const ModeSolution& s) const {
  const elements::PreloadedNut* nut = model_.preloaded_nut();
  if (!nut) return 0.0;
  const int r = model_.rotor();
  const double normal = std::max(std::abs(s.preload_normal), nut->preload / nut->cos_lead);
  return normal * (std::abs(model_.normal_direction()[r]) +
                   nut->mu * std::abs(model_.tangent_direction()[r]));
}

bool DriveHybrid::rotor_impulse_consistent(const moreau_contacts::RotorMode& mode, double dw,
                                           bool at_rest) const {
  const elements::TrainFriction& train = *rotor_train_;
  if (mode.slip == 0) return train.self_locking();
  const double w = v_[model_.rotor()];
  if (!(mode.slip * (at_rest ? dw : w) > 0.0)) return false;
  if (!train.stage) return true;
  const double k = train.torque_ratio(mode.flow, mode.breakaway);
  return mode.flow * mode.slip * (-dw / k) >= 0.0;  // P_b = -R dw / k, R > 0
}

}  // namespace leadscrew::model::drive
