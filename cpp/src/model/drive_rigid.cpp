#include "leadscrew/model/drive_rigid.hpp"

#include "leadscrew/core/errors.hpp"

namespace leadscrew::model {

bool RigidDriveModes::applies(const DriveModel& model, const DriveDynamics& dynamics) {
  const DriveParameters& p = model.parameters();
  return p.concept == Concept::rigid && model.bilateral_thread() && !p.speed_controlled &&
         p.friction == FrictionLaw::coulomb && model.springs().empty() &&
         model.coordinate_count() == 2 && model.independent().size() == 1 &&
         !dynamics.painleve_possible();
}

RigidDriveModes::RigidDriveModes(const DriveModel& model, DriveDynamics& dynamics) {
  if (!applies(model, dynamics))
    throw InvalidArgument("RigidDriveModes needs the torque-driven rigid drive without play "
                          "with exact Coulomb friction outside the Painleve regime");
  const int n = model.coordinate_count();
  const int rotor = model.rotor();
  const int load = model.load();
  // The thread e = grad e . q = 0 with the load eliminated (StateLayout):
  // u_load = -(de/dphi) / (de/du) phi, i.e. -h p phi (eq. 4.1 with the supports).
  const Eigen::VectorXd& play_gradient = model.play_gradient();
  load_per_angle_ = -play_gradient[rotor] / play_gradient[load];
  const Eigen::VectorXd& tangent = model.tangent_direction();
  slip_per_speed_ = tangent[rotor] + tangent[load] * load_per_angle_;
  inertia_ = model.mass()[rotor];
  mass_ = model.mass()[load];

  const CoordinateVector zero = CoordinateVector::Zero(n);
  dynamics.set_state(0.0, zero, zero);
  CoordinateVector unit_torque = zero, unit_force = zero;
  unit_torque[rotor] = 1.0;
  unit_force[load] = 1.0;
  const FrictionMode frictions[] = {FrictionMode::none, FrictionMode::stick, FrictionMode::slip,
                                    FrictionMode::slip};
  const int slip_signs[] = {0, 0, 1, -1};
  for (int mode = 0; mode < 4; ++mode) {
    for (int side = 0; side < 2; ++side) {
      ModeSpec spec;
      spec.contact = ThreadContact::bilateral;
      spec.sigma = side == 0 ? 1 : -1;
      spec.friction = frictions[mode];
      spec.slip_sign = slip_signs[mode];
      const ModeSolution torque = dynamics.solve_with_forces(spec, unit_torque);
      const ModeSolution force = dynamics.solve_with_forces(spec, unit_force);
      if (!torque.regular || !force.regular)
        throw SimulationError(0.0, "the constraint equations of the rigid drive are singular",
                              "check masses, inertias and the thread geometry");
      RigidModeCoefficients& c = table_[index(spec.friction, spec.slip_sign)][side];
      c.acceleration = {torque.acceleration[rotor], force.acceleration[rotor]};
      c.normal_force = {torque.normal_force, force.normal_force};
      c.friction_force = {torque.friction_force, force.friction_force};
    }
  }
}

}  // namespace leadscrew::model
