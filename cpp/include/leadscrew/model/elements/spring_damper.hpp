// Element: a linear spring and a viscous damper in parallel between two
// coordinates, or between one and the ground (a support: the screw's
// bearings, the nut's housing). Its stiffness is constant or the screw's,
// which follows the nut (thesis eq. 4.24: the segment between the drive or
// load end and the nut, and with both ends supported the segment beyond it
// in parallel).
//
// Contributions: the generalized force -k x - c x' on its coordinates (and,
// for the screw's stiffness, -k'(a) x^2 / 2 along the nut position's
// gradient, the force of the potential k(a) x^2 / 2 on the nut, which keeps
// the energy account exact), the Jacobians of that force (stiffness and
// damping matrices; the stiffness without the terms of k's change along the
// nut), the elastic energy k x^2 / 2 and the damping power c x'^2.
#pragma once

#include <Eigen/Core>
#include <string>

namespace leadscrew::model::elements {

struct SpringDamper {
  enum class Law { constant, screw_axial, screw_torsional };
  std::string name;
  int first = -1;   // coordinate index
  int second = -1;  // coordinate index or -1 (ground)
  Law law = Law::constant;
  double stiffness = 0.0;  // constant law [N/m or N m/rad]
  double damping = 0.0;    // [N s/m or N m s/rad]
  // The screw's laws: its axial (E A) or torsional (G I_p) rigidity, its
  // length, and whether the segment beyond the nut carries the load too.
  double rigidity = 0.0;
  double screw_length = 0.0;
  bool far_segment = false;
  // Part of the screw: its coordinates exist only while the nut is on the
  // screw, 0 < a < screw_length (DriveDynamics::set_state checks).
  bool on_screw = false;

  // The stiffness at nut position a, and its derivative d k / d a.
  double stiffness_at(double a, double* derivative) const {
    *derivative = 0.0;
    switch (law) {
      case Law::constant:
        return stiffness;
      case Law::screw_torsional: {
        // Only the segment between the drive (or load) end and the nut
        // carries torque: a torsionally held far end would lock the drive.
        // (Thesis eq. 4.25 adds a second segment; see README.)
        const double k = rigidity / a;
        *derivative = -k / a;
        return k;
      }
      case Law::screw_axial:
      default: {
        // Eq. (4.24): segments to the supports in parallel.
        double k = rigidity / a;
        *derivative = -k / a;
        if (far_segment) {
          const double rest = screw_length - a;
          const double k_far = rigidity / rest;
          k += k_far;
          *derivative += k_far / rest;
        }
        return k;
      }
    }
  }

  // Adds its force at positions q, velocities v and nut position a to
  // `forces` (the nut position's gradient carries the stiffness change's
  // force), its elastic energy to `elastic` and its damping power to
  // `damping_power`.
  template <class Vector, class Gradient>
  void add_forces(const Vector& q, const Vector& v, double a, const Gradient& nut_gradient,
                  Vector& forces, double& elastic, double& damping_power) const {
    const double x = q[first] - (second >= 0 ? q[second] : 0.0);
    const double rate = v[first] - (second >= 0 ? v[second] : 0.0);
    double dk_da = 0.0;
    const double k = stiffness_at(a, &dk_da);
    const double force = -k * x - damping * rate;
    forces[first] += force;
    if (second >= 0) forces[second] -= force;
    if (dk_da != 0.0) forces -= 0.5 * dk_da * x * x * nut_gradient;
    elastic += 0.5 * k * x * x;
    damping_power += damping * rate * rate;
  }

  // Its damping power c x'^2 at the velocities v.
  template <class Vector>
  double damping_power(const Vector& v) const {
    const double rate = v[first] - (second >= 0 ? v[second] : 0.0);
    return damping * rate * rate;
  }

  // Adds `value` times its pattern (+ on the diagonal, - off it) to the
  // square matrix K: with value k the stiffness matrix -dF/dq, with value c
  // the damping matrix -dF/dv.
  template <class Matrix>
  void add_pattern(Matrix& K, double value) const {
    K(first, first) += value;
    if (second >= 0) {
      K(second, second) += value;
      K(first, second) -= value;
      K(second, first) -= value;
    }
  }
  template <class Matrix>
  void add_stiffness(Matrix& K, double a) const {
    double derivative = 0.0;
    add_pattern(K, stiffness_at(a, &derivative));
  }
  template <class Matrix>
  void add_damping(Matrix& C) const {
    add_pattern(C, damping);
  }
};

}  // namespace leadscrew::model::elements
