// An element's scene section declared once, in the element's own file: the
// section's name, its fields (key, SI unit, default or required, range, doc
// line; a choice field with its names), its rules across fields and
// sections (a check function), how it builds the element into a model and,
// where it has one, its part in the driver (its channels), its inputs
// (excitations of time: a DC motor's voltage) and its part as the rotor's
// drive (RotorDrive). The registry
// (cpp/src/model/elements/section_registry.cpp) lists the sections, one line
// each; from there everything follows: the Python scene schema's section and
// describe_schema() (python/leadscrew/scene_schema.py reads
// _core.element_sections()), the range checks, the scene's hand-off to the
// core (DriveParameters::sections, the section's dict as is), the core spec's
// TOML (core_spec.cpp), the Python attributes of DriveParameters and the
// batch overrides (each number field's `attribute`). docs/architecture.md,
// "Adding an element".
//
// The values reach the core in DriveParameters::sections (by section name:
// present or not, and the values given, by key); an element's builder reads
// them once, when the model is built (Section::number, a lookup by key at
// build time only), into its own struct: no string lookup per right-hand
// side.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "leadscrew/excitation/excitation.hpp"

namespace leadscrew::model {

struct DriveParameters;

namespace elements {
struct DriveElements;
}
namespace drive {
struct ElementKind;
}

// One field of a section.
struct SectionField {
  enum class Kind { number, choice };
  // required: the scene must give it; optional: it may be absent (the core
  // then takes `value`, e.g. -inf: no lower stop); defaulted: absent, it
  // takes `value` (a choice: its first name).
  enum class Presence { required, optional, defaulted };

  const char* key = "";
  const char* unit = "";  // SI ("" a pure number)
  const char* doc = "";
  Kind kind = Kind::number;
  Presence presence = Presence::defaulted;
  double value = 0.0;
  std::vector<std::string> choices;  // a choice's names, the first its default
  const char* default_doc = "";      // the default in words (where it depends on others)
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  bool low_open = false, high_open = false;
  // A number's name as an attribute of DriveParameters (Python), a batch
  // override and a key of the core spec's [parameters]; a choice's: the
  // section's presence (its names and "none": no such section).
  const char* attribute = nullptr;
  // A number's co-simulation parameter (an FMU's, model/cosim.hpp): its unit
  // in FMI's names ("N.m/A") and its description; nullptr: not one.
  const char* fmi_unit = nullptr;
  const char* fmi_doc = "";

  // Declaration helpers: number("k", "N/m", "doc").required().above(0.0).named("x").
  SectionField required(double absent = 0.0) const;
  SectionField optional(double absent) const;
  SectionField defaults(double v) const;
  SectionField range(double lo, double hi, bool lo_open = false, bool hi_open = false) const;
  SectionField above(double lo) const { return range(lo, high, true, high_open); }
  SectionField at_least(double lo) const { return range(lo, high, false, high_open); }
  SectionField below(double hi) const { return range(low, hi, low_open, true); }
  SectionField named(const char* name) const;
  SectionField described(const char* text) const;
  SectionField cosim(const char* unit, const char* doc) const;
};

// An input of a section's element: an excitation of time it reads (a DC
// motor's voltage), given in the scene under the section's `key`, carried
// in ElementSection::inputs by `name` (its Python attribute, the core
// spec's [loads] key, the stepper's and the FMU's input).
struct SectionInput {
  const char* name = "";
  const char* key = "";
  const char* unit = "";      // SI, as leadscrew.units writes it
  const char* fmi_unit = "";  // in FMI's names
  const char* doc = "";       // the FMU input's description
};

// An element that drives the rotor in place of loads.drive_torque and
// loads.drive_speed (a DC motor): its section's first input is the
// rotor's drive (the stepper's, the batch's and the FMU's input in their
// place; the loads the drivers' breakpoints and step hints take).
struct RotorDrive {
  const char* what = "";    // in messages: "a DC motor (motor.type = \"dc\")"
  const char* absent = "";  // where the drive has none: "a DC motor (no motor section)"
  const char* prefix = "";  // a batch override's name starting with it needs the section
  // The FMU output it adds before drive_torque (its name, FMI unit, description).
  const char* output = "";
  const char* output_unit = "";
  const char* output_doc = "";
};

SectionField number(const char* key, const char* unit, const char* doc);
SectionField choice(const char* key, std::vector<std::string> names, const char* doc);

// A section's values as given (a scene's dict, attributes, the core spec):
// whether the model has the section, and its values by key.
struct ElementSection {
  bool present = false;
  std::vector<std::pair<std::string, double>> numbers;
  std::vector<std::pair<std::string, std::string>> choices;
  std::vector<std::pair<std::string, Excitation>> inputs;  // by SectionInput::name
};
using ElementSections = std::map<std::string, ElementSection>;

class Section;
struct SectionType;

// How a check's message shows values: as the Scene shows them (Python's
// repr: 'exact', 10000000.0) or as the core does ("exact", 1e+07).
struct MessageStyle {
  bool scene = false;
  std::string text(const std::string& s) const;
  std::string number(double v) const;
  // The section's values ({'upper': 0.1, 'contact': 'penalty'}).
  std::string section(const Section& s) const;
};

// A registered section: what its element's file declares.
struct SectionType {
  const char* name = "";
  const char* doc = "";  // where it is absent (the scene schema's comment)
  std::vector<SectionField> fields;
  // Its presence as a bool attribute of DriveParameters (and a key of the core
  // spec's [drive]) where no choice field carries it (nullptr: a choice does).
  const char* flag = nullptr;
  // The scene section that carries its keys where the Python scene schema
  // declares that one (the DC motor's: `motor`, type = "dc"): the key
  // paths' prefix; such a section is no scene section of its own
  // (_core.element_sections() and DriveParameters.sections leave it out,
  // its attributes carry it). nullptr: its own name.
  const char* scene = nullptr;
  // When it is built: with the motor (before the load and the other
  // elements: an element that drives the rotor), or after the others.
  enum class Stage { motor, elements };
  Stage stage = Stage::elements;
  std::vector<SectionInput> inputs;
  const RotorDrive* rotor_drive = nullptr;  // nullptr: it drives no rotor
  // Its rules across fields and sections, after each field's range (raise
  // InvalidArgument naming the key path, the value and what is allowed).
  void (*check)(const Section& s, const DriveParameters& p, const MessageStyle& style) = nullptr;
  // Builds its element into e (after the bodies, the thread, the motor and
  // the load), its values checked.
  void (*build)(const Section& s, const DriveParameters& p, elements::DriveElements& e) = nullptr;
  // Its part in the driver (drive/declaration.hpp; nullptr: none).
  const drive::ElementKind& (*kind)() = nullptr;

  int field_index(const std::string& key) const;  // -1: none
  // The presence attribute's name (the flag, or the choice's attribute).
  std::string presence_attribute() const;
  // A key's path in the scene ("end_stops.upper", "motor.resistance").
  std::string key_path(const char* key) const {
    return std::string(scene != nullptr ? scene : name) + "." + key;
  }
};

// A present section's complete values: the given ones and the defaults.
class Section {
 public:
  Section(const SectionType& type, const ElementSection& given);
  const SectionType& type() const noexcept { return *type_; }
  // True if the key was given and differs from what its absence means.
  bool given(const char* key) const;
  // True if the key was given at all (also at the value its absence
  // means: a required stiffness given as 0 is out of range, not missing).
  bool supplied(const char* key) const;
  double number(const char* key) const;
  const std::string& choice(const char* key) const;
  std::string path(const char* key) const { return type_->key_path(key); }

 private:
  const SectionType* type_;
  std::vector<double> numbers_;
  std::vector<std::string> choices_;
  std::vector<bool> supplied_;  // given at all (given(): and not its absence's value)
};

// The registry, in its order (section_registry.cpp).
const std::vector<SectionType>& element_section_types();
// Adds a section to the registry at run time, after the registry's own (a
// program's element outside the core: tests/cpp/core/test_brake.cpp), once
// per name; before the first model with it is built, from one thread.
void register_element_section(SectionType type);
// The section named `name` (InvalidArgument naming the registered ones).
const SectionType& element_section_type(const std::string& name);

// The section of p (nullptr: absent).
const ElementSection* find_section(const DriveParameters& p, const char* name);
// Each field's value checked against its range (the core's messages).
void check_section_ranges(const Section& s);
// Builds every present section's element of the stage into e: ranges,
// check, build.
void build_element_sections(const DriveParameters& p, elements::DriveElements& e,
                            SectionType::Stage stage = SectionType::Stage::elements);
// The Scene's check of one section (its ranges are the scene's): the
// type's check with the Scene's messages.
void check_element_section(const std::string& name, const ElementSection& given,
                           const DriveParameters& context);

// The attributes (DriveParameters' Python attributes, the batch overrides,
// the core spec): a number field's value (given, else what its absence
// means), set; the presence ("none" or a choice's name; a flag: "false" /
// "true").
double section_number(const DriveParameters& p, const SectionType& type, int field);
void set_section_number(DriveParameters& p, const SectionType& type, int field, double value);
std::string section_presence(const DriveParameters& p, const SectionType& type);
void set_section_presence(DriveParameters& p, const SectionType& type, const std::string& value);
// An input's excitation (absent: a constant 0), set.
const Excitation& section_input(const DriveParameters& p, const SectionType& type, int input);
void set_section_input(DriveParameters& p, const SectionType& type, int input, Excitation value);

// The present section whose element drives the rotor (nullptr: none: the
// loads drive_torque or drive_speed do).
const SectionType* rotor_drive_section(const DriveParameters& p);
// The excitation that drives the rotor: that section's first input, else
// loads.drive_speed (speed-controlled) or loads.drive_torque.
const Excitation& rotor_drive(const DriveParameters& p);
// The present sections' input named `name` (nullptr: none).
const Excitation* find_section_input(const DriveParameters& p, const std::string& name);
Excitation* find_section_input(DriveParameters& p, const std::string& name);

}  // namespace leadscrew::model
