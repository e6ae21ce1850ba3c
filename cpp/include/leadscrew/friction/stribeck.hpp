// Stribeck's curve, shared by the stribeck and lugre laws:
// mu(v) = mu + (mu_static - mu) exp(-(v / v_s)^delta).
#pragma once

#include <cmath>
#include <vector>

#include "leadscrew/friction/law.hpp"

namespace leadscrew::friction {

struct StribeckCurve {
  double mu, mu_static, velocity, exponent;
};

double stribeck_curve(const StribeckCurve& curve, double speed);

// mu, mu_static, stribeck_velocity, stribeck_exponent, viscous: the
// parameters both laws take, in this order.
std::vector<ParameterInfo> stribeck_parameters();

}  // namespace leadscrew::friction
