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

// 2/pi of the arctan laws lambda_T = (2/pi) mu' lambda_N atan(k_V x), eq. (3.15)/(3.16).
constexpr double kTwoOverPi = 0.63661977236758134308;

FrictionLaw parse_friction_law(const std::string& name);
std::string friction_law_name(FrictionLaw law);
std::vector<std::string> friction_law_names();

}  // namespace leadscrew
