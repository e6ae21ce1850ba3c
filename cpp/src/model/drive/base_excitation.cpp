// The housing's vibration's declaration (base_excitation.hpp).
#include "base_excitation.hpp"

namespace leadscrew::model::drive {

namespace {

void declare(const DriveModel& model, bool bristle, Declaration& d) {
  (void)bristle;
  if (model.base() == nullptr) return;
  d.states = {"base_work"};
  d.channels = base_excitation_kind().catalog;
}

}  // namespace

const ElementKind& base_excitation_kind() {
  static const ElementKind kind{"base_excitation",
                                {{"base_force", "N", Role::load_force},
                                 {"base_torque", "N*m", Role::load_torque},
                                 {"base_work", "J", Role::work}},
                                &declare};
  return kind;
}

}  // namespace leadscrew::model::drive
