// Element: a rigid body's inertia on one coordinate (a mass on a
// translational coordinate [kg], a polar moment of inertia on a rotational
// one [kg m^2]). Bodies that move together share a coordinate (the rigid
// drive's rotor and screw, its load and nut): their inertias add up on it.
// A body's part of the energy account is its kinetic energy m v^2 / 2,
// which the model evaluates from the assembled diagonal mass matrix.
#pragma once

#include <Eigen/Core>
#include <string>

namespace leadscrew::model::elements {

struct RigidBody {
  std::string name;      // "rotor", "screw", "nut", "load"
  int coordinate = -1;   // the coordinate it moves with
  double inertia = 0.0;  // mass [kg] or polar inertia [kg m^2]

  // Its contribution to the (diagonal) mass matrix.
  void add_mass(Eigen::VectorXd& diagonal) const { diagonal[coordinate] += inertia; }
  // Its kinetic energy [J] at the velocities v.
  double kinetic_energy(const double* v) const {
    return 0.5 * inertia * v[coordinate] * v[coordinate];
  }
};

}  // namespace leadscrew::model::elements
