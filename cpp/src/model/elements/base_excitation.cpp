// The housing's vibration as an element (elements/base_excitation.hpp, its
// physics; docs/physics/base_excitation.md), behind the element interface
// (model/element.hpp): its declaration (the base's work a state of y; the
// channels base_force [N] and base_torque [N*m], the largest inertial loads
// for the checks' bounds, and base_work [J], a work of the energy account),
// its generalised force -a m_u - alpha J_phi, its work's rate and, in
// Moreau-Jean, its work over a step (its force at t + theta h over the
// step's displacement); the scene's keys (loads.base_acceleration,
// loads.base_angular_acceleration) and its build. One line in the registry
// (drive/element_registry.cpp).
#include "leadscrew/model/elements/base_excitation.hpp"

#include <memory>

#include "../drive/declaration.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/element.hpp"
#include "leadscrew/model/elements/drive_elements.hpp"

namespace leadscrew::model {
namespace drive {
const ElementKind& base_excitation_kind();
}

namespace elements {

namespace {

// Its channels (the declaration's, in this order).
enum Channel { kForce, kTorque, kWork };

class BaseExcitationElement final : public Element {
 public:
  explicit BaseExcitationElement(BaseExcitation base) : base_(std::move(base)) {}

  const char* name() const override { return "base_excitation"; }
  void declare(drive::Declaration& d) const override {
    d.states = {"base_work"};
    d.channels = drive::base_excitation_kind().catalog;
  }
  void add_forces(const ElementState& s, const ElementMode& mode, double* forces) const override {
    (void)mode;
    double force = 0.0, torque = 0.0;
    base_.add_forces(s.t, forces, force, torque);
  }
  // (A function of time, but not a drive torque or an axial force: the
  // load-driven roots' coefficients do not take it; the sampled margins
  // decide.)
  bool forces_from_loads_alone() const override { return false; }
  void rates(const ElementState& s, const ElementMode& mode, double* own_rates,
             double* energy) const override {
    (void)mode;
    (void)energy;
    own_rates[0] = base_.power(s.t, s.v);
  }
  void output(const ElementState& s, const ElementMode& mode, double* values) const override {
    (void)mode;
    values[kForce] = -base_.acceleration(s.t) * base_.total_mass;
    values[kTorque] = -base_.angular_acceleration(s.t) * base_.total_inertia;
    values[kWork] = s.own[0];
  }
  // (Its work, with the work.)
  double energy_terms(const ElementState& s) const override { return -s.own[0]; }
  // Moreau-Jean: its force at t + theta h (the step's right-hand side has
  // it) over the step's displacement.
  void step_end(const ElementStep& step, const double* q_next, const double* v_next,
                ElementMode& mode, double* own_next, double* energy) const override {
    (void)v_next;
    (void)mode;
    (void)energy;
    double displacement[kMaxDisplacement];
    for (std::size_t i = 0; i < base_.mass.size(); ++i)
      displacement[i] = q_next[i] - step.start.q[i];
    own_next[0] = step.start.own[0] + base_.power(step.start.t, displacement);
  }

 private:
  static constexpr std::size_t kMaxDisplacement = 6;  // (kMaxCoordinates)
  BaseExcitation base_;
};

bool at_rest(const Excitation& load) {
  const Excitation::Definition d = load.definition();
  return d.kind == "constant" && d.parameters.at(0) == 0.0;
}

void declare(const DriveModel& model, const friction::Law& law, drive::Declaration& d) {
  (void)law;
  drive::declare_model_element(model, "base_excitation", d);
}

}  // namespace

std::string given_base_excitation(const DriveParameters& p) {
  if (!at_rest(p.base_acceleration))
    return "loads.base_acceleration = " + p.base_acceleration.describe();
  if (!at_rest(p.base_angular_acceleration))
    return "loads.base_angular_acceleration = " + p.base_angular_acceleration.describe();
  return "";
}

void build_base_excitation(const DriveParameters& p, DriveElements& e) {
  const bool axial = !at_rest(p.base_acceleration);
  const bool angular = !at_rest(p.base_angular_acceleration);
  if (!axial && !angular) return;
  if (angular && p.gear != GearType::none)
    throw InvalidArgument("loads.base_angular_acceleration = " +
                          p.base_angular_acceleration.describe() +
                          " is invalid with a gear stage: the rotor's axis relative to the "
                          "screw's is not modelled (give it without the gear section)");
  BaseExcitation base;
  base.acceleration = p.base_acceleration;
  base.angular_acceleration = p.base_angular_acceleration;
  const std::size_t n = e.coordinates.size();
  base.mass.assign(n, 0.0);
  base.inertia.assign(n, 0.0);
  // Coordinates are named u_<part> (axial) or phi_<part> (angular).
  for (const RigidBody& body : e.bodies) {
    const std::string& name = e.coordinates[static_cast<std::size_t>(body.coordinate)];
    auto& weight = name.rfind("u_", 0) == 0 ? base.mass : base.inertia;
    weight[static_cast<std::size_t>(body.coordinate)] += body.inertia;
  }
  for (std::size_t i = 0; i < n; ++i) {
    base.total_mass += base.mass[i];
    base.total_inertia += base.inertia[i];
  }
  e.elements.push_back(std::make_shared<BaseExcitationElement>(std::move(base)));
}

}  // namespace elements

namespace drive {
const ElementKind& base_excitation_kind() {
  static const ElementKind kind{"base_excitation",
                                {{"base_force", "N", Role::load_force},
                                 {"base_torque", "N*m", Role::load_torque},
                                 {"base_work", "J", Role::work}},
                                &elements::declare};
  return kind;
}
}  // namespace drive

}  // namespace leadscrew::model
