// The co-simulation variables of a drive (model/cosim.hpp).
#include "leadscrew/model/cosim.hpp"

#include <algorithm>

#include "drive/declaration.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/friction/law.hpp"

namespace leadscrew::model {

namespace {

constexpr unsigned kInputs = 1, kOutputs = 10, kLawParameters = 100, kBodyParameters = 200;

struct Output {
  const char* name;
  const char* unit;
  const char* description;
};
const Output kOutputList[] = {
    {"u_load", "m", "the load's displacement along +x"},
    {"v_load", "m/s", "the load's velocity"},
    {"phi_drive", "rad", "the rotor's angle about +x"},
    {"omega_drive", "rad/s", "the rotor's speed"},
    {"normal_force", "N", "the flank normal force on the screw"},
    {"friction_force", "N", "the flank friction force on the screw (helix tangent)"},
    {"stick", "", "the thread sticks"},
    {"friction_loss", "J", "the work friction dissipated since the start"},
};
// Where an element drives the rotor (a DC motor) its output
// (RotorDrive::output), and where the torque is no input (such an element,
// a speed-controlled drive) the torque: after the outputs above.
const Output kTorqueOutput = {"drive_torque", "N.m",
                              "the motor's torque on the rotor about +x (what the motor supplies)"};

// The drive's parameters an FMU exposes, and the drives that have them.
// (Then the elements' sections' numbers that are co-simulation parameters,
// SectionField::fmi_unit, where the section is present: section_parameters.)
enum class Has { every_drive, flexible_drive };
struct Body {
  const char* name;
  const char* unit;
  Has has;
  const char* description;
};
const Body kBodyList[] = {
    {"rotor_inertia", "kg.m2", Has::every_drive, "the rotor's polar moment of inertia"},
    {"load_mass", "kg", Has::every_drive, "the load's mass"},
    {"screw_mass", "kg", Has::every_drive, "the screw's mass"},
    {"screw_inertia", "kg.m2", Has::every_drive, "the screw's polar moment of inertia"},
    {"nut_mass", "kg", Has::every_drive, "the nut's mass"},
    {"nut_inertia", "kg.m2", Has::every_drive, "the nut's polar moment of inertia"},
    {"screw_axial_stiffness", "N/m", Has::flexible_drive, "the screw's axial stiffness (0: from its geometry)"},
    {"screw_torsional_stiffness", "N.m/rad", Has::flexible_drive,
     "the screw's torsional stiffness (0: from its geometry)"},
    {"nut_axial_stiffness", "N/m", Has::flexible_drive, "the nut's axial stiffness"},
    {"nut_torsional_stiffness", "N.m/rad", Has::flexible_drive, "the nut's torsional stiffness"},
};

double DriveParameters::*field(const char* name) {
  for (const ScalarField& f : scalar_fields())
    if (std::string(f.name) == name) return f.member;
  throw InvalidArgument(std::string("no parameter ") + name);
}

bool shown(const DriveParameters& p, const Body& body) {
  switch (body.has) {
    case Has::flexible_drive:
      return p.concept != Concept::rigid;
    default:
      return true;
  }
}

// The elements' sections' co-simulation parameters, in the registry's
// order, after the body list's references.
struct SectionParameter {
  const SectionType* type;
  int field;
};
const std::vector<SectionParameter>& section_parameters() {
  static const std::vector<SectionParameter> list = [] {
    std::vector<SectionParameter> out;
    for (const SectionType& type : element_section_types())
      for (std::size_t i = 0; i < type.fields.size(); ++i)
        if (type.fields[i].fmi_unit != nullptr) out.push_back({&type, static_cast<int>(i)});
    return out;
  }();
  return list;
}
constexpr unsigned kSectionParameters =
    kBodyParameters + static_cast<unsigned>(std::size(kBodyList));

// The law's parameters by key with its defaults filled, in its order.
friction::LawValues law_values(const DriveParameters& p) {
  const friction::LawType& type = friction::law_type(p.friction);
  friction::LawValues given = p.friction_values;
  for (const friction::ParameterInfo& info : type.parameters) {
    if (std::string(info.key) == "mu") given.emplace_back("mu", p.mu);
    if (std::string(info.key) == "k_v") given.emplace_back("k_v", p.k_v);
  }
  const std::vector<double> values = friction::complete_values(type, given);
  friction::LawValues out;
  for (std::size_t i = 0; i < type.parameters.size(); ++i)
    out.emplace_back(type.parameters[i].key, values[i]);
  return out;
}

std::string fmi_unit(const std::string& unit) {
  // The law registry's SI units in FMI's unit names.
  std::string out = unit;
  std::replace(out.begin(), out.end(), '*', '.');
  return out;
}

// Every channel the drive's elements declare (drive/declaration.hpp: an end
// stop's stop_force, a load spring's force, a DC motor's voltage and
// energies, the stages' losses, ...), as outputs after the fixed ones,
// in the registry's order; a name already listed is not repeated.
void add_element_outputs(const DriveParameters& p, std::vector<CosimVariable>& out) {
  const DriveModel model(p);
  unsigned reference = kOutputs + static_cast<unsigned>(std::size(kOutputList)) + 2;
  for (const drive::Declaration& declaration : drive::declare_elements(model, model.law()))
    for (const drive::ChannelSpec& c : declaration.channels) {
      const auto listed = [&](const CosimVariable& v) { return v.name == c.name; };
      if (std::any_of(out.begin(), out.end(), listed)) continue;
      if (reference >= kLawParameters)
        throw InvalidArgument("the drive declares more channels than an FMU's outputs hold");
      out.push_back({c.name, reference++, CosimVariable::Kind::output, false, fmi_unit(c.unit),
                     0.0, std::string("the channel ") + c.name + " of the drive's elements"});
    }
}

}  // namespace

std::vector<CosimVariable> cosim_variables(const DriveParameters& p) {
  using Kind = CosimVariable::Kind;
  std::vector<CosimVariable> out;
  const SectionType* driver = rotor_drive_section(p);
  if (driver != nullptr) {
    const SectionInput& input = driver->inputs.front();  // (the rotor's drive)
    out.push_back({input.name, kInputs, Kind::input, false, input.fmi_unit,
                   section_input(p, *driver, 0)(0.0), input.doc});
  } else if (p.speed_controlled)
    out.push_back({"drive_speed", kInputs, Kind::input, false, "rad/s", p.drive_speed(0.0),
                   "the rotor's prescribed speed about +x: a new value is reached by a linear "
                   "ramp over the next step, then held"});
  else
    out.push_back({"drive_torque", kInputs, Kind::input, false, "N.m", p.drive_torque(0.0),
                   "the motor's torque on the rotor about +x, held over a step"});
  out.push_back({"axial_force", kInputs + 1, Kind::input, false, "N", p.axial_force(0.0),
                 "the axial force on the load along +x, held over a step"});
  unsigned reference = kOutputs;
  for (const Output& o : kOutputList) {
    const bool boolean = std::string(o.name) == "stick";
    out.push_back({o.name, reference++, Kind::output, boolean, o.unit, 0.0, o.description});
  }
  if (driver != nullptr)
    out.push_back({driver->rotor_drive->output, reference, Kind::output, false,
                   driver->rotor_drive->output_unit, 0.0, driver->rotor_drive->output_doc});
  if (driver != nullptr || p.speed_controlled)
    out.push_back({kTorqueOutput.name, reference + 1, Kind::output, false, kTorqueOutput.unit, 0.0,
                   kTorqueOutput.description});
  add_element_outputs(p, out);
  const friction::LawType& type = friction::law_type(p.friction);
  const friction::LawValues law = law_values(p);
  for (std::size_t i = 0; i < law.size(); ++i)
    out.push_back({law[i].first, kLawParameters + static_cast<unsigned>(i), Kind::parameter,
                   false, fmi_unit(type.parameters[i].unit), law[i].second,
                   type.parameters[i].doc});
  for (std::size_t i = 0; i < std::size(kBodyList); ++i) {
    const Body& body = kBodyList[i];
    if (!shown(p, body)) continue;
    out.push_back({body.name, kBodyParameters + static_cast<unsigned>(i), Kind::parameter, false,
                   body.unit, p.*field(body.name), body.description});
  }
  const std::vector<SectionParameter>& sections = section_parameters();
  for (std::size_t i = 0; i < sections.size(); ++i) {
    const SectionType& type = *sections[i].type;
    if (find_section(p, type.name) == nullptr) continue;
    const SectionField& f = type.fields[static_cast<std::size_t>(sections[i].field)];
    out.push_back({f.attribute, kSectionParameters + static_cast<unsigned>(i), Kind::parameter,
                   false, f.fmi_unit, section_number(p, type, sections[i].field), f.fmi_doc});
  }
  return out;
}

void set_cosim_parameter(DriveParameters& p, unsigned reference, double value) {
  if (reference >= kLawParameters && reference < kBodyParameters) {
    // (By the registry's keys, not the law's values: a value set out of
    // range is refused where the drive is built, and a later value in range
    // replaces it.)
    const std::vector<friction::ParameterInfo>& keys = friction::law_type(p.friction).parameters;
    const std::size_t i = reference - kLawParameters;
    if (i < keys.size()) {
      const std::string key = keys[i].key;
      if (key == "mu") {
        p.mu = value;
      } else if (key == "k_v") {
        p.k_v = value;
      } else {
        auto at = std::find_if(p.friction_values.begin(), p.friction_values.end(),
                               [&](const auto& entry) { return entry.first == key; });
        if (at == p.friction_values.end())
          p.friction_values.emplace_back(key, value);
        else
          at->second = value;
      }
      return;
    }
  }
  if (reference >= kBodyParameters && reference - kBodyParameters < std::size(kBodyList)) {
    const Body& body = kBodyList[reference - kBodyParameters];
    if (shown(p, body)) {
      p.*field(body.name) = value;
      return;
    }
  }
  const std::vector<SectionParameter>& sections = section_parameters();
  if (reference >= kSectionParameters && reference - kSectionParameters < sections.size()) {
    const SectionParameter& at = sections[reference - kSectionParameters];
    if (find_section(p, at.type->name) != nullptr) {
      set_section_number(p, *at.type, at.field, value);
      return;
    }
  }
  throw InvalidArgument("value reference " + std::to_string(reference) +
                        " is invalid: it is none of the drive's parameters");
}

}  // namespace leadscrew::model
