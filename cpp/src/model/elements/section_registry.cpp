// The elements' scene sections, one line each: X(name) for a section
// declared by `SectionType name_section()` in its element's file
// (element_section.hpp; cpp/src/model/elements/name.cpp), then the
// sections of the model's elements behind the element interface, from
// their registry's lines (drive/element_registry.cpp, S(name)). The order
// is the scene schema's and the core spec's.
#include <string>
#include <utility>

#include "leadscrew/model/element_section.hpp"

#define LEADSCREW_ELEMENT_SECTIONS(X) \
  X(end_stops)                        \
  X(load_spring)

namespace leadscrew::model {

#define LEADSCREW_DECLARE_SECTION(name) SectionType name##_section();
LEADSCREW_ELEMENT_SECTIONS(LEADSCREW_DECLARE_SECTION)
#undef LEADSCREW_DECLARE_SECTION

namespace drive {
std::vector<SectionType> model_element_sections();
}

namespace {
std::vector<SectionType>& registered_sections() {
#define LEADSCREW_LIST_SECTION(name) name##_section(),
  static std::vector<SectionType> types = [] {
    std::vector<SectionType> own = {LEADSCREW_ELEMENT_SECTIONS(LEADSCREW_LIST_SECTION)};
    for (SectionType& type : drive::model_element_sections()) own.push_back(std::move(type));
    return own;
  }();
#undef LEADSCREW_LIST_SECTION
  return types;
}
}  // namespace

const std::vector<SectionType>& element_section_types() { return registered_sections(); }

void register_element_section(SectionType type) {
  for (const SectionType& known : registered_sections())
    if (std::string(known.name) == type.name) return;  // (registered once)
  registered_sections().push_back(std::move(type));
}

}  // namespace leadscrew::model
