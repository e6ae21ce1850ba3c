// The housing's vibration in the drivers (elements/base_excitation.hpp):
// its declaration (the base's work a state of y; the channels base_force
// [N] and base_torque [N*m], the largest inertial loads for the checks'
// bounds, and base_work [J], a work of the energy account) and its
// channels' values, written by the constrained solver and Moreau-Jean.
// Internal to cpp/src/model.
#pragma once

#include "channels.hpp"
#include "state_layout.hpp"

namespace leadscrew::model::drive {

const ElementKind& base_excitation_kind();

// Where the base's work and channels are in a layout (-1: the model has none).
struct BaseSlots {
  explicit BaseSlots(const StateLayout& layout)
      : state(layout.find_state("base_work")), channel(layout.find_channel("base_force")) {}
  int state, channel;

  // Its channels' values at the state `dynamics` was last set to, with the
  // work integral of y.
  void write(const DriveDynamics& dynamics, const double* y, ChannelState& out) const {
    if (state < 0) return;
    out.values[channel] = dynamics.base_force();
    out.values[channel + 1] = dynamics.base_torque();
    out.values[channel + 2] = y[state];
  }
};

}  // namespace leadscrew::model::drive
