// What an element of the drive declares once, when a run's system is built:
// its internal states in y (a DC motor's current, LuGre's bristle
// deflection, a stage's loss integral), its result channels with their SI
// unit and their role in the energy account. StateLayout allocates the
// states' slots from the declarations, in the registry's order
// (element_registry.cpp); the channel list (channels.cpp), the energy
// account's lists of the result checks (checks.cpp) and the channels' units
// (model::drive_channel_units, the binding _core.drive_channel_units) are built
// from them. Internal to cpp/src/model (docs/architecture.md, "Adding an
// element").
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "leadscrew/friction/law.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model::drive {

// A channel's part in the energy account (ResultCheckSpec's lists):
//   none          a value (a current, a force of the element's own)
//   work          work put in (either sign), added to the account's work
//   stored        energy stored (>= 0, starting at 0: a magnetic energy)
//   loss          a loss (>= 0, never falling), an integral in y
//   load_force    an applied force's channel [N] (the energies' round-off)
//   load_torque   an applied torque's channel [N m], over the lever
//   flank_normal  the normal force the friction coefficient multiplies
//                 (ResultCheckSpec::normal; a lift-off preloaded nut's)
// The values' channels come after the base's (the thread's forces, the
// play); work and losses after impact_loss; stored energies after elastic;
// each group in the registry's order of the elements and each element's
// order of declaration.
enum class Role { none, work, stored, loss, load_force, load_torque, flank_normal };

// The most channels a model's elements declare together (ChannelState's
// values: no allocation per output row; StateLayout refuses more).
constexpr int kMaxElementChannels = 16;

// A result channel: its name, its SI unit as leadscrew.units writes it
// ("m", "N*m", "J", "" for a flag) and its role.
struct ChannelSpec {
  const char* name;
  const char* unit;
  Role role;
};

// One element's declaration for a model (empty where the model has none of
// that kind).
struct Declaration {
  int kind = -1;                     // its index in element_kinds() (the registry's order)
  std::vector<const char*> states;   // its internal states in y, in order (names)
  std::vector<ChannelSpec> channels; // its result channels, in order
  // Energy that is kinetic-like, E = m x'^2 / 2 in a state of its own (a DC
  // motor's magnetic energy L i^2 / 2: m = L): the result checks' momentum
  // bound (ResultCheckSpec::momentum_factor).
  double momentum_mass = 0.0;
  // The stiffness of its elastic energy [N/m] (the checks' force bound).
  double stiffness = 0.0;
  // The normal force the friction coefficient multiplies at a row's normal
  // and friction force (ResultCheckSpec::flank_normal; empty: none).
  std::function<double(double normal, double friction)> flank_normal;
  // What of its channels' values follows from the row's coordinates alone
  // (values: its own, from first_channel), added for every driver after
  // the event-driven driver's elements wrote theirs (Element::output;
  // Moreau-Jean has none): the penalty end stops' force. Empty: none.
  std::function<void(const CoordinateVector& q, const CoordinateVector& v, double* values)>
      add_from_coordinates;
  // The model's element it declares (model/element.hpp): its index in
  // DriveElements::elements (-1: a kind the drivers handle themselves).
  int element = -1;
  // Filled by StateLayout: its first state's index in y, its first
  // channel's index in ChannelState::values.
  int first_state = -1, first_channel = -1;

  bool empty() const {
    return states.empty() && channels.empty() && momentum_mass == 0.0 && stiffness == 0.0 &&
           !flank_normal && !add_from_coordinates;
  }
};

// A registered kind of element (element_registry.cpp): its name, every
// channel it may declare (the units' table) and its declaration for a
// model; `law`: the friction law that runs on the thread (its own states,
// Law::state_names, are declared through it).
struct ElementKind {
  const char* name;
  std::vector<ChannelSpec> catalog;
  void (*declare)(const DriveModel& model, const friction::Law& law, Declaration& declaration);
};

// The registered kinds, in the registry's order (the order of their states
// in y and of their channels).
const std::vector<const ElementKind*>& element_kinds();

// A model's non-empty declarations, in the registry's order (kind set).
std::vector<Declaration> declare_elements(const DriveModel& model, const friction::Law& law);

// An element kind's declare for a model's element (model/element.hpp) of
// that name: its own declaration (Element::declare), `element` set; none
// where the model has no such element.
void declare_model_element(const DriveModel& model, const char* name, Declaration& declaration);

}  // namespace leadscrew::model::drive
