// The nut's transverse slip on the flank (transverse_slip.cpp;
// docs/physics/transverse_slip.md): what the drivers share of it. Internal
// to cpp/src/model.
#pragma once

#include <string>

#include "channels.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_dynamics.hpp"
#include "state_layout.hpp"

namespace leadscrew::model::drive {

// Refuses (InvalidArgument naming loads.transverse_slip_velocity, the
// obstacle and what is supported) a transverse slip where the 2-D cone is
// not implemented: other concepts, elements, laws and integrators, and on
// the event-driven scheme a w held at zero over an interval (a table) or
// unknown ahead (a callable), and a set-valued cone's smooth phases on
// CVODE (smooth_integrator). Nothing without a transverse slip.
void check_transverse_slip(const DriveModel& model, const std::string& integrator,
                           const std::string& smooth_integrator, double t_end);

// Moreau-Jean's output row: the declared channels (w at the state set, the
// transverse friction given, the work integral of y); nothing without them.
void write_transverse_channels(const StateLayout& layout, const DriveDynamics& dynamics,
                               double transverse_friction, const double* y,
                               ChannelState& state);

}  // namespace leadscrew::model::drive
