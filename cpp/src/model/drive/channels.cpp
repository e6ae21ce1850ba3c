// The drive's result channels (channels.hpp).
#include "channels.hpp"

#include <cmath>

#include "leadscrew/model/drive_simulation.hpp"
#include "state_layout.hpp"

namespace leadscrew::model::drive {

namespace {

// A declared channel's group in the row: 0 the values (after the base's),
// 1 work and losses (after impact_loss), 2 stored energies (after elastic).
int group(Role role) {
  if (role == Role::work || role == Role::loss) return 1;
  return role == Role::stored ? 2 : 0;
}

// The thread's play: with play only (not on a bilateral thread).
const std::vector<ChannelSpec>& play_channels() {
  static const std::vector<ChannelSpec> channels = {{"gap", "m", Role::none},
                                                    {"play", "m", Role::none}};
  return channels;
}

}  // namespace

const std::vector<ChannelSpec>& base_channels() {
  static const std::vector<ChannelSpec> channels = {
      {"u_load", "m", Role::none},
      {"v_load", "m/s", Role::none},
      {"phi_drive", "rad", Role::none},
      {"omega_drive", "rad/s", Role::none},
      {"drive_torque", "N*m", Role::load_torque},
      {"axial_force", "N", Role::load_force},
      {"normal_force", "N", Role::none},
      {"friction_force", "N", Role::none},
      {"slip_velocity", "m/s", Role::none},
      {"stick", "", Role::none}};  // a flag: 1 stick, 0 slip
  return channels;
}

const std::vector<ChannelSpec>& account_channels() {
  static const std::vector<ChannelSpec> channels = {
      {"work_drive", "J", Role::work},      {"work_axial", "J", Role::work},
      {"friction_loss", "J", Role::loss},   {"damping_loss", "J", Role::loss},
      {"contact_loss", "J", Role::loss},    {"impact_loss", "J", Role::loss},
      {"kinetic", "J", Role::stored},       {"elastic", "J", Role::stored},
      {"energy_residual", "J", Role::none}};
  return channels;
}

std::vector<std::string> drive_channel_names(const StateLayout& layout) {
  const DriveModel& model = layout.model();
  std::vector<std::string> names;
  for (const ChannelSpec& c : base_channels()) names.push_back(c.name);
  if (!model.bilateral_thread())
    for (const ChannelSpec& c : play_channels()) names.push_back(c.name);
  auto declared = [&](int g) {
    for (const Declaration& d : layout.declarations())
      for (const ChannelSpec& c : d.channels)
        if (group(c.role) == g) names.push_back(c.name);
  };
  declared(0);
  const int n = model.coordinate_count();
  for (int i = 1; i < n - 1; ++i) {
    const std::string& name = model.coordinate_names()[i];
    names.push_back(name);
    names.push_back((name[0] == 'u' ? "v" : "omega") + name.substr(name.find('_')));
  }
  const std::vector<ChannelSpec>& account = account_channels();
  for (int e = 0; e <= kEnergyCount; ++e) names.push_back(account[e].name);  // and impact_loss
  declared(1);
  names.push_back(account[kEnergyCount + 1].name);  // kinetic
  names.push_back(account[kEnergyCount + 2].name);  // elastic
  declared(2);
  names.push_back(account[kEnergyCount + 3].name);  // energy_residual
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

void write_drive_channels(const StateLayout& layout, const ChannelState& state,
                          const ContactForces& forces, const double* energy, double impact_loss,
                          double kinetic0, double stored0, double* out) {
  const DriveModel& model = layout.model();
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
  // The elements' values, with what follows from the coordinates alone.
  std::array<double, kMaxElementChannels> values = state.values;
  for (const Declaration& d : layout.declarations())
    if (d.add_from_coordinates) d.add_from_coordinates(q, v, values.data() + d.first_channel);
  auto declared = [&](int g) {
    for (const Declaration& d : layout.declarations())
      for (std::size_t c = 0; c < d.channels.size(); ++c)
        if (group(d.channels[c].role) == g)
          out[k++] = values[d.first_channel + static_cast<int>(c)];
  };
  declared(0);
  for (int i = 1; i < n - 1; ++i) {
    out[k++] = q[i];
    out[k++] = v[i];
  }
  const double kinetic = state.kinetic;
  const double elastic = state.elastic;
  for (int e = 0; e < kEnergyCount; ++e) out[k++] = energy[e];
  out[k++] = impact_loss;
  declared(1);
  out[k++] = kinetic;
  out[k++] = elastic;
  declared(2);
  // The residual: the work put in less the energy stored and lost, the
  // elements' terms in their order (a stored energy of theirs counted from
  // its value at t = 0, which stored0 holds: a DC motor's L i^2 / 2 of a
  // current that starts in equilibrium).
  double work = energy[kWorkDrive] + energy[kWorkAxial];
  double spent = kinetic - kinetic0 + elastic - stored0 + energy[kFrictionLoss] +
                 energy[kDampingLoss] + energy[kContactLoss] + impact_loss;
  for (const Declaration& d : layout.declarations())
    for (std::size_t c = 0; c < d.channels.size(); ++c) {
      const Role role = d.channels[c].role;
      const double value = values[d.first_channel + static_cast<int>(c)];
      if (role == Role::work) work += value;
      if (role == Role::loss || role == Role::stored) spent += value;
    }
  out[k++] = work - spent;
}

}  // namespace leadscrew::model::drive

namespace leadscrew::model {

std::vector<std::pair<std::string, std::string>> drive_channel_units() {
  using namespace drive;
  std::vector<std::pair<std::string, std::string>> units;
  for (const std::vector<ChannelSpec>* list : {&base_channels(), &play_channels(),
                                               &account_channels()})
    for (const ChannelSpec& c : *list) units.emplace_back(c.name, c.unit);
  for (const ElementKind* kind : element_kinds())
    for (const ChannelSpec& c : kind->catalog) units.emplace_back(c.name, c.unit);
  return units;
}

}  // namespace leadscrew::model
