// The registry of the drive's elements that declare states or channels of
// their own (declaration.hpp) and of the event-driven driver's elements with
// events (driver_element.hpp): one line per kind, in the order of their
// states in y, of their channels in a row and of their roots.
//   D(name)  declares (const ElementKind& name_kind(), in its own file)
//   E(name)  declares and has events in the event-driven driver (also
//            make_name_element, declared here, in the same file)
// The elements' sections (element_section.hpp) add their kinds after these,
// from their own registry (section_registry.cpp): an element with a section
// of its own needs no line here.
#include "driver_element.hpp"

#define LEADSCREW_DRIVE_ELEMENTS(D, E) \
  D(lugre_bristles)                    \
  E(dc_motor)                          \
  E(end_stops)                         \
  E(preloaded_nut)                     \
  D(train_friction)                    \
  D(base_excitation)

namespace leadscrew::model::drive {

#define LEADSCREW_DECLARE_KIND(name) const ElementKind& name##_kind();
#define LEADSCREW_DECLARE_EVENTS(name) \
  LEADSCREW_DECLARE_KIND(name)         \
  std::unique_ptr<DriveHybrid::Element> make_##name##_element(DriveHybrid&, const DriveModel&);
LEADSCREW_DRIVE_ELEMENTS(LEADSCREW_DECLARE_KIND, LEADSCREW_DECLARE_EVENTS)
#undef LEADSCREW_DECLARE_EVENTS
#undef LEADSCREW_DECLARE_KIND

const std::vector<const ElementKind*>& element_kinds() {
#define LEADSCREW_KIND(name) &name##_kind(),
  static const std::vector<const ElementKind*> kinds = [] {
    std::vector<const ElementKind*> out = {LEADSCREW_DRIVE_ELEMENTS(LEADSCREW_KIND, LEADSCREW_KIND)};
    // Then the elements' sections' kinds (element_section.hpp), in their
    // registry's order: no events (no factory).
    for (const SectionType& type : element_section_types())
      if (type.kind != nullptr) out.push_back(&type.kind());
    return out;
  }();
#undef LEADSCREW_KIND
  return kinds;
}

const std::vector<ElementFactory>& element_factories() {
#define LEADSCREW_NO_EVENTS(name) nullptr,
#define LEADSCREW_EVENTS(name) &make_##name##_element,
  static const std::vector<ElementFactory> factories = {
      LEADSCREW_DRIVE_ELEMENTS(LEADSCREW_NO_EVENTS, LEADSCREW_EVENTS)};
#undef LEADSCREW_EVENTS
#undef LEADSCREW_NO_EVENTS
  return factories;
}

std::vector<Declaration> declare_elements(const DriveModel& model, bool bristle) {
  std::vector<Declaration> declarations;
  const std::vector<const ElementKind*>& kinds = element_kinds();
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    Declaration d;
    kinds[k]->declare(model, bristle, d);
    if (d.empty()) continue;
    d.kind = static_cast<int>(k);
    declarations.push_back(std::move(d));
  }
  return declarations;
}

}  // namespace leadscrew::model::drive
