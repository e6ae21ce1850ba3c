// The drive's result channels (channels.hpp).
#include "channels.hpp"

#include <cmath>

#include "state_layout.hpp"

namespace leadscrew::model::drive {

std::vector<std::string> drive_channel_names(const DriveModel& model) {
  std::vector<std::string> names = {"u_load",        "v_load",      "phi_drive",
                                    "omega_drive",   "drive_torque", "axial_force",
                                    "normal_force",  "friction_force", "slip_velocity",
                                    "stick"};
  if (!model.bilateral_thread()) {
    names.push_back("gap");
    names.push_back("play");
  }
  if (model.law().resolution() == friction::Resolution::bristle)
    names.push_back("bristle_deflection");
  const bool dc = model.dc_motor() != nullptr;
  if (dc) {
    names.push_back("motor_current");
    names.push_back("motor_voltage");
  }
  // The end stops' force on the load along +u (elements/end_stop.hpp).
  if (model.parameters().end_stops != EndStopContact::none) names.push_back("stop_force");
  // A lift-off preloaded nut (elements/preloaded_nut.hpp).
  if (model.preloaded_nut() && model.preloaded_nut()->lift_off)
    for (const char* name : {"preload_force", "normal_force_a", "flank_normal"})
      names.push_back(name);
  const int n = model.coordinate_count();
  for (int i = 1; i < n - 1; ++i) {
    const std::string& name = model.coordinate_names()[i];
    names.push_back(name);
    names.push_back((name[0] == 'u' ? "v" : "omega") + name.substr(name.find('_')));
  }
  for (const char* name : {"work_drive", "work_axial", "friction_loss", "damping_loss",
                           "contact_loss", "impact_loss"})
    names.push_back(name);
  if (dc) names.push_back("copper_loss");
  const elements::TrainFriction* train = model.train_friction();
  if (train && train->motor_friction_present()) names.push_back("motor_friction_loss");
  if (train && train->stage) names.push_back("gear_loss");
  names.push_back("kinetic");
  names.push_back("elastic");
  if (dc) names.push_back("magnetic_energy");
  names.push_back("energy_residual");
  return names;
}

ChannelState channel_state(const DriveDynamics& dynamics) {
  return {dynamics.q(),
          dynamics.v(),
          dynamics.axial_force(),
          dynamics.slip_velocity(),
          dynamics.play(),
          dynamics.kinetic_energy(),
          dynamics.elastic_energy() + dynamics.contact_energy()};
}

void write_drive_channels(const DriveModel& model, const ChannelState& state,
                          const ContactForces& forces, const double* energy, double impact_loss,
                          double kinetic0, double elastic0, double* out) {
  const DriveParameters& p = model.parameters();
  const CoordinateVector& q = state.q;
  const CoordinateVector& v = state.v;
  const int n = model.coordinate_count();
  int k = 0;
  out[k++] = q[model.load()];
  out[k++] = v[model.load()];
  out[k++] = p.rotor_angle + model.gear().rotor_angle(q[model.rotor()]);
  out[k++] = model.gear().rotor_speed(v[model.rotor()]);
  out[k++] = forces.motor_torque;
  out[k++] = state.axial_force;
  out[k++] = forces.normal;
  out[k++] = forces.friction;
  out[k++] = state.slip_velocity;
  out[k++] = forces.stick ? 1.0 : 0.0;
  if (!model.bilateral_thread()) {
    out[k++] = 0.5 * p.clearance - std::abs(state.play);
    out[k++] = state.play;
  }
  if (model.law().resolution() == friction::Resolution::bristle) out[k++] = state.bristle;
  const bool dc = model.dc_motor() != nullptr;
  if (dc) {
    out[k++] = state.motor_current;
    out[k++] = state.motor_voltage;
  }
  if (p.end_stops != EndStopContact::none) {
    double stop_force = state.stop_force;
    for (const elements::EndStop& stop : model.elements().end_stops())
      stop_force += stop.force_on_load(q[model.load()], v[model.load()]);
    out[k++] = stop_force;
  }
  if (model.preloaded_nut() && model.preloaded_nut()->lift_off) {
    out[k++] = state.preload_force;
    out[k++] = state.normal_force_a;
    out[k++] = state.flank_normal;
  }
  for (int i = 1; i < n - 1; ++i) {
    out[k++] = q[i];
    out[k++] = v[i];
  }
  const double kinetic = state.kinetic;
  const double elastic = state.elastic;
  for (int e = 0; e < kEnergyCount; ++e) out[k++] = energy[e];
  out[k++] = impact_loss;
  if (dc) out[k++] = state.copper_loss;
  const elements::TrainFriction* train = model.train_friction();
  if (train && train->motor_friction_present()) out[k++] = state.motor_friction_loss;
  if (train && train->stage) out[k++] = state.gear_loss;
  out[k++] = kinetic;
  out[k++] = elastic;
  // (A DC motor's current, and so its magnetic energy, starts at 0.)
  if (dc) out[k++] = state.magnetic;
  out[k++] = energy[kWorkDrive] + energy[kWorkAxial] -
             (kinetic - kinetic0 + elastic - elastic0 + energy[kFrictionLoss] +
              energy[kDampingLoss] + energy[kContactLoss] + impact_loss + state.copper_loss +
              state.magnetic + state.motor_friction_loss + state.gear_loss);
}

}  // namespace leadscrew::model::drive
