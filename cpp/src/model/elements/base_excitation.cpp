// The housing's vibration as an element (elements/base_excitation.hpp).
#include "leadscrew/model/elements/base_excitation.hpp"

#include "leadscrew/core/errors.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/elements/drive_elements.hpp"

namespace leadscrew::model::elements {

namespace {

bool at_rest(const Excitation& load) {
  const Excitation::Definition d = load.definition();
  return d.kind == "constant" && d.parameters.at(0) == 0.0;
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
  e.base = std::move(base);
}

}  // namespace leadscrew::model::elements
