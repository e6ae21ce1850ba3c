// The end stops' scene section (element_section.hpp; elements/end_stop.hpp,
// docs/physics/end_stops.md): its fields, its rules across fields and
// sections, and the stops it builds on the load. (Absent: no end stops; the
// load travels until the nut leaves the screw.)
#include <cmath>
#include <limits>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/friction/law.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/element_section.hpp"
#include "leadscrew/model/elements/drive_elements.hpp"

namespace leadscrew::model {

namespace {

void check(const Section& s, const DriveParameters& p, const MessageStyle& m) {
  if (!s.given("lower") && !s.given("upper"))
    throw InvalidArgument("end_stops = " + m.section(s) +
                          " is invalid without end_stops.lower or end_stops.upper: give "
                          "end_stops.lower [m] (< 0), end_stops.upper [m] (> 0) or both");
  const std::string& contact = s.choice("contact");
  if (contact == "exact") {
    // (A stiffness is given where it differs from its absence; the damping
    // where it is not 0, its default.)
    for (const char* key : {"stiffness", "damping"})
      if (s.given(key) && s.number(key) != 0.0)
        throw InvalidArgument(s.path(key) + " = " + m.number(s.number(key)) +
                              " is invalid: must be absent with end_stops.contact = " +
                              m.text("exact") +
                              " (a rigid stop; its impacts take end_stops.restitution)");
    // Exact play where the load rides on the part that carries the flank
    // (the rigid drive, the nut-driven flexible nut): while the stop holds
    // the load, a flank's impact would be a second impact at once on a
    // tied body (the flank's and the stop's impulses through the thread's
    // friction), which the event-driven flank impact does not take;
    // Moreau-Jean solves both as rows of its step (drive/integrators.cpp:
    // the scene's only integrator), which takes a set-valued law only.
    const bool load_on_flank =
        p.concept == Concept::rigid ||
        (p.concept == Concept::flexible_nut && p.drive == DrivenPart::nut);
    if (load_on_flank && p.backlash == BacklashContact::exact &&
        !friction::law_type(p.friction).time_stepping)
      throw InvalidArgument(
          "end_stops.contact = " + m.text("exact") + " is invalid with backlash.contact = " +
          m.text("exact") + " and friction.law = " + m.text(p.friction) + " on concept = " +
          m.text(concept_name(p.concept)) + " and drive = " + m.text(drive_name(p.drive)) +
          ": the load rides on the part that carries the flank, a flank's impact while the "
          "stop holds it is two impacts at once, which Moreau-Jean's step takes with a "
          "set-valued law only (friction.law = " + m.text("coulomb") + ", " +
          m.text("stribeck") + "); or use backlash.contact = " + m.text("bistop") + " or " +
          m.text("cubic") + ", end_stops.contact = " + m.text("penalty") + ", or no play");
  } else {
    if (s.number("restitution") != 0.0)
      throw InvalidArgument("end_stops.restitution = " + m.number(s.number("restitution")) +
                            " is invalid: must be 0 with end_stops.contact = " +
                            m.text(contact) +
                            " (a penalty stop's restitution follows from its stiffness and "
                            "damping)");
    if (!s.supplied("stiffness"))
      throw InvalidArgument("end_stops.stiffness is missing: required with end_stops.contact = " +
                            m.text(contact) + " [N/m]");
    if (!(s.number("stiffness") > 0.0))
      throw InvalidArgument("end_stops.stiffness = " + m.number(s.number("stiffness")) +
                            " N/m is invalid: must be > 0 with end_stops.contact = " +
                            m.text(contact));
  }
}

// The stops on the load, lower < 0 < upper relative to its start, which a
// relaxed start puts at u_load = 0 (an equilibrium start moves them by its
// u_load: DriveModel::place_stops_at_equilibrium).
void build(const Section& s, const DriveParameters& p, elements::DriveElements& e) {
  (void)p;
  const int load = e.load.coordinate;
  const bool exact = s.choice("contact") == "exact";
  for (const int side : {-1, 1}) {
    const double position = s.number(side < 0 ? "lower" : "upper");
    if (std::isinf(position)) continue;
    const char* name = side < 0 ? "lower end stop" : "upper end stop";
    if (exact) {
      e.exact_stops.push_back({name, load, side, position, s.number("restitution")});
      continue;
    }
    elements::EndStop stop;
    stop.name = name;
    stop.coordinate = load;
    stop.side = side;
    stop.position = position;
    stop.stiffness = s.number("stiffness");
    stop.damping = s.number("damping");
    e.forces.of<elements::EndStop>().push_back(stop);
  }
}

}  // namespace

SectionType end_stops_section() {
  const double inf = std::numeric_limits<double>::infinity();
  SectionType type;
  type.name = "end_stops";
  type.doc = "(Absent: no end stops; the load travels until the nut leaves "
                                "the screw.)";
  type.fields = {
      number("lower", "m",
             "the lower end stop's face: the load's axial position u_load where it touches, "
             "relative to the load's start (u_load at t = 0), < 0 (absent: no lower stop; give "
             "lower, upper or both)")
          .optional(-inf)
          .below(0.0)
          .named("end_stop_lower"),
      number("upper", "m",
             "the upper end stop's face, relative to the load's start, > 0 (absent: no upper "
             "stop)")
          .optional(inf)
          .above(0.0)
          .named("end_stop_upper"),
      choice("contact", {"penalty", "exact"},
             "the stops' contact: 'penalty', a one-sided spring-damper on the load against the "
             "ground, F = max(0, k d + c d') for a penetration d > 0, which pushes and never "
             "pulls; 'exact', a rigid unilateral stop with Newton impacts (restitution); where "
             "the load is rigid in the thread (concept 'rigid', 'flexible_nut' with drive "
             "'nut') the closed stop holds the drive and carries the loads, the thread's "
             "friction what it cannot (docs/physics/end_stops.md)")
          .named("end_stops"),
      number("stiffness", "N/m",
             "the penalty stop's stiffness k (required with contact = 'penalty', absent with "
             "'exact'): the static deflection under a held force F is F / k")
          .optional(0.0)
          .above(0.0)
          .named("end_stop_stiffness"),
      number("damping", "N*s/m",
             "the penalty stop's damping c in contact (0: an elastic stop, which gives back all "
             "it stores)")
          .defaults(0.0)
          .at_least(0.0)
          .named("end_stop_damping"),
      number("restitution", "",
             "Newton restitution coefficient e of an 'exact' stop's impacts, in [0, 1]: the "
             "load leaves at e times its approach speed; a rebound below the run's "
             "bounce_threshold closes the contact (the load held at the face while the forces "
             "press it there)")
          .defaults(0.0)
          .range(0.0, 1.0)
          .named("end_stop_restitution"),
  };
  type.check = &check;
  type.build = &build;
  return type;
}

namespace elements {

bool has_exact_end_stops(const DriveParameters& p) {
  if (const ElementSection* stops = find_section(p, "end_stops"))
    for (const auto& [key, value] : stops->choices)
      if (key == "contact" && value == "exact") return true;
  return false;
}

}  // namespace elements

}  // namespace leadscrew::model
