// Element: a penalty end stop of the load's travel (issue 19, item 3; scene
// section `end_stops`, contact = "penalty"; docs/physics/end_stops.md): a
// one-sided spring-damper on the load coordinate u against the ground, at
// `position` (the stop's face; the scene gives it relative to the load's
// start, which a relaxed start puts at u = 0).
//
// Penetration d = side (u - position) (side +1: the upper stop, -1: the lower)
// and its rate d' = side u'. The stop pushes, never pulls:
//   F = max(0, k d + c d')  where d > 0,   F = 0 where d <= 0,
// its force on the load -side F. (Kelvin-Voigt in contact; where the load
// leaves faster than the damper lets the spring relax, k d + c d' < 0, the
// load has left the stop's face and the force is 0, not a pull.)
// Energy: the elastic energy k d^2 / 2 (d > 0) and the loss power
//   F d' - k d d'  (= c d'^2 in contact, = -k d d' > 0 after the release),
// never negative: the stop's work on the load is minus the change of its
// elastic energy minus its loss.
// Events: contact_margin() > 0 exactly where F > 0 (min(d, d + c d' / k), a
// length); DriveHybrid's end-stop roots watch it, so that the integrator
// does not step over the onset (a jump of c d') or the release (a kink).
//
// As a force element (ForceElements): add_forces, elastic energy and loss
// power at a state. Its Jacobian depends on the contact, which
// add_stiffness(K, a) / add_damping(C) / damping_power(v) do not see:
// they add nothing. Moreau-Jean decides the contact per step and adds k and
// c itself (drive/moreau.cpp, DriveMoreau::assemble); the static
// equilibrium is the drive's without its stops (the load starts strictly
// between them), which DriveModel::place_stops_at_equilibrium places
// relative to it.
#pragma once

#include <algorithm>
#include <string>

namespace leadscrew::model::elements {

struct EndStop {
  std::string name;       // "lower end stop" or "upper end stop"
  int coordinate = -1;    // the load's coordinate
  int side = 1;           // +1: upper stop (pushes toward -u), -1: lower (toward +u)
  double position = 0.0;  // the face's u [m]
  double stiffness = 0.0;  // k [N/m] > 0
  double damping = 0.0;    // c [N s/m] >= 0
  bool on_screw = false;   // (the force element's field: the stop is on the ground)

  double penetration(double u) const { return side * (u - position); }
  // The pushing force F >= 0 at position u and velocity du [N].
  double pushing_force(double u, double du) const {
    const double d = penetration(u);
    if (!(d > 0.0)) return 0.0;
    return std::max(0.0, stiffness * d + damping * side * du);
  }
  // Its force on the load along +u [N] (the channel stop_force).
  double force_on_load(double u, double du) const { return -side * pushing_force(u, du); }
  // > 0 exactly where the stop pushes: min(d, d + c d' / k) [m].
  double contact_margin(double u, double du) const {
    const double d = penetration(u);
    return std::min(d, d + damping * side * du / stiffness);
  }

  template <class Vector, class Gradient>
  void add_forces(const Vector& q, const Vector& v, double a, const Gradient& nut_gradient,
                  Vector& forces, double& elastic, double& damping_power) const {
    (void)a;
    (void)nut_gradient;
    const double d = penetration(q[coordinate]);
    if (!(d > 0.0)) return;
    const double rate = side * v[coordinate];
    const double force = std::max(0.0, stiffness * d + damping * rate);
    forces[coordinate] -= side * force;
    elastic += 0.5 * stiffness * d * d;
    damping_power += (force - stiffness * d) * rate;
  }

  // (See above: the contact's Jacobian is not part of this interface.)
  template <class Vector>
  double damping_power(const Vector& v) const {
    (void)v;
    return 0.0;
  }
  template <class Matrix>
  void add_stiffness(Matrix& K, double a) const {
    (void)K;
    (void)a;
  }
  template <class Matrix>
  void add_damping(Matrix& C) const {
    (void)C;
  }
  // Its stiffness in contact (the result checks' force scale).
  double stiffness_at(double a, double* derivative) const {
    (void)a;
    *derivative = 0.0;
    return stiffness;
  }
};

// An exact end stop (contact = "exact"; docs/physics/end_stops.md): a
// unilateral contact on the load coordinate u, gap g = side (position - u)
// >= 0, with Newton's impact law u'+ = -e u'- (restitution e), and a closed
// contact (u held at the face) while the forces on the load press it
// there (on the rigid drive the stop carries the loads, the thread's
// friction what it cannot: docs/physics/end_stops.md, "The rigid drive at
// an exact stop"); DriveHybrid holds its contact state
// (hybrid_end_stops.cpp). Not a force element.
struct ExactEndStop {
  std::string name;
  int coordinate = -1;
  int side = 1;
  double position = 0.0;
  double restitution = 0.0;

  // The gap to the face [m] (>= 0 while free).
  double gap(double u) const { return side * (position - u); }
};

}  // namespace leadscrew::model::elements
