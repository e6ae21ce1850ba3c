// The registry of the drive's elements that declare states or channels of
// their own (declaration.hpp) and of the event-driven driver's elements with
// events (driver_element.hpp): one line per kind, in the order of their
// states in y, of their channels in a row and of their roots.
//   D(name)  declares (const ElementKind& name_kind(), in its own file)
//   E(name)  declares and has events in the event-driven driver (also
//            make_name_element, declared here, in the same file)
//   M(name)  an element of the model behind the element interface
//            (model/element.hpp): its file declares name_kind() and builds
//            it; the drivers take it through the interface alone
//   S(name)  as M, its parameters and inputs in a section of its own
//            (element_section.hpp; SectionType name_section(), in its
//            file): the sections' registry lists it after its own
//            (model_element_sections()); its kind is listed here
// The elements' sections (element_section.hpp) add their kinds after these,
// from their own registry (section_registry.cpp): an element with a section
// of its own needs no line here.
#include "driver_element.hpp"
#include "leadscrew/model/element_section.hpp"

#define LEADSCREW_DRIVE_ELEMENTS(D, E, M, S) \
  D(lugre_bristles)                          \
  S(dc_motor)                                \
  E(end_stops)                               \
  E(preloaded_nut)                           \
  E(train_friction)                          \
  M(base_excitation)                         \
  E(transverse_slip)

namespace leadscrew::model::drive {

#define LEADSCREW_DECLARE_KIND(name) const ElementKind& name##_kind();
#define LEADSCREW_DECLARE_EVENTS(name) \
  LEADSCREW_DECLARE_KIND(name)         \
  std::unique_ptr<DriveHybrid::Element> make_##name##_element(DriveHybrid&, const DriveModel&);
LEADSCREW_DRIVE_ELEMENTS(LEADSCREW_DECLARE_KIND, LEADSCREW_DECLARE_EVENTS, LEADSCREW_DECLARE_KIND,
                         LEADSCREW_DECLARE_KIND)
#undef LEADSCREW_DECLARE_EVENTS
#undef LEADSCREW_DECLARE_KIND

}  // namespace leadscrew::model::drive

namespace leadscrew::model {
#define LEADSCREW_NO_SECTION(name)
#define LEADSCREW_DECLARE_SECTION(name) SectionType name##_section();
LEADSCREW_DRIVE_ELEMENTS(LEADSCREW_NO_SECTION, LEADSCREW_NO_SECTION, LEADSCREW_NO_SECTION,
                         LEADSCREW_DECLARE_SECTION)
#undef LEADSCREW_DECLARE_SECTION
}  // namespace leadscrew::model

namespace leadscrew::model::drive {

std::vector<SectionType> model_element_sections() {
#define LEADSCREW_SECTION(name) name##_section(),
  return {LEADSCREW_DRIVE_ELEMENTS(LEADSCREW_NO_SECTION, LEADSCREW_NO_SECTION,
                                   LEADSCREW_NO_SECTION, LEADSCREW_SECTION)};
#undef LEADSCREW_SECTION
}
#undef LEADSCREW_NO_SECTION

const std::vector<const ElementKind*>& element_kinds() {
#define LEADSCREW_KIND(name) &name##_kind(),
  static std::vector<const ElementKind*> kinds;
  static std::size_t sections = 0;
  // Then the elements' sections' kinds (element_section.hpp), in their
  // registry's order, sections registered at run time included (rebuilt
  // where one was added since).
  const std::vector<SectionType>& types = element_section_types();
  if (kinds.empty() || sections != types.size()) {
    kinds = {LEADSCREW_DRIVE_ELEMENTS(LEADSCREW_KIND, LEADSCREW_KIND, LEADSCREW_KIND,
                                      LEADSCREW_KIND)};
    for (const SectionType& type : types)
      if (type.kind != nullptr) kinds.push_back(&type.kind());
    sections = types.size();
  }
#undef LEADSCREW_KIND
  return kinds;
}

const std::vector<ElementFactory>& element_factories() {
#define LEADSCREW_NO_EVENTS(name) nullptr,
#define LEADSCREW_EVENTS(name) &make_##name##_element,
#define LEADSCREW_MODEL(name) \
  [](DriveHybrid& hybrid, const DriveModel& model) { return make_model_element(hybrid, model, #name); },
  static const std::vector<ElementFactory> factories = {
      LEADSCREW_DRIVE_ELEMENTS(LEADSCREW_NO_EVENTS, LEADSCREW_EVENTS, LEADSCREW_MODEL,
                               LEADSCREW_MODEL)};
#undef LEADSCREW_MODEL
#undef LEADSCREW_EVENTS
#undef LEADSCREW_NO_EVENTS
  return factories;
}

void declare_model_element(const DriveModel& model, const char* name, Declaration& declaration) {
  const std::vector<std::shared_ptr<const Element>>& elements = model.elements().elements;
  for (std::size_t k = 0; k < elements.size(); ++k)
    if (std::string(elements[k]->name()) == name) {
      elements[k]->declare(declaration);
      declaration.element = static_cast<int>(k);
      return;
    }
}

std::vector<Declaration> declare_elements(const DriveModel& model, const friction::Law& law) {
  std::vector<Declaration> declarations;
  const std::vector<const ElementKind*>& kinds = element_kinds();
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    Declaration d;
    kinds[k]->declare(model, law, d);
    if (d.empty()) continue;
    d.kind = static_cast<int>(k);
    declarations.push_back(std::move(d));
  }
  return declarations;
}

}  // namespace leadscrew::model::drive
