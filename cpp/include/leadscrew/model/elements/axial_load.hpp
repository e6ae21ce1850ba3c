// Element: the axial force on the load's coordinate (loads.axial_force; its
// work is the axial work in the energy account).
#pragma once

#include "leadscrew/excitation/excitation.hpp"

namespace leadscrew::model::elements {

struct AxialLoad {
  int coordinate = -1;
  Excitation force;  // [N]

  double force_at(double t) const { return force(t); }
  // Its power, the axial work rate [W], at the force it applies and the
  // velocities v.
  template <class Vector>
  double power(double applied_force, const Vector& v) const {
    return applied_force * v[coordinate];
  }
};

}  // namespace leadscrew::model::elements
