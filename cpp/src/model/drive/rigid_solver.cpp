// DriveHybrid::RigidSolver (mode_solver.hpp): the rigid drive without play as
// one degree of freedom, y = [phi_rotor, omega_rotor, energy integrals]; the
// forces and the acceleration of every mode are linear in the loads, from
// RigidDriveModes' coefficients (drive_rigid.hpp; docs/physics/rigid_drive.md).
#include <cmath>
#include <limits>

#include "mode_solver.hpp"

namespace leadscrew::model::drive {

DriveHybrid::RigidSolver::RigidSolver(DriveHybrid& hybrid)
    : RigidDofSolver(hybrid),
      loads_time_(std::numeric_limits<double>::quiet_NaN()) {}

// For the nut's position alone (the screw-end root, at every root
// evaluation): StateLayout::expand's result for y = [phi, omega, ...] and
// the load eliminated by e = grad e . q = 0, written out. StateLayout's
// general loops took 157 instructions of the 518 of a rigid drive's root
// evaluation (callgrind); this takes about 20. Bit for bit StateLayout's:
// grad e . q is w_rotor phi (the load's term is w_load 0).
void DriveHybrid::RigidSolver::expand(double /*t*/, const double* y) {
  const Eigen::VectorXd& w = h_.model_.play_gradient();
  const int rotor = h_.model_.rotor(), load = h_.model_.load();
  h_.q_.setZero(2);
  h_.v_.setZero(2);
  h_.q_[rotor] = y[0];
  h_.v_[rotor] = y[1];
  h_.q_[load] = -(w[rotor] * y[0]) / w[load];
  h_.v_[load] = -(w[rotor] * y[1]) / w[load];
}

// The forces and acceleration at (t, y) from the coefficients of the mode:
// DriveHybrid::solve_current's decisions without the constrained solve.
// Outside the Painleve regime at most one normal-force sign is consistent:
// try the last one first.
DriveHybrid::RigidSolver::Solution DriveHybrid::RigidSolver::solve(double t, const double* y) {
  Solution s;
  if (t != loads_time_) {  // the roots at a step's end follow its last stage
    loads_time_ = t;
    torque_ = h_.p_.drive_torque(t);
    axial_force_ = h_.p_.axial_force(t);
  }
  s.torque = torque_;
  s.axial_force = axial_force_;
  const Mode& mode = h_.mode_;
  int& sigma = h_.sigma_guess_;
  const bool slip = mode.friction == FrictionMode::slip;
  for (int attempt = 0; attempt < 2; ++attempt) {
    const RigidModeCoefficients& c =
        rigid_.coefficients(mode.friction, mode.slip_sign, slip ? sigma : 1);
    s.normal_force = c.normal_force(s.torque, s.axial_force);
    if (slip && sigma * s.normal_force < 0.0) {
      sigma = -sigma;
      continue;
    }
    s.acceleration = c.acceleration(s.torque, s.axial_force);
    s.friction_force = c.friction_force(s.torque, s.axial_force);
    return s;
  }
  h_.set(t, y);  // the state for the report
  h_.jam("no sign of the flank normal force is consistent");
}

ThreadForces DriveHybrid::RigidSolver::forces(double t, const double* y) {
  const Solution s = solve(t, y);
  return {s.normal_force, s.friction_force};
}

void DriveHybrid::RigidSolver::rhs(double t, const double* y, double* ydot) {
  const Solution s = solve(t, y);
  const double omega = y[1];
  ydot[0] = omega;
  ydot[1] = s.acceleration;
  double* energy = ydot + h_.layout_.energy_offset();
  energy[kWorkDrive] = h_.model_.gear().driven_torque(s.torque) * omega;
  energy[kWorkAxial] = s.axial_force * rigid_.load_per_angle() * omega;
  energy[kFrictionLoss] = -s.friction_force * rigid_.slip_per_speed() * omega;
  energy[kDampingLoss] = 0.0;
  energy[kContactLoss] = 0.0;
}

ChannelState DriveHybrid::RigidSolver::output(double t, const double* y, ContactForces& forces) {
  const Solution s = solve(t, y);
  forces.normal = s.normal_force;
  forces.friction = s.friction_force;
  forces.motor_torque = s.torque;
  const double phi = y[0], omega = y[1];
  const double v_load = rigid_.load_per_angle() * omega;
  const DriveModel& model = h_.model_;
  h_.q_[model.rotor()] = phi;
  h_.q_[model.load()] = rigid_.load_per_angle() * phi;
  h_.v_[model.rotor()] = omega;
  h_.v_[model.load()] = v_load;
  return {h_.q_,
          h_.v_,
          s.axial_force,
          rigid_.slip_per_speed() * omega,
          0.0,
          0.5 * (rigid_.inertia() * omega * omega + rigid_.mass() * v_load * v_load),
          0.0};
}

double DriveHybrid::RigidDofSolver::slip_resolution() const {
  return std::abs(rigid_.slip_per_speed()) * h_.integrator_options_.atol;
}

RigidModeCoefficients DriveHybrid::RigidDofSolver::coefficients(int sigma) {
  return rigid_.coefficients(h_.mode_.friction, h_.mode_.slip_sign, sigma);
}

}  // namespace leadscrew::model::drive
