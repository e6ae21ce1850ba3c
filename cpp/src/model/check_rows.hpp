// What the result checks share (result_checks.cpp, bristle_check.cpp): a
// check's record and the worst row of an invariant value <= bound. Internal
// to cpp/src/model.
#pragma once

#include <limits>

#include "leadscrew/integrate/simulation_result.hpp"

namespace leadscrew::model::check_rows {

inline integrate::InvariantCheck make_check(const char* name, const char* what,
                                            const char* unit) {
  integrate::InvariantCheck c;
  c.name = name;
  c.what = what;
  c.unit = unit;
  return c;
}

// Keeps the worst excess (value - bound) of an invariant value <= bound.
struct Worst {
  integrate::InvariantCheck& check;
  double excess = -std::numeric_limits<double>::infinity();
  void offer(double value, double bound, double t) {
    const double e = value - bound;
    if (!(e <= excess)) {  // the first, a larger one, or NaN
      excess = e;
      check.value = value;
      check.bound = bound;
      check.time = t;
    }
    if (!(value <= bound)) check.passed = false;
  }
};

}  // namespace leadscrew::model::check_rows
