// The drive's result channels: their names (the thread and motor forces,
// the play, the coordinates, the energy account) and the writing of one
// output row, shared by the event-driven and Moreau-Jean systems. Internal to
// cpp/src/model.
#pragma once

#include <string>
#include <vector>

#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model::drive {

// The names of a drive's result channels, in the order write_drive_channels
// writes them.
std::vector<std::string> drive_channel_names(const DriveModel& model);

// Thread and motor forces at an output point (motor_torque: the torque on
// the rotor, before a gear stage).
struct ContactForces {
  double normal = 0.0, friction = 0.0, motor_torque = 0.0;
  bool stick = false;
};

// The state of an output row besides the thread and motor forces.
struct ChannelState {
  const CoordinateVector& q;
  const CoordinateVector& v;
  double axial_force = 0.0, slip_velocity = 0.0, play = 0.0, kinetic = 0.0, elastic = 0.0;
  double bristle = 0.0;  // LuGre's bristle deflection z [m]
  // A DC motor's: its current [A], the driver's voltage [V], the copper
  // loss integral [J] and the magnetic energy L i^2 / 2 [J].
  double motor_current = 0.0, motor_voltage = 0.0, copper_loss = 0.0, magnetic = 0.0;
  // The exact end stops' force on the load [N] (the penalty stops' follows
  // from q and v).
  double stop_force = 0.0;
  // A lift-off preloaded nut's: the spring force S [N], half A's normal
  // force [N] and |N_A| + |N_B| [N] (elements/preloaded_nut.hpp).
  double preload_force = 0.0, normal_force_a = 0.0, flank_normal = 0.0;
  // The train's friction stages' loss integrals [J] (train_friction.hpp).
  double motor_friction_loss = 0.0, gear_loss = 0.0;
};

// From the state last set in dynamics.
ChannelState channel_state(const DriveDynamics& dynamics);

// Writes one output row.
void write_drive_channels(const DriveModel& model, const ChannelState& state,
                          const ContactForces& forces, const double* energy, double impact_loss,
                          double kinetic0, double elastic0, double* out);

}  // namespace leadscrew::model::drive
