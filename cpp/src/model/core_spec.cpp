// The core spec's one writer and one reader (model/core_spec.hpp). The TOML
// parser is toml++ (Debian's libtomlplusplus-dev), used header-only.
#include "leadscrew/model/core_spec.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#define TOML_HEADER_ONLY 1
#define TOML_ENABLE_FORMATTERS 0
#include <toml++/toml.h>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/thread/thread.hpp"
#include "leadscrew/model/elements/drive_elements.hpp"

namespace leadscrew::model {

namespace {

constexpr const char* kFormat = "leadscrew-core-spec";
constexpr int kVersion = 1;

// The shortest decimal that reads back as the same double, as a TOML float.
std::string number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buffer[64];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
  std::string text(buffer, end);
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string number_list(const std::vector<double>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + number(values[i]);
  return out + "]";
}

void write_load(std::ostringstream& out, const char* name, const Excitation& load,
                const char* unit) {
  const Excitation::Definition d = load.definition();
  if (d.kind == "callable")
    throw InvalidArgument(std::string("loads.") + name + " = " + load.describe() +
                          " is invalid in a core spec: a callable cannot be written to a file "
                          "(use a constant, a sine, a table, a random vibration or a record)");
  out << "\n[loads." << name << "]  # " << unit << "\ntype = " << quoted(d.kind) << "\n";
  if (d.kind == "constant") {
    out << "value = " << number(d.parameters[0]) << "\n";
  } else if (d.kind == "sine") {
    out << "amplitude = " << number(d.parameters[0]) << "\nomega = " << number(d.parameters[1])
        << "  # rad/s\nphase = " << number(d.parameters[2])
        << "  # rad\noffset = " << number(d.parameters[3]) << "\n";
  } else if (d.kind == "random") {
    out << "frequencies = " << number_list(d.times) << "  # Hz\npsd = " << number_list(d.values)
        << "  # (" << unit << ")^2/Hz\nseed = " << number(d.parameters[0])
        << "\nduration = " << number(d.parameters[1]) << "  # s\n";
  } else {
    out << "times = " << number_list(d.times) << "  # s\nvalues = " << number_list(d.values)
        << "\n";
    if (d.kind == "measured")
      out << "scale = " << number(d.parameters[0])
          << "\nrepeat = " << (d.parameters[1] == 1.0 ? "true" : "false") << "\n";
  }
}

// Reading: each table's keys are checked against the keys it takes.
class Reader {
 public:
  Reader(const toml::table& root, std::string source) : root_(root), source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw InvalidArgument((source_.empty() ? std::string("core spec") : source_) + ": " + path +
                          " " + what);
  }

  const toml::table* table(const toml::table& parent, const std::string& prefix,
                           const std::string& key) const {
    const toml::node* node = parent.get(key);
    if (!node) return nullptr;
    const toml::table* t = node->as_table();
    if (!t) fail(prefix + key, "is invalid: must be a table");
    return t;
  }

  void known(const toml::table& t, const std::string& prefix,
             const std::set<std::string>& keys) const {
    for (const auto& [key, node] : t) {
      const std::string k(key.str());
      if (!keys.count(k)) {
        std::string listed;
        for (const std::string& name : keys) listed += (listed.empty() ? "" : ", ") + name;
        fail(prefix + k, "is an unknown key: the keys here are " + listed);
      }
    }
  }

  // The value at key through `take` (false: of the wrong type, which
  // `must` describes); false where the key is left out.
  template <class Take>
  bool value(const toml::table& t, const std::string& prefix, const std::string& key,
             const char* must, Take take) const {
    const toml::node* node = t.get(key);
    if (!node) return false;
    if (!take(*node)) fail(prefix + key, std::string("is invalid: must be ") + must);
    return true;
  }

  static bool as_real(const toml::node& node, double& out) {
    if (const auto* f = node.as_floating_point()) {
      out = f->get();
      return true;
    }
    if (const auto* i = node.as_integer()) {
      out = static_cast<double>(i->get());
      return true;
    }
    return false;
  }

  bool real(const toml::table& t, const std::string& prefix, const std::string& key,
            double& out) const {
    return value(t, prefix, key, "a number (SI)",
                 [&](const toml::node& n) { return as_real(n, out); });
  }

  bool whole(const toml::table& t, const std::string& prefix, const std::string& key,
             long& out) const {
    return value(t, prefix, key, "an integer", [&](const toml::node& n) {
      const auto* i = n.as_integer();
      if (i) out = static_cast<long>(i->get());
      return i != nullptr;
    });
  }

  bool text(const toml::table& t, const std::string& prefix, const std::string& key,
            std::string& out) const {
    return value(t, prefix, key, "a string", [&](const toml::node& n) {
      const auto* s = n.as_string();
      if (s) out = s->get();
      return s != nullptr;
    });
  }

  bool flag(const toml::table& t, const std::string& prefix, const std::string& key,
            bool& out) const {
    return value(t, prefix, key, "true or false", [&](const toml::node& n) {
      const auto* b = n.as_boolean();
      if (b) out = b->get();
      return b != nullptr;
    });
  }

  std::vector<double> reals(const toml::table& t, const std::string& prefix,
                            const std::string& key) const {
    const toml::node* node = t.get(key);
    if (!node) fail(prefix + key, "is missing: a table load takes times and values");
    const toml::array* a = node->as_array();
    if (!a) fail(prefix + key, "is invalid: must be an array of numbers");
    std::vector<double> out;
    for (const toml::node& element : *a) {
      double x = 0.0;
      if (!as_real(element, x)) fail(prefix + key, "is invalid: must be an array of numbers");
      out.push_back(x);
    }
    return out;
  }

  Excitation load(const toml::table& t, const std::string& prefix) const {
    std::string type;
    if (!text(t, prefix, "type", type)) fail(prefix + "type", "is missing");
    // Errors of the values name the key (Excitation's own name the quantity).
    try {
      if (type == "constant") {
        known(t, prefix, {"type", "value"});
        double value = 0.0;
        if (!real(t, prefix, "value", value)) fail(prefix + "value", "is missing");
        return Excitation(ConstantExcitation{value});
      }
      if (type == "sine") {
        known(t, prefix, {"type", "amplitude", "omega", "phase", "offset"});
        SineExcitation s;
        if (!real(t, prefix, "amplitude", s.amplitude)) fail(prefix + "amplitude", "is missing");
        if (!real(t, prefix, "omega", s.omega)) fail(prefix + "omega", "is missing");
        real(t, prefix, "phase", s.phase);
        real(t, prefix, "offset", s.offset);
        return Excitation(s);
      }
      if (type == "table") {
        known(t, prefix, {"type", "times", "values"});
        return Excitation(TableExcitation{reals(t, prefix, "times"), reals(t, prefix, "values")});
      }
      if (type == "random") {
        known(t, prefix, {"type", "frequencies", "psd", "seed", "duration"});
        RandomVibrationSpec r{reals(t, prefix, "frequencies"), reals(t, prefix, "psd")};
        real(t, prefix, "seed", r.seed);
        real(t, prefix, "duration", r.duration);
        return Excitation(r);
      }
      if (type == "measured") {
        known(t, prefix, {"type", "times", "values", "scale", "repeat"});
        MeasuredSpec m{reals(t, prefix, "times"), reals(t, prefix, "values")};
        real(t, prefix, "scale", m.scale);
        flag(t, prefix, "repeat", m.repeat);
        return Excitation(m);
      }
    } catch (const InvalidArgument& e) {
      if (std::string(e.what()).rfind(source_.empty() ? "core spec" : source_, 0) == 0) throw;
      fail(prefix.substr(0, prefix.size() - 1), std::string("is invalid: ") + e.what());
    }
    fail(prefix + "type", "= " + quoted(type) +
                              " is invalid: must be \"constant\", \"sine\", \"table\", "
                              "\"random\" or \"measured\"");
  }

  // An enumeration's name through its parser, the error naming the key.
  template <class Parse>
  void choice(const toml::table& t, const std::string& prefix, const std::string& key,
              Parse parse) const {
    std::string name;
    if (!text(t, prefix, key, name)) return;
    try {
      parse(name);
    } catch (const InvalidArgument& e) {
      fail(prefix + key, std::string("is invalid: ") + e.what());
    }
  }

 private:
  const toml::table& root_;
  std::string source_;
};

// [drive]: the concept, the drive, support, backlash contact, initial state,
// gear and each element section's presence.
void read_drive_section(const Reader& r, const toml::table& t, DriveParameters& p) {
  const std::string at = "drive.";
  std::set<std::string> names = {"concept", "drive", "support", "backlash", "initial_state",
                                 "speed_controlled", "gear"};
  for (const SectionType& type : element_section_types()) {
    const std::string name = type.presence_attribute();
    names.insert(name);
    if (type.flag != nullptr) {
      bool present = false;
      if (r.flag(t, at, name, present)) set_section_presence(p, type, present ? "true" : "false");
    } else {
      r.choice(t, at, name, [&](const std::string& v) { set_section_presence(p, type, v); });
    }
  }
  r.known(t, at, names);
  r.choice(t, at, "concept", [&](const std::string& v) { p.concept = parse_concept(v); });
  r.choice(t, at, "drive", [&](const std::string& v) { p.drive = parse_drive(v); });
  r.choice(t, at, "support", [&](const std::string& v) { p.support = parse_support(v); });
  r.choice(t, at, "backlash",
           [&](const std::string& v) { p.backlash = parse_backlash_contact(v); });
  r.choice(t, at, "initial_state",
           [&](const std::string& v) { p.initial_state = parse_initial_state(v); });
  r.flag(t, at, "speed_controlled", p.speed_controlled);
  r.choice(t, at, "gear", [&](const std::string& v) { p.gear = parse_gear_type(v); });
}

// [thread]: the thread's geometry (pitch, mean diameter, starts, included
// flank angle, hand), checked as a whole by Thread.
void read_thread_section(const Reader& r, const toml::table& t, DriveParameters& p) {
  const std::string at = "thread.";
  r.known(t, at, {"pitch", "mean_diameter", "starts", "flank_angle", "hand"});
  double pitch = p.thread.pitch(), diameter = p.thread.mean_diameter();
  double flank = p.thread.flank_angle();
  long starts = p.thread.starts();
  Hand hand = p.thread.hand();
  r.real(t, at, "pitch", pitch);
  r.real(t, at, "mean_diameter", diameter);
  r.whole(t, at, "starts", starts);
  r.real(t, at, "flank_angle", flank);
  r.choice(t, at, "hand", [&](const std::string& v) { hand = parse_hand(v); });
  try {
    p.thread = Thread(pitch, diameter, static_cast<int>(starts), flank, hand);
  } catch (const InvalidArgument& e) {
    r.fail("thread", std::string("is invalid: ") + e.what());
  }
}

// [friction]: the friction law's name and its values.
void read_friction_section(const Reader& r, const toml::table& t, DriveParameters& p) {
  const std::string at = "friction.";
  r.known(t, at, {"law", "values"});
  r.choice(t, at, "law", [&](const std::string& v) {
    friction::law_type(v);  // raises for an unknown law
    p.friction = v;
  });
  if (const toml::table* values = r.table(t, at, "values")) {
    p.friction_values.clear();
    for (const auto& [key, node] : *values) {
      double value = 0.0;
      r.real(*values, at + "values.", std::string(key.str()), value);
      p.friction_values.emplace_back(std::string(key.str()), value);
    }
  }
}

// [parameters]: the drive's scalar numbers and the element sections' numbers.
void read_parameters_section(const Reader& r, const toml::table& t, DriveParameters& p) {
  std::set<std::string> names;
  for (const ScalarField& field : scalar_fields()) {
    names.insert(field.name);
    r.real(t, "parameters.", field.name, p.*(field.member));
  }
  for (const SectionType& type : element_section_types())
    for (std::size_t i = 0; i < type.fields.size(); ++i) {
      const SectionField& f = type.fields[i];
      if (f.kind != SectionField::Kind::number || f.attribute == nullptr) continue;
      names.insert(f.attribute);
      double value = 0.0;
      if (r.real(t, "parameters.", f.attribute, value))
        set_section_number(p, type, static_cast<int>(i), value);
    }
  r.known(t, "parameters.", names);
}

// [loads]: the excitations (drive torque or speed, axial force, the housing's
// vibration, transverse slip, the elements' inputs such as a motor's voltage).
void read_loads_section(const Reader& r, const toml::table& t, DriveParameters& p) {
  // The drive's own loads by their keys (the elements' inputs join them).
  const std::pair<const char*, Excitation DriveParameters::*> drive_loads[] = {
      {"drive_torque", &DriveParameters::drive_torque},
      {"drive_speed", &DriveParameters::drive_speed},
      {"axial_force", &DriveParameters::axial_force},
      {"base_acceleration", &DriveParameters::base_acceleration},
      {"base_angular_acceleration", &DriveParameters::base_angular_acceleration},
      {"transverse_slip_velocity", &DriveParameters::transverse_slip_velocity}};
  std::set<std::string> names;
  for (const auto& load : drive_loads) names.insert(load.first);
  for (const SectionType& type : element_section_types())
    for (const SectionInput& input : type.inputs) names.insert(input.name);
  r.known(t, "loads.", names);
  for (const SectionType& type : element_section_types())
    for (std::size_t i = 0; i < type.inputs.size(); ++i) {
      const std::string name = type.inputs[i].name;
      if (const toml::table* l = r.table(t, "loads.", name))
        set_section_input(p, type, static_cast<int>(i), r.load(*l, "loads." + name + "."));
    }
  for (const auto& [name, member] : drive_loads)
    if (const toml::table* l = r.table(t, "loads.", name))
      p.*member = r.load(*l, "loads." + std::string(name) + ".");
}

// [options]: the integrators, tolerances, step and event limits.
void read_options_section(const Reader& r, const toml::table& t, DriveSimulationOptions& o) {
  const std::string at = "options.";
  r.known(t, at, {"integrator", "smooth_integrator", "rtol", "atol", "max_steps",
                  "max_events", "max_step", "first_step", "max_order", "bounce_threshold"});
  r.text(t, at, "integrator", o.integrator);
  r.text(t, at, "smooth_integrator", o.smooth_integrator);
  r.real(t, at, "rtol", o.integrator_options.rtol);
  r.real(t, at, "atol", o.integrator_options.atol);
  r.whole(t, at, "max_steps", o.integrator_options.max_steps);
  r.whole(t, at, "max_events", o.max_events);
  r.real(t, at, "max_step", o.integrator_options.max_step);
  r.real(t, at, "first_step", o.integrator_options.first_step);
  long order = 0;
  if (r.whole(t, at, "max_order", order)) o.integrator_options.max_order = static_cast<int>(order);
  r.real(t, at, "bounce_threshold", o.bounce_threshold);
}

}  // namespace

std::string write_core_spec(const DriveParameters& p, const DriveSimulationOptions& options) {
  std::ostringstream out;
  out << "# leadscrew core spec: the drive as the core runs it. Every value SI\n"
         "# (m, kg, s, N, N*m, rad), every default and derived value explicit.\n"
         "format = " << quoted(kFormat) << "\nversion = " << kVersion << "\n";
  out << "\n[drive]\nconcept = " << quoted(concept_name(p.concept))
      << "\ndrive = " << quoted(drive_name(p.drive))
      << "\nsupport = " << quoted(support_name(p.support))
      << "\nbacklash = " << quoted(backlash_contact_name(p.backlash))
      << "\ninitial_state = " << quoted(initial_state_name(p.initial_state))
      << "\nspeed_controlled = " << (p.speed_controlled ? "true" : "false")
      << "\ngear = " << quoted(gear_type_name(p.gear));
  // The elements' sections (element_section.hpp): each one's presence here,
  // its numbers in [parameters] by their attributes.
  for (const SectionType& type : element_section_types()) {
    const std::string presence = section_presence(p, type);
    out << "\n" << type.presence_attribute() << " = "
        << (type.flag != nullptr ? presence : quoted(presence));
  }
  out << "\n";
  out << "\n[thread]\npitch = " << number(p.thread.pitch())
      << "\nmean_diameter = " << number(p.thread.mean_diameter())
      << "\nstarts = " << p.thread.starts() << "\nflank_angle = " << number(p.thread.flank_angle())
      << "  # rad, included\nhand = " << quoted(hand_name(p.thread.hand())) << "\n";
  out << "\n[friction]\nlaw = " << quoted(p.friction) << "\n\n[friction.values]\n";
  for (const auto& [key, value] : p.friction_values) out << key << " = " << number(value) << "\n";
  out << "\n[parameters]\n";
  for (const ScalarField& field : scalar_fields())
    out << field.name << " = " << number(p.*(field.member)) << "\n";
  for (const SectionType& type : element_section_types())
    for (std::size_t i = 0; i < type.fields.size(); ++i)
      if (type.fields[i].kind == SectionField::Kind::number && type.fields[i].attribute)
        out << type.fields[i].attribute << " = "
            << number(section_number(p, type, static_cast<int>(i))) << "\n";
  write_load(out, "drive_torque", p.drive_torque, "N*m");
  write_load(out, "drive_speed", p.drive_speed, "rad/s");
  write_load(out, "axial_force", p.axial_force, "N");
  // The housing's vibration where it has one (a spec without it is at rest).
  if (!elements::given_base_excitation(p).empty()) {
    write_load(out, "base_acceleration", p.base_acceleration, "m/s^2");
    write_load(out, "base_angular_acceleration", p.base_angular_acceleration, "rad/s^2");
  }
  // The elements' inputs (a DC motor's voltage), given or not.
  for (const SectionType& type : element_section_types())
    for (std::size_t i = 0; i < type.inputs.size(); ++i)
      write_load(out, type.inputs[i].name, section_input(p, type, static_cast<int>(i)),
                 type.inputs[i].unit);
  if (has_transverse_slip(p))
    write_load(out, "transverse_slip_velocity", p.transverse_slip_velocity, "m/s");
  const integrate::IntegratorOptions& o = options.integrator_options;
  out << "\n[options]\nintegrator = " << quoted(options.integrator)
      << "\nsmooth_integrator = " << quoted(options.smooth_integrator)
      << "\nrtol = " << number(o.rtol) << "\natol = " << number(o.atol)
      << "\nmax_steps = " << o.max_steps << "\nmax_events = " << options.max_events
      << "\nmax_step = " << number(o.max_step) << "\nfirst_step = " << number(o.first_step)
      << "\nmax_order = " << o.max_order
      << "\nbounce_threshold = " << number(options.bounce_threshold) << "\n";
  return out.str();
}

CoreSpec read_core_spec(const std::string& text, const std::string& source) {
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream message;
    message << (source.empty() ? std::string("core spec") : source) << ": not valid TOML ("
            << e.description() << " at line " << e.source().begin.line << ", column "
            << e.source().begin.column << ")";
    throw InvalidArgument(message.str());
  }
  Reader r(root, source);
  r.known(root, "", {"format", "version", "drive", "thread", "friction", "parameters", "loads",
                     "options"});
  std::string format;
  if (!r.text(root, "", "format", format) || format != kFormat)
    r.fail("format", "must be \"" + std::string(kFormat) + "\" (a file written by "
                     "Scene.to_core_toml or `leadscrew scene resolve`)");
  long version = 0;
  if (!r.whole(root, "", "version", version) || version != kVersion)
    r.fail("version", "must be " + std::to_string(kVersion));

  CoreSpec spec;
  DriveParameters& p = spec.parameters;
  if (const toml::table* t = r.table(root, "", "drive")) read_drive_section(r, *t, p);
  if (const toml::table* t = r.table(root, "", "thread")) read_thread_section(r, *t, p);
  if (const toml::table* t = r.table(root, "", "friction")) read_friction_section(r, *t, p);
  if (const toml::table* t = r.table(root, "", "parameters")) read_parameters_section(r, *t, p);
  if (const toml::table* t = r.table(root, "", "loads")) read_loads_section(r, *t, p);
  if (const toml::table* t = r.table(root, "", "options"))
    read_options_section(r, *t, spec.options);
  return spec;
}

CoreSpec read_core_spec_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument("core spec file \"" + path + "\" cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  return read_core_spec(text.str(), path);
}

}  // namespace leadscrew::model
