// How DriveHybrid's current mode is solved at a state y, and how y maps to
// the coordinates, the slip velocity, the energy rates and an output row:
// the one place where a drive's structure specialises the event-driven
// driver. Internal to cpp/src/model (docs/architecture.md, "The rigid path
// as a specialisation").
//
// Two implementations, each in a file of its own, chosen once per
// DriveHybrid by make_mode_solver (mode_solver.cpp) from the model's
// structure:
//   constrained_solver.cpp  ConstrainedSolver: any model; y expanded by
//                           StateLayout, the mode solved by DriveDynamics'
//                           constrained solve (DriveHybrid::solve_current)
//   rigid_solver.cpp        RigidSolver: the rigid drive without play, one
//                           degree of freedom (RigidDriveModes::applies); y =
//                           [phi, omega, energy integrals], every mode in
//                           closed form from RigidDriveModes' coefficients
// The mode itself (contact, stick or slip, the flank's sign), its events and
// their decisions (the flank LCP, impacts, jamming) stay DriveHybrid's, for
// every model: an implementation only evaluates the mode it is given. The
// implementations are DriveHybrid's nested classes (they read its mode and
// workspace); no call allocates.
#pragma once

#include <memory>

#include "channels.hpp"
#include "hybrid.hpp"

namespace leadscrew::model::drive {

// The thread's forces in the current mode [N] (on the screw).
struct ThreadForces {
  double normal_force = 0.0;
  double friction_force = 0.0;
  double preload_normal = 0.0;  // a preloaded nut's preload half (ModeSolution's)
};

class DriveHybrid::ModeSolver {
 public:
  explicit ModeSolver(DriveHybrid& hybrid) : h_(hybrid) {}
  virtual ~ModeSolver() = default;
  ModeSolver(const ModeSolver&) = delete;
  ModeSolver& operator=(const ModeSolver&) = delete;

  // y at t into the coordinates DriveHybrid::q_, v_ (the constrained
  // solve: and the dynamics' state, DriveHybrid::set).
  virtual void expand(double t, const double* y) = 0;
  // The slip velocity gamma_T at the state expand set [m/s].
  virtual double slip_velocity(const double* y) const = 0;
  // The current mode's thread forces at (t, y), after expand.
  virtual ThreadForces forces(double t, const double* y) = 0;
  // The right-hand side of the current mode: positions, velocities,
  // internal states, the work and loss integrals' rates.
  virtual void rhs(double t, const double* y, double* ydot) = 0;
  // An output row's state at (t, y); fills the thread's and the motor's
  // forces (forces.stick is set by the caller).
  virtual ChannelState output(double t, const double* y, ContactForces& forces) = 0;
  // The slip velocity the integrator resolves: its absolute tolerance on the
  // velocities through the slip's gradient (|W_T| atol) [m/s].
  virtual double slip_resolution() const = 0;
  // The thread forces of the current mode per unit drive torque and axial
  // force, with the normal-force sign sigma where it matters (the
  // load-driven roots, hybrid_load_roots.cpp).
  virtual RigidModeCoefficients coefficients(int sigma) = 0;

 protected:
  DriveHybrid& h_;
};

class DriveHybrid::ConstrainedSolver final : public DriveHybrid::ModeSolver {
 public:
  explicit ConstrainedSolver(DriveHybrid& hybrid) : ModeSolver(hybrid) {}
  void expand(double t, const double* y) override { h_.set(t, y); }
  double slip_velocity(const double* y) const override;
  ThreadForces forces(double t, const double* y) override;
  void rhs(double t, const double* y, double* ydot) override;
  ChannelState output(double t, const double* y, ContactForces& forces) override;
  double slip_resolution() const override;
  RigidModeCoefficients coefficients(int sigma) override;
};

class DriveHybrid::RigidSolver final : public DriveHybrid::ModeSolver {
 public:
  // Computes the modes' coefficients with the hybrid's DriveDynamics (its
  // state is reset); the model must be one RigidDriveModes applies to.
  explicit RigidSolver(DriveHybrid& hybrid);
  void expand(double t, const double* y) override;
  double slip_velocity(const double* y) const override {
    return rigid_.slip_per_speed() * y[1];
  }
  ThreadForces forces(double t, const double* y) override;
  void rhs(double t, const double* y, double* ydot) override;
  ChannelState output(double t, const double* y, ContactForces& forces) override;
  double slip_resolution() const override;
  RigidModeCoefficients coefficients(int sigma) override;

 private:
  struct Solution {
    double torque = 0.0, axial_force = 0.0;
    double acceleration = 0.0, normal_force = 0.0, friction_force = 0.0;
  };
  Solution solve(double t, const double* y);

  RigidDriveModes rigid_;
  double loads_time_;  // the loads last evaluated (NaN: none yet)
  double torque_ = 0.0, axial_force_ = 0.0;
};

}  // namespace leadscrew::model::drive
