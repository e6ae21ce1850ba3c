#include "leadscrew/core/validate.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "leadscrew/core/errors.hpp"

namespace leadscrew {

std::string format_value(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  // The shortest form from 12 significant digits up that reads back as the
  // same double: a value just outside a range must not print as its bound
  // ("t_eval[3] = 0.0294 is invalid: must be in [0, 0.0294]").
  std::string text;
  for (int digits = 12; digits <= 17; ++digits) {
    std::ostringstream out;
    out.precision(digits);
    out << value;
    text = out.str();
    if (std::strtod(text.c_str(), nullptr) == value) break;
  }
  return text;
}

namespace {
[[noreturn]] void fail(const std::string& name, double value, const std::string& range) {
  throw InvalidArgument(name + " = " + format_value(value) + " is invalid: must be " + range);
}
}  // namespace

double require_finite(const std::string& name, double value) {
  if (!std::isfinite(value)) fail(name, value, "a finite number");
  return value;
}

double require_positive(const std::string& name, double value) {
  if (!std::isfinite(value) || !(value > 0.0)) fail(name, value, "a finite number > 0");
  return value;
}

double require_nonnegative(const std::string& name, double value) {
  if (!std::isfinite(value) || !(value >= 0.0)) fail(name, value, "a finite number >= 0");
  return value;
}

double require_in_range(const std::string& name, double value, double low, double high,
                        bool low_open, bool high_open) {
  const bool above = low_open ? value > low : value >= low;
  const bool below = high_open ? value < high : value <= high;
  if (!std::isfinite(value) || !above || !below) {
    const std::string range = std::string("a finite number in ") + (low_open ? "(" : "[") +
                              format_value(low) + ", " + format_value(high) +
                              (high_open ? ")" : "]");
    fail(name, value, range);
  }
  return value;
}

int require_choice(const std::string& name, const std::string& value,
                   const std::vector<std::string>& allowed, const std::string& condition) {
  for (std::size_t i = 0; i < allowed.size(); ++i)
    if (allowed[i] == value) return static_cast<int>(i);
  std::string options;
  for (std::size_t i = 0; i < allowed.size(); ++i)
    options += (i ? ", \"" : "\"") + allowed[i] + "\"";
  throw InvalidArgument(name + " = \"" + value + "\" is invalid" +
                        (condition.empty() ? "" : " for " + condition) + ": must be one of " +
                        options);
}

}  // namespace leadscrew
