// The mode's description in event names (modes.hpp).
#include "modes.hpp"

namespace leadscrew::model::drive {

std::string describe(const Mode& m, bool backlash) {
  std::string friction;
  switch (m.friction) {
    case FrictionMode::stick:
      friction = m.half_b_edge == 0 ? "stick"
                 : m.half_b_edge > 0 ? "stick (half B at slip+'s edge)"
                                     : "stick (half B at slip-'s edge)";
      break;
    case FrictionMode::slip:
      friction = m.slip_sign > 0 ? "slip+" : "slip-";
      break;
    case FrictionMode::none:
      friction = "free";
      break;
    default:
      friction = "regularized";
  }
  if (!backlash || m.contact == ThreadContact::penalty) return friction;
  if (m.contact == ThreadContact::open) return "open";
  return std::string(m.flank > 0 ? "lower flank " : "upper flank ") + friction;
}

}  // namespace leadscrew::model::drive
