#include "leadscrew/friction/laws.hpp"

#include "leadscrew/core/validate.hpp"

namespace leadscrew {

namespace {
// Made once: every simulation parses and names its law, and a short one
// takes microseconds (three strings, one longer than the small-string buffer).
const std::vector<std::string>& law_names() {
  static const std::vector<std::string> names = {"coulomb", "arctan_velocity",
                                                  "arctan_acceleration"};
  return names;
}
}  // namespace

std::vector<std::string> friction_law_names() { return law_names(); }

FrictionLaw parse_friction_law(const std::string& name) {
  return static_cast<FrictionLaw>(require_choice("friction", name, law_names()));
}

std::string friction_law_name(FrictionLaw law) { return law_names()[static_cast<int>(law)]; }

}  // namespace leadscrew
