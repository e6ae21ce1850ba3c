// Where a drive's run ends: the nut's end at the screw's end. Internal to
// cpp/src/model.
#pragma once

#include "leadscrew/core/errors.hpp"
#include "leadscrew/model/drive.hpp"

namespace leadscrew::model::drive {

// A run ends where the nut's end reaches the screw's
// (DriveModel::screw_end_margin), for every concept: beyond it the thread no
// longer holds the nut, and the results would describe a drive that does not
// exist. The flexible screw needs it besides: its stiffness grows as 1/a
// toward an end (eq. 4.24), and a run that wound the nut there took ever
// smaller steps (CVODE ground to max_steps within a millimetre of the end).
[[noreturn]] inline void nut_left_the_screw(const DriveModel& model, double t,
                                            double nut_position) {
  throw NutOffScrew(t, model.nut_off_screw(nut_position), DriveModel::kNutOffScrewHint);
}

}  // namespace leadscrew::model::drive
