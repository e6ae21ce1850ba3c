#include "leadscrew/friction/laws.hpp"

#include "leadscrew/core/validate.hpp"

namespace leadscrew {

std::vector<std::string> friction_law_names() {
  return {"coulomb", "arctan_velocity", "arctan_acceleration"};
}

FrictionLaw parse_friction_law(const std::string& name) {
  return static_cast<FrictionLaw>(require_choice("friction", name, friction_law_names()));
}

std::string friction_law_name(FrictionLaw law) {
  return friction_law_names()[static_cast<int>(law)];
}

}  // namespace leadscrew
