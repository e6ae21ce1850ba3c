// A drive as a list of elements over its coordinates (Pinocchio's Model:
// immutable once built; DriveDynamics is its Data). One element per file in
// this directory:
//   rigid_body.hpp     RigidBody: inertia on a coordinate (mass matrix, kinetic energy)
//   spring_damper.hpp  SpringDamper: springs, dampers and supports (eq. 4.24's screw),
//                      a force element (ForceElements below)
//   thread_pair.hpp    ThreadPair: the flank constraint or contact and its friction law
//   motor.hpp          Motor: torque-controlled force or speed-controlled constraint
//   dc_motor.hpp       DcMotor: armature current (a state), voltage driver, current limit
//                      (an Element: cpp/src/model/elements/dc_motor.cpp)
//   axial_load.hpp     AxialLoad: the axial force on the load
//   gear.hpp           Gear: a stage between the rotor and the driven part (the
//                      Motor's; the rotor reflected onto its coordinate)
//   preloaded_nut.hpp  PreloadedNut: the split nut's preload half on the thread without play
//   end_stop.hpp       EndStop: a penalty end stop of the load's travel (a force element)
//   section_force.hpp  SectionForce: a force element defined in a source file of its own
//                      with its scene section (cpp/src/model/elements/<name>.cpp: the
//                      load spring)
// The lists are grouped by type (no virtual call per scalar in the
// right-hand side): DriveDynamics loops over each. A force element with a
// scene section of its own is a SectionForce (section_force.hpp: its file
// and one line of section_registry.cpp); a type in ForceElements is for a
// force the right-hand side must not reach through a virtual call (the
// screw's position-dependent springs, the end stops' events).
//
// build_drive_elements is the one place where the thesis's concepts (rigid,
// flexible_nut, flexible; the screw or the nut driven) become elements.
#pragma once

#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "leadscrew/model/element.hpp"
#include "leadscrew/model/elements/axial_load.hpp"
#include "leadscrew/model/elements/base_excitation.hpp"
#include "leadscrew/model/elements/dc_motor.hpp"
#include "leadscrew/model/elements/gear.hpp"
#include "leadscrew/model/elements/end_stop.hpp"
#include "leadscrew/model/elements/motor.hpp"
#include "leadscrew/model/elements/preloaded_nut.hpp"
#include "leadscrew/model/elements/train_friction.hpp"
#include "leadscrew/model/elements/rigid_body.hpp"
#include "leadscrew/model/elements/section_force.hpp"
#include "leadscrew/model/elements/spring_damper.hpp"
#include "leadscrew/model/elements/thread_pair.hpp"

namespace leadscrew::model {
struct DriveParameters;
}

namespace leadscrew::model::elements {

// Lists of force elements, one std::vector per type, visited in the order
// of the types (static dispatch: no virtual call in the right-hand side).
// A force element has the members of SpringDamper's interface:
//   add_forces(q, v, a, nut_gradient, forces, elastic, damping_power)
//   add_stiffness(K, a), add_damping(C), damping_power(v), stiffness_at(a, &dk)
//   and the field on_screw (its coordinates need the nut on the screw).
template <class... Types>
struct ForceElementLists {
  std::tuple<std::vector<Types>...> lists;

  template <class T>
  std::vector<T>& of() {
    return std::get<std::vector<T>>(lists);
  }
  template <class T>
  const std::vector<T>& of() const {
    return std::get<std::vector<T>>(lists);
  }
  // True if there is no force element of any type.
  bool empty() const {
    return std::apply([](const auto&... list) { return (list.empty() && ...); }, lists);
  }
  // Calls f(element) for every element, type by type.
  template <class F>
  void for_each(F&& f) const {
    std::apply([&](const auto&... list) { (visit_list(list, f), ...); }, lists);
  }
  template <class F>
  void for_each(F&& f) {
    std::apply([&](auto&... list) { (visit_list(list, f), ...); }, lists);
  }

 private:
  template <class List, class F>
  static void visit_list(List& list, F& f) {
    for (auto& element : list) f(element);
  }
};

// The force elements' types (a new element with a scene section is a
// SectionForce, not a type here).
using ForceElements = ForceElementLists<SpringDamper, EndStop, SectionForce>;

struct DriveElements {
  std::vector<std::string> coordinates;  // their names, in order
  std::vector<RigidBody> bodies;
  ForceElements forces;  // springs, dampers, supports
  std::optional<ThreadPair> thread;
  Motor motor;
  AxialLoad load;
  std::optional<PreloadedNut> preloaded_nut;  // on the thread without play (any concept)
  // The motor's friction and a lossy or worm stage (rigid drive without play).
  std::optional<TrainFriction> train_friction;
  // The elements with states, events or a Moreau-Jean part of their own
  // (model/element.hpp: a DC motor, ...), in the registry's order.
  std::vector<std::shared_ptr<const Element>> elements;
  std::vector<ExactEndStop> exact_stops;  // end_stops.contact = "exact" (not force elements)
  // The coordinates that turn with the rotor and those that translate with
  // the load in a rigid-body motion of the drive (consistent_velocity).
  std::vector<int> rotating_group, translating_group;

  int coordinate_count() const noexcept { return static_cast<int>(coordinates.size()); }
  const std::vector<SpringDamper>& springs() const { return forces.of<SpringDamper>(); }
  // The penalty end stops of the load's travel (elements/end_stop.hpp).
  const std::vector<EndStop>& end_stops() const { return forces.of<EndStop>(); }
};

// The elements of the drive `p` describes, its values checked (raises
// InvalidArgument naming the key, the value and the valid range). Normalizes
// p: exact contacts without play are the thread without play.
DriveElements build_drive_elements(DriveParameters& p);

// The housing's vibration of p (loads.base_acceleration,
// loads.base_angular_acceleration) into e.elements, its weights from e's bodies
// (none where both are a constant 0). Refuses the angular one behind a gear
// stage (the rotor's axis relative to the screw's is not modelled).
void build_base_excitation(const DriveParameters& p, DriveElements& e);
// The first base excitation p gives, as "loads.<key> = <load>"; "" for none.
std::string given_base_excitation(const DriveParameters& p);

// Whether p has end stops of contact "exact" (elements/end_stops.cpp).
bool has_exact_end_stops(const DriveParameters& p);

// Why the event-driven scheme cannot run the train's friction stages of p
// (the concept, play, a thread law beyond plain Coulomb's; "" where it
// can): they run there on Moreau-Jean only (drive/integrators.cpp).
std::string train_event_driven_obstacle(const DriveParameters& p, const friction::Law& law);

}  // namespace leadscrew::model::elements
