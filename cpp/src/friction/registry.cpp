// The friction laws, one line each: X(name) for a law defined by
// `LawType name_law()` in cpp/src/friction/laws/name.cpp.
#include <string>

#include "leadscrew/core/validate.hpp"
#include "leadscrew/friction/law.hpp"

#define LEADSCREW_FRICTION_LAWS(X) \
  X(coulomb)                       \
  X(arctan_velocity)               \
  X(arctan_acceleration)           \
  X(stribeck)                      \
  X(lugre)

namespace leadscrew::friction {

#define LEADSCREW_DECLARE_LAW(name) LawType name##_law();
LEADSCREW_FRICTION_LAWS(LEADSCREW_DECLARE_LAW)
#undef LEADSCREW_DECLARE_LAW

const std::vector<LawType>& law_types() {
#define LEADSCREW_LIST_LAW(name) name##_law(),
  static const std::vector<LawType> types = {LEADSCREW_FRICTION_LAWS(LEADSCREW_LIST_LAW)};
#undef LEADSCREW_LIST_LAW
  return types;
}

}  // namespace leadscrew::friction
