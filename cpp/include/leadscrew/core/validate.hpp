// Input validation shared by every part of the core.
//
// Each check throws InvalidArgument with a message of one form:
//   "<name> = <value> is invalid: must be <range>"
// so that a user sees the parameter (or key path), what was given and what is
// allowed.
#pragma once

#include <string>
#include <vector>

namespace leadscrew {

std::string format_value(double value);

// finite and > 0
double require_positive(const std::string& name, double value);
// finite and >= 0
double require_nonnegative(const std::string& name, double value);
// finite
double require_finite(const std::string& name, double value);
// finite and in [low, high] (either end open when the flag says so)
double require_in_range(const std::string& name, double value, double low, double high,
                        bool low_open = false, bool high_open = false);
// one of the allowed names; returns its index. `condition` qualifies the
// message: 'integrator = "dopri5" is invalid for friction = "coulomb": ...'.
int require_choice(const std::string& name, const std::string& value,
                   const std::vector<std::string>& allowed, const std::string& condition = "");

}  // namespace leadscrew
