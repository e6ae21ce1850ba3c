// Element: a force element defined in a source file of its own, with its
// scene section (element_section.hpp; cpp/src/model/elements/<name>.cpp):
// its law behind one virtual call per member, so that a new element is its
// file and one registry line (section_registry.cpp), not a type in
// ForceElements. One virtual call per element and right-hand side; no
// string lookup, no allocation. A force that depends on the nut's position
// along the screw (the screw's stiffness) is a type of its own instead
// (SpringDamper).
#pragma once

#include <memory>

namespace leadscrew::model::elements {

// The law of a section's force element, on raw arrays of the coordinates
// (n of them; a matrix column-major, n x n).
class SectionForceLaw {
 public:
  virtual ~SectionForceLaw() = default;
  // Adds its generalized force at positions q and velocities v to `forces`,
  // its elastic energy to `elastic` and its loss power to `damping_power`.
  virtual void add_forces(const double* q, const double* v, double* forces, double& elastic,
                          double& damping_power) const = 0;
  // Its loss power at the velocities v (Moreau-Jean's step).
  virtual double damping_power(const double* v) const = 0;
  // Adds -dF/dq and -dF/dv (Moreau-Jean's iteration matrix, the equilibrium's Newton).
  virtual void add_stiffness(double* K, int n) const = 0;
  virtual void add_damping(double* C, int n) const = 0;
  // Its largest stiffness (the result checks' force bound).
  virtual double stiffness() const = 0;
};

struct SectionForce {
  std::shared_ptr<const SectionForceLaw> law;
  bool on_screw = false;  // (the force element's field: a section's element is not on the screw)

  template <class Vector, class Gradient>
  void add_forces(const Vector& q, const Vector& v, double a, const Gradient& nut_gradient,
                  Vector& forces, double& elastic, double& damping_power) const {
    (void)a;
    (void)nut_gradient;
    law->add_forces(q.data(), v.data(), forces.data(), elastic, damping_power);
  }
  template <class Vector>
  double damping_power(const Vector& v) const {
    return law->damping_power(v.data());
  }
  template <class Matrix>
  void add_stiffness(Matrix& K, double a) const {
    (void)a;
    law->add_stiffness(K.data(), static_cast<int>(K.rows()));
  }
  template <class Matrix>
  void add_damping(Matrix& C) const {
    law->add_damping(C.data(), static_cast<int>(C.rows()));
  }
  double stiffness_at(double a, double* derivative) const {
    (void)a;
    *derivative = 0.0;
    return law->stiffness();
  }
};

}  // namespace leadscrew::model::elements
