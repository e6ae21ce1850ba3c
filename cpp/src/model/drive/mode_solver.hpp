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
//                           constrained solve (DriveHybrid::solve_current);
//                           the train's friction stages behind a prescribed
//                           rotor speed (the motor's torque and their losses)
//   train_solver.cpp        TrainSolver: the rigid drive without play with
//                           the train's friction stages (a DC motor too)
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
  // DriveHybrid::project: y's change onto the mode's held constraints (false:
  // y carries none, the rigid drive's one degree of freedom).
  virtual bool project(double t, const double* y, double* correction) {
    (void)t, (void)y, (void)correction;
    return false;
  }

 protected:
  DriveHybrid& h_;
};

class DriveHybrid::ConstrainedSolver final : public DriveHybrid::ModeSolver {
 public:
  explicit ConstrainedSolver(DriveHybrid& hybrid);
  void expand(double t, const double* y) override { h_.set(t, y); }
  double slip_velocity(const double* y) const override;
  ThreadForces forces(double t, const double* y) override;
  void rhs(double t, const double* y, double* ydot) override;
  ChannelState output(double t, const double* y, ContactForces& forces) override;
  double slip_resolution() const override;
  RigidModeCoefficients coefficients(int sigma) override;
  bool project(double t, const double* y, double* correction) override;

 private:
  // LuGre's bristles (lugre_bristles_kind): the deflection's index in y
  // (its stored energy's follows; -1: none) and its channel's; their rates
  // and the friction power they store in the solution s (rhs).
  int bristle_state_, bristle_channel_;
  void bristle_rates(const ModeSolution& s, double* ydot, double* energy) const;
  // The train's friction stages behind a prescribed rotor speed (nullptr:
  // none, or a torque-driven rotor, which TrainSolver takes): the motor's
  // torque on the rotor's coordinate in the solution s at the speed set
  // (the constraint's multiplier and the frictions ahead of the stage's
  // output), their loss integrals in y and channels (train_friction_kind).
  const elements::TrainFriction* speed_train_;
  double speed_train_torque(const ModeSolution& s) const;
  int motor_friction_state_, gear_state_, motor_friction_channel_, gear_channel_;
};

// What the rigid drive without play's solvers share: one degree of freedom,
// y = [phi, omega, ...], the thread's modes in closed form (RigidDriveModes,
// computed with the hybrid's DriveDynamics: its state is reset).
class DriveHybrid::RigidDofSolver : public DriveHybrid::ModeSolver {
 public:
  explicit RigidDofSolver(DriveHybrid& hybrid)
      : ModeSolver(hybrid), rigid_(hybrid.model_, hybrid.dynamics_) {}
  double slip_velocity(const double* y) const override {
    return rigid_.slip_per_speed() * y[1];
  }
  double slip_resolution() const override;
  RigidModeCoefficients coefficients(int sigma) override;

 protected:
  RigidDriveModes rigid_;
};

class DriveHybrid::RigidSolver final : public DriveHybrid::RigidDofSolver {
 public:
  // The model must be one RigidDriveModes applies to.
  explicit RigidSolver(DriveHybrid& hybrid);
  void expand(double t, const double* y) override;
  ThreadForces forces(double t, const double* y) override;
  void rhs(double t, const double* y, double* ydot) override;
  ChannelState output(double t, const double* y, ContactForces& forces) override;

 private:
  struct Solution {
    double torque = 0.0, axial_force = 0.0;
    double acceleration = 0.0, normal_force = 0.0, friction_force = 0.0;
  };
  Solution solve(double t, const double* y);

  double loads_time_;  // the loads last evaluated (NaN: none yet)
  double torque_ = 0.0, axial_force_ = 0.0;
};

// The rigid drive without play with the train's friction stages
// (elements/train_friction.hpp: the motor's Coulomb friction, a lossy or worm
// stage), driven by a torque or a DC motor: one degree of freedom whose
// contacts (motor, stage, thread) stick and slip together. In slip with sign
// s each contact's friction opposes the slip and its size follows the sign
// of what it transmits (the thread's normal force sigma, the stage's power
// flow); for each combination of the signs the acceleration and the forces
// are linear in the loads (the thread's from RigidDriveModes), and the one
// consistent combination is kept (none or several: JammingError). At zero
// slip the drive sticks while neither direction's start is consistent
// (breakaway, with the stages' static coefficients). Chosen by
// make_mode_solver for every model with friction stages (train_solver.cpp).
class DriveHybrid::TrainSolver final : public DriveHybrid::RigidDofSolver {
 public:
  explicit TrainSolver(DriveHybrid& hybrid);
  void expand(double t, const double* y) override { h_.set(t, y); }
  ThreadForces forces(double t, const double* y) override;
  void rhs(double t, const double* y, double* ydot) override;
  ChannelState output(double t, const double* y, ContactForces& forces) override;

  // At the state set, at zero slip: 0 where the train can stick (the static
  // test, stick_margin >= 0, and hint 0), else the direction in which a
  // slip starts consistently (+-1; both, or two combinations: JammingError);
  // `hint` (+-1: a stick's root fired for that direction) is taken where
  // neither starts.
  int breakaway(int hint);
  // At the state set: the static stick test's margin, >= 0 iff some split
  // of the holding torque between the motor's friction, the stage (its
  // static efficiencies) and the thread (its cone) holds the loads.
  double stick_margin();
  // The direction in which the loads leave the static test (its smaller margin).
  int exit_direction();
  // In slip, at the state set: the stage's torque on the driven part tau_b
  // (its sign is the power flow's with the slip's; a root where it changes).
  double stage_torque();
  // A stage whose law changes with the power flow's sign (a lossless one
  // does not: no root).
  bool has_stage() const noexcept {
    return train_.stage && !(train_.efficiency == 1.0 && train_.efficiency_backdrive == 1.0);
  }

 private:
  struct Solution {
    double torque = 0.0, axial_force = 0.0;  // on the rotor (the motor's), on the load
    double acceleration = 0.0, normal_force = 0.0, friction_force = 0.0;
    double stage_torque = 0.0, stage_loss = 0.0;  // tau_b, (k - 1) tau_b on phi [N m]
    int count = 0;  // consistent combinations found (slip)
  };
  // The thread's slip response per unit torque on phi and per unit axial force.
  struct ThreadSlip {
    double a = 0.0, b = 0.0, normal_q = 0.0, normal_f = 0.0, friction_q = 0.0, friction_f = 0.0;
  };
  double coordinate_torque() const;
  // The axial force on the load along +u at the state set [N]: the scene's
  // axial load and the penalty end stops' force (stop_force; 0 without).
  double load_force() const;
  double stop_force() const;  // the penalty stops' force on the load [N] (0: none)
  Solution slip(int s, bool breakaway, double torque, double force);
  Solution stick(double torque, double force) const;
  void thread_holds(double force, double& lo, double& hi) const;
  void static_margins(double& up, double& down) const;
  std::string stage_regime(bool breakaway) const;
  Solution solve();

  const elements::TrainFriction& train_;
  // The stages' loss integrals in y, their channels (train_friction_kind;
  // -1: none).
  int motor_friction_state_, gear_state_, motor_friction_channel_, gear_channel_;
  const std::vector<elements::EndStop>& stops_;  // the penalty end stops (on the load)
  // The sign of phi' in a slip of sign +1 (gamma_T = slip_per_speed phi'):
  // -1 where the rotor turns the nut (drive = "nut"). The motor's friction,
  // the stage's power flow and a start's acceleration go with phi', the
  // thread's coefficients and the mode's sign with the slip.
  int phi_per_slip_ = 1;
  ThreadSlip thread_[2][2];  // [s > 0 ? 0 : 1][sigma > 0 ? 0 : 1]
  RigidModeCoefficients stick_;  // per unit torque on phi
  int stage_guess_ = 1;
};

}  // namespace leadscrew::model::drive
