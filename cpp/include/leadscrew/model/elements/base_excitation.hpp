// Element: the housing's vibration (loads.base_acceleration, the housing's
// axial acceleration a(t); loads.base_angular_acceleration, its angular
// acceleration alpha(t) about the screw axis). The coordinates are the
// bodies' displacements relative to the housing, so in the housing's frame
// every translating body feels the inertial force -m a and every rotating
// body the torque -J alpha: a generalised force -a(t) m_u - alpha(t) J_phi,
// with m_u the masses on the axial coordinates and J_phi the inertias on
// the angular ones. Its power is the base's work rate in the energy account
// (docs/physics/base_excitation.md).
#pragma once

#include <vector>

#include "leadscrew/excitation/excitation.hpp"

namespace leadscrew::model::elements {

struct BaseExcitation {
  Excitation acceleration;          // a(t) [m/s^2]
  Excitation angular_acceleration;  // alpha(t) [rad/s^2]
  std::vector<double> mass;         // per coordinate: the mass on an axial one [kg]
  std::vector<double> inertia;      // per coordinate: the inertia on an angular one [kg m^2]
  double total_mass = 0.0, total_inertia = 0.0;

  // Adds its generalised force at time t to `forces`; returns its axial
  // force and torque sums (-a m_total, -alpha J_total) through `force`, `torque`.
  template <class Vector>
  void add_forces(double t, Vector& forces, double& force, double& torque) const {
    const double a = acceleration(t), alpha = angular_acceleration(t);
    for (std::size_t i = 0; i < mass.size(); ++i)
      forces[static_cast<int>(i)] -= a * mass[i] + alpha * inertia[i];
    force = -a * total_mass;
    torque = -alpha * total_inertia;
  }
  // Its power [W] at time t and the velocities v (relative to the housing).
  template <class Vector>
  double power(double t, const Vector& v) const {
    const double a = acceleration(t), alpha = angular_acceleration(t);
    double p = 0.0;
    for (std::size_t i = 0; i < mass.size(); ++i)
      p -= (a * mass[i] + alpha * inertia[i]) * v[static_cast<int>(i)];
    return p;
  }
};

}  // namespace leadscrew::model::elements
