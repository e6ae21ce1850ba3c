// Friction laws of the flank and of the friction benchmark.
//  coulomb:              exact set-valued Coulomb friction (thesis eq. 2.17),
//                        resolved by an LCP (eq. 3.10-3.14)
//  arctan_velocity:      lambda_T = (2/pi) mu |lambda_N| atan(k_V * slip velocity)   (eq. 2.25, 3.16)
//  arctan_acceleration:  lambda_T = (2/pi) mu |lambda_N| atan(k_V * slip acceleration) (eq. 3.15)
#pragma once

#include <cmath>
#include <string>
#include <vector>

namespace leadscrew {

enum class FrictionLaw { coulomb, arctan_velocity, arctan_acceleration };

FrictionLaw parse_friction_law(const std::string& name);
std::string friction_law_name(FrictionLaw law);
std::vector<std::string> friction_law_names();

// Regularized Coulomb force magnitude law, eq. (2.25): bounded by mu |normal|.
inline double arctan_friction(double mu, double normal_force, double k_v, double slip) {
  constexpr double two_over_pi = 0.63661977236758134308;
  return two_over_pi * mu * std::abs(normal_force) * std::atan(k_v * slip);
}

}  // namespace leadscrew
