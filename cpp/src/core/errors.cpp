#include "leadscrew/core/errors.hpp"

#include <sstream>

namespace leadscrew {

std::string SimulationError::compose(double time, const std::string& reason,
                                     const std::string& hint) {
  std::ostringstream out;
  out.precision(17);
  out << "at t = " << time << " s: " << reason;
  if (!hint.empty()) out << " (hint: " << hint << ")";
  return out.str();
}

}  // namespace leadscrew
