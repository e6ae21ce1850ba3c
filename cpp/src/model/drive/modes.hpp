// The event-driven drive's mode: the thread contact (bilateral, a closed
// flank, open, penalty) and the friction state on it (stick, slip with its
// sign, free, regularized), and its description in event names. The choice
// of the mode (the flank LCP and the stick test) is DriveHybrid's
// (hybrid_modes.cpp). Internal to cpp/src/model.
#pragma once

#include <string>

#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model::drive {

// The event-driven drive's current mode (DriveHybrid::mode_).
struct Mode {
  ThreadContact contact = ThreadContact::bilateral;
  int flank = 1;  // sign of the normal force on a closed flank: +1 lower (e = -c/2), -1 upper
  FrictionMode friction = FrictionMode::none;
  int slip_sign = 0;
  // A lift-off nut's stick with half B at slip s's edge state (s = +-1;
  // 0: at its spring's force), Moreau-Jean's third stick (moreau_lift_off.cpp):
  // DriveHybrid::stick_at_half_b_edge.
  int half_b_edge = 0;
  bool operator==(const Mode& o) const {
    return contact == o.contact && flank == o.flank && friction == o.friction &&
           slip_sign == o.slip_sign && half_b_edge == o.half_b_edge;
  }
};

// "lower flank slip+", "open", ...: the mode in an event's description.
std::string describe(const Mode& m, bool backlash);

// -1, 0 or +1.
inline int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

}  // namespace leadscrew::model::drive
