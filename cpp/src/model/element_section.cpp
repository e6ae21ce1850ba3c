// Element sections (element_section.hpp): the declarations' helpers, the
// values' defaults, the range checks and the attributes, generic over the
// registry.
#include "leadscrew/model/element_section.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/model/drive.hpp"

namespace leadscrew::model {

SectionField SectionField::required(double absent) const {
  SectionField f = *this;
  f.presence = Presence::required;
  f.value = absent;
  return f;
}
SectionField SectionField::optional(double absent) const {
  SectionField f = *this;
  f.presence = Presence::optional;
  f.value = absent;
  return f;
}
SectionField SectionField::defaults(double v) const {
  SectionField f = *this;
  f.presence = Presence::defaulted;
  f.value = v;
  return f;
}
SectionField SectionField::range(double lo, double hi, bool lo_open, bool hi_open) const {
  SectionField f = *this;
  f.low = lo;
  f.high = hi;
  f.low_open = lo_open;
  f.high_open = hi_open;
  return f;
}
SectionField SectionField::named(const char* name) const {
  SectionField f = *this;
  f.attribute = name;
  return f;
}
SectionField SectionField::described(const char* text) const {
  SectionField f = *this;
  f.default_doc = text;
  return f;
}

SectionField SectionField::cosim(const char* unit, const char* doc) const {
  SectionField f = *this;
  f.fmi_unit = unit;
  f.fmi_doc = doc;
  return f;
}

SectionField number(const char* key, const char* unit, const char* doc) {
  SectionField f;
  f.key = key;
  f.unit = unit;
  f.doc = doc;
  return f;
}

SectionField choice(const char* key, std::vector<std::string> names, const char* doc) {
  SectionField f;
  f.key = key;
  f.doc = doc;
  f.kind = SectionField::Kind::choice;
  f.choices = std::move(names);
  return f;
}

namespace {

// Python's repr of a float: the shortest digits that read back, fixed
// notation for exponents in [-4, 16) (with ".0" where it is whole), else
// scientific with a two-digit exponent at least.
std::string python_float(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buffer[40];
  int digits = 1;
  for (; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*e", digits - 1, v);
    if (std::strtod(buffer, nullptr) == v) break;
  }
  const std::string text(buffer);
  const std::size_t e = text.find('e');
  const int exponent = std::atoi(text.c_str() + e + 1);
  if (exponent >= -4 && exponent < 16) {
    std::snprintf(buffer, sizeof buffer, "%.*f", std::max(0, digits - 1 - exponent), v);
    std::string fixed(buffer);
    if (fixed.find('.') == std::string::npos) fixed += ".0";
    return fixed;
  }
  std::string mantissa = text.substr(0, e);
  char power[16];
  std::snprintf(power, sizeof power, "e%c%02d", exponent < 0 ? '-' : '+', std::abs(exponent));
  return mantissa + power;
}

bool absent_value(const SectionField& f, double v) {
  return v == f.value || (std::isnan(v) && std::isnan(f.value));
}

std::string range_text(const SectionField& f) {
  if (std::isinf(f.low) && std::isinf(f.high)) return "finite";
  if (std::isinf(f.high)) return std::string(f.low_open ? "> " : ">= ") + format_value(f.low);
  if (std::isinf(f.low)) return std::string(f.high_open ? "< " : "<= ") + format_value(f.high);
  return std::string("in ") + (f.low_open ? "(" : "[") + format_value(f.low) + ", " +
         format_value(f.high) + (f.high_open ? ")" : "]");
}

ElementSection& entry(DriveParameters& p, const SectionType& type) {
  return p.sections[type.name];
}

const SectionField& choice_field(const SectionType& type) {
  for (const SectionField& f : type.fields)
    if (f.kind == SectionField::Kind::choice && f.attribute != nullptr) return f;
  throw InvalidArgument(std::string(type.name) + " has no presence attribute");
}

}  // namespace

std::string MessageStyle::text(const std::string& s) const {
  return scene ? "'" + s + "'" : "\"" + s + "\"";
}

std::string MessageStyle::number(double v) const {
  return scene ? python_float(v) : format_value(v);
}

std::string MessageStyle::section(const Section& s) const {
  std::string out;
  for (const SectionField& f : s.type().fields) {
    const bool number_field = f.kind == SectionField::Kind::number;
    if (number_field && !s.given(f.key) && !(f.presence == SectionField::Presence::defaulted))
      continue;
    if (!out.empty()) out += ", ";
    out += scene ? "'" + std::string(f.key) + "': " : std::string(f.key) + " = ";
    out += number_field ? number(s.number(f.key)) : text(s.choice(f.key));
  }
  return "{" + out + "}";
}

int SectionType::field_index(const std::string& key) const {
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (key == fields[i].key) return static_cast<int>(i);
  return -1;
}

std::string SectionType::presence_attribute() const {
  return flag != nullptr ? flag : choice_field(*this).attribute;
}

Section::Section(const SectionType& type, const ElementSection& given) : type_(&type) {
  for (const SectionField& f : type.fields) {
    bool found = false;
    if (f.kind == SectionField::Kind::number) {
      double v = f.value;
      for (const auto& [key, value] : given.numbers)
        if (key == f.key) v = value, found = true;
      numbers_.push_back(v);
      choices_.emplace_back();
      supplied_.push_back(found);
    } else {
      std::string v = f.choices.front();
      for (const auto& [key, value] : given.choices)
        if (key == f.key) v = value, found = true;
      numbers_.push_back(0.0);
      choices_.push_back(v);
      supplied_.push_back(found);
    }
  }
}

bool Section::given(const char* key) const {
  const int i = type_->field_index(key);
  if (i < 0) return false;
  const auto k = static_cast<std::size_t>(i);
  const SectionField& f = type_->fields[k];
  return supplied_[k] && (f.kind == SectionField::Kind::choice ||
                          f.presence == SectionField::Presence::defaulted ||
                          !absent_value(f, numbers_[k]));
}

bool Section::supplied(const char* key) const {
  const int i = type_->field_index(key);
  return i >= 0 && supplied_[static_cast<std::size_t>(i)];
}

double Section::number(const char* key) const {
  const int i = type_->field_index(key);
  if (i < 0) throw InvalidArgument(path(key) + " is not a field");
  return numbers_[static_cast<std::size_t>(i)];
}

const std::string& Section::choice(const char* key) const {
  const int i = type_->field_index(key);
  if (i < 0) throw InvalidArgument(path(key) + " is not a field");
  return choices_[static_cast<std::size_t>(i)];
}

const SectionType& element_section_type(const std::string& name) {
  std::string names;
  for (const SectionType& type : element_section_types()) {
    if (name == type.name) return type;
    names += (names.empty() ? "" : ", ") + std::string(type.name);
  }
  throw InvalidArgument("section \"" + name + "\" is invalid: must be one of " + names);
}

const ElementSection* find_section(const DriveParameters& p, const char* name) {
  const auto it = p.sections.find(name);
  return it != p.sections.end() && it->second.present ? &it->second : nullptr;
}

void check_section_ranges(const Section& s) {
  for (const SectionField& f : s.type().fields) {
    if (f.kind == SectionField::Kind::choice) {
      std::vector<std::string> allowed = f.choices;
      require_choice(s.path(f.key), s.choice(f.key), allowed);
      continue;
    }
    if (!s.given(f.key)) {
      if (f.presence == SectionField::Presence::required && !s.supplied(f.key))
        throw InvalidArgument(s.path(f.key) + " is missing: " + f.doc +
                              (*f.unit ? std::string(" [") + f.unit + "]" : std::string()));
      if (f.presence != SectionField::Presence::required) continue;
    }
    const double v = s.number(f.key);
    const bool above = f.low_open ? v > f.low : v >= f.low;
    const bool below = f.high_open ? v < f.high : v <= f.high;
    if (!(std::isfinite(v) && above && below))
      throw InvalidArgument(s.path(f.key) + " = " + format_value(v) +
                            (*f.unit ? std::string(" ") + f.unit : std::string()) +
                            " is invalid: must be " + range_text(f));
  }
}

void build_element_sections(const DriveParameters& p, elements::DriveElements& e,
                            SectionType::Stage stage) {
  const MessageStyle core;
  for (const SectionType& type : element_section_types()) {
    const ElementSection* given = find_section(p, type.name);
    if (given == nullptr || type.stage != stage) continue;
    const Section s(type, *given);
    check_section_ranges(s);
    if (type.check) type.check(s, p, core);
    if (type.build) type.build(s, p, e);
  }
}

void check_element_section(const std::string& name, const ElementSection& given,
                           const DriveParameters& context) {
  const SectionType& type = element_section_type(name);
  MessageStyle scene;
  scene.scene = true;
  if (type.check) type.check(Section(type, given), context, scene);
}

double section_number(const DriveParameters& p, const SectionType& type, int field) {
  const SectionField& f = type.fields[static_cast<std::size_t>(field)];
  const auto it = p.sections.find(type.name);
  if (it != p.sections.end())
    for (const auto& [key, value] : it->second.numbers)
      if (key == f.key) return value;
  return f.value;
}

void set_section_number(DriveParameters& p, const SectionType& type, int field, double value) {
  const SectionField& f = type.fields[static_cast<std::size_t>(field)];
  ElementSection& s = entry(p, type);
  for (auto& [key, v] : s.numbers)
    if (key == f.key) {
      v = value;
      return;
    }
  s.numbers.emplace_back(f.key, value);
}

std::string section_presence(const DriveParameters& p, const SectionType& type) {
  const ElementSection* s = find_section(p, type.name);
  if (type.flag != nullptr) return s ? "true" : "false";
  if (s == nullptr) return "none";
  const SectionField& f = choice_field(type);
  for (const auto& [key, value] : s->choices)
    if (key == f.key) return value;
  return f.choices.front();
}

void set_section_presence(DriveParameters& p, const SectionType& type, const std::string& value) {
  if (type.flag != nullptr) {
    const int index = require_choice(type.flag, value, {"false", "true"});
    entry(p, type).present = index == 1;
    return;
  }
  const SectionField& f = choice_field(type);
  std::vector<std::string> allowed = {"none"};
  allowed.insert(allowed.end(), f.choices.begin(), f.choices.end());
  const int index = require_choice(std::string(type.name) + "." + f.key, value, allowed);
  ElementSection& s = entry(p, type);
  s.present = index > 0;
  if (index == 0) return;
  for (auto& [key, v] : s.choices)
    if (key == f.key) {
      v = value;
      return;
    }
  s.choices.emplace_back(f.key, value);
}

const Excitation& section_input(const DriveParameters& p, const SectionType& type, int input) {
  static const Excitation none;
  const char* name = type.inputs[static_cast<std::size_t>(input)].name;
  const auto it = p.sections.find(type.name);
  if (it != p.sections.end())
    for (const auto& [key, value] : it->second.inputs)
      if (key == name) return value;
  return none;
}

void set_section_input(DriveParameters& p, const SectionType& type, int input, Excitation value) {
  const char* name = type.inputs[static_cast<std::size_t>(input)].name;
  ElementSection& s = entry(p, type);
  for (auto& [key, v] : s.inputs)
    if (key == name) {
      v = std::move(value);
      return;
    }
  s.inputs.emplace_back(name, std::move(value));
}

const SectionType* rotor_drive_section(const DriveParameters& p) {
  for (const SectionType& type : element_section_types())
    if (type.rotor_drive != nullptr && find_section(p, type.name) != nullptr) return &type;
  return nullptr;
}

const Excitation& rotor_drive(const DriveParameters& p) {
  if (const SectionType* type = rotor_drive_section(p)) return section_input(p, *type, 0);
  return p.speed_controlled ? p.drive_speed : p.drive_torque;
}

const Excitation* find_section_input(const DriveParameters& p, const std::string& name) {
  for (const SectionType& type : element_section_types()) {
    if (find_section(p, type.name) == nullptr) continue;
    for (std::size_t i = 0; i < type.inputs.size(); ++i)
      if (name == type.inputs[i].name) return &section_input(p, type, static_cast<int>(i));
  }
  return nullptr;
}

Excitation* find_section_input(DriveParameters& p, const std::string& name) {
  for (const SectionType& type : element_section_types()) {
    if (find_section(p, type.name) == nullptr) continue;
    for (std::size_t i = 0; i < type.inputs.size(); ++i)
      if (name == type.inputs[i].name) {
        set_section_input(p, type, static_cast<int>(i),
                          section_input(p, type, static_cast<int>(i)));  // (an entry)
        for (auto& [key, value] : p.sections[type.name].inputs)
          if (key == name) return &value;
      }
  }
  return nullptr;
}

}  // namespace leadscrew::model
