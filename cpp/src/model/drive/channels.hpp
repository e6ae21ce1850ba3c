// The drive's result channels: their names (the thread and motor forces,
// the play, the elements' declared channels, the coordinates, the energy
// account) and the writing of one output row, shared by the event-driven and
// Moreau-Jean systems. Internal to cpp/src/model.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "declaration.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_dynamics.hpp"
#include "state_layout.hpp"

namespace leadscrew::model::drive {

// The base channels every drive writes ahead of the elements' (the thread
// pair's, the motor's, the axial load's): name, unit, role.
const std::vector<ChannelSpec>& base_channels();
// The energy account's channels every drive writes: the work and loss
// integrals (Energy's order), the impact loss, the stored energies and the
// residual.
const std::vector<ChannelSpec>& account_channels();

// The names of a drive's result channels, in the order write_drive_channels
// writes them.
std::vector<std::string> drive_channel_names(const StateLayout& layout);

// Thread and motor forces at an output point (motor_torque: the torque on
// the rotor, before a gear stage).
struct ContactForces {
  double normal = 0.0, friction = 0.0, motor_torque = 0.0;
  bool stick = false;
  // A preloaded nut's half B's normal force (part of normal; 0 without one).
  double preload_normal = 0.0;
};

// The state of an output row besides the thread and motor forces.
struct ChannelState {
  const CoordinateVector& q;
  const CoordinateVector& v;
  double axial_force = 0.0, slip_velocity = 0.0, play = 0.0, kinetic = 0.0, elastic = 0.0;
  // The elements' declared channels' values, by their index
  // (Declaration::first_channel, StateLayout::find_channel): each element
  // writes its own.
  std::array<double, kMaxElementChannels> values{};
};

// From the state last set in dynamics.
ChannelState channel_state(const DriveDynamics& dynamics);

// Writes one output row. kinetic0, stored0: the kinetic and the other stored
// energies at t = 0 (the elastic and contact energies and the elements'
// energy terms, DriveDynamics::element_energy_terms), the energy residual's start.
void write_drive_channels(const StateLayout& layout, const ChannelState& state,
                          const ContactForces& forces, const double* energy, double impact_loss,
                          double kinetic0, double stored0, double* out);

}  // namespace leadscrew::model::drive
