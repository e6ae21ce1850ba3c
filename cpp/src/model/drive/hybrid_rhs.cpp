// DriveHybrid (hybrid.hpp): construction, the right-hand side of the current
// mode (the rigid drive's one degree of freedom, LuGre's bristle states and
// energy), the output rows, the loads' breakpoints and time scales.
#include "hybrid.hpp"

#include "channels.hpp"

namespace leadscrew::model::drive {

DriveHybrid::DriveHybrid(const DriveModel& model, const friction::Law& law,
                         double bounce_threshold, double t_end,
                         const integrate::IntegratorOptions& integrator_options)
    : model_(model),
      p_(model.parameters()),
      dynamics_(model, &law),
      layout_(model, law.resolution() == friction::Resolution::bristle),
      bounce_threshold_(bounce_threshold),
      backlash_(p_.backlash != BacklashContact::none),
      t_end_(t_end),
      integrator_options_(integrator_options) {
  const int n = model.coordinate_count();
  q_.setZero(n);
  v_.setZero(n);
  names_ = drive_channel_names(model);
  saved_state_.resize(static_cast<std::size_t>(layout_.size()));
  if (RigidDriveModes::applies(model, dynamics_)) rigid_.emplace(model, dynamics_);
}

void DriveHybrid::rhs(double t, const double* y, double* ydot) {
  if (rigid_) {
    // One degree of freedom: y = [phi_rotor, omega_rotor, energy integrals].
    const RigidSolution s = solve_rigid(t, y);
    const double omega = y[1];
    ydot[0] = omega;
    ydot[1] = s.acceleration;
    double* energy = ydot + layout_.energy_offset();
    energy[kWorkDrive] = s.torque * omega;
    energy[kWorkAxial] = s.axial_force * rigid_->load_per_angle() * omega;
    energy[kFrictionLoss] = -s.friction_force * rigid_->slip_per_speed() * omega;
    energy[kDampingLoss] = 0.0;
    energy[kContactLoss] = 0.0;
    return;
  }
  set(t, y);
  const ModeSolution s = solve_current();
  const int np = static_cast<int>(layout_.positions().size());
  for (int k = 0; k < np; ++k) ydot[k] = v_[layout_.positions()[k]];
  for (std::size_t k = 0; k < layout_.velocities().size(); ++k)
    ydot[np + k] = s.acceleration[layout_.velocities()[k]];
  double* energy = ydot + layout_.energy_offset();
  energy[kWorkDrive] = model_.motor().power(s.motor_torque, v_);
  energy[kWorkAxial] = model_.axial_load().power(dynamics_.axial_force(), v_);
  energy[kFrictionLoss] =
      mode_.friction == FrictionMode::stick ? 0.0 : -s.friction_force * dynamics_.slip_velocity();
  const int bristle = layout_.bristle();
  if (bristle >= 0) {
    // LuGre's bristles: z' of the law. Of the friction's power, the part
    // |N|' sigma0 z z' is stored in the bristles, not lost; it is
    // integrated (the state after z) rather than taken as |N|' sigma0 z^2
    // / 2, which would miss the work of a changing normal force on a
    // deflected bristle. What remains, |N|' (sigma0^2 |gamma| z^2 / mu(|gamma|)
    // + sigma1 z' gamma) + viscous gamma^2, is the loss (sigma1 z' gamma can be
    // negative: LuGre is passive only for small sigma1).
    const double z = y[bristle];
    const double rate = dynamics_.law().bristle_rate(dynamics_.slip_velocity(), z);
    const double stored = std::abs(s.normal_force) * model_.flank_factor() *
                          dynamics_.law().bristle_stiffness() * z * rate;
    ydot[bristle] = rate;
    ydot[bristle + 1] = stored;
    energy[kFrictionLoss] -= stored;
  }
  energy[kDampingLoss] = dynamics_.damping_power();
  energy[kContactLoss] = dynamics_.contact_loss_power();
  if (model_.dc_motor()) motor_rates(t, ydot, energy);
}

// The rigid drive's forces and acceleration at (t, y) from the coefficients
// of its mode (RigidDriveModes): the decisions of solve_current without the
// constrained solve. Outside the Painleve regime at most one normal-force
// sign is consistent: try the last one first.
DriveHybrid::RigidSolution DriveHybrid::solve_rigid(double t, const double* y) {
  RigidSolution s;
  if (t != loads_time_) {  // the roots at a step's end follow its last stage
    loads_time_ = t;
    torque_ = p_.drive_torque(t);
    axial_force_ = p_.axial_force(t);
  }
  s.torque = torque_;
  s.axial_force = axial_force_;
  const bool slip = mode_.friction == FrictionMode::slip;
  for (int attempt = 0; attempt < 2; ++attempt) {
    const RigidModeCoefficients& c =
        rigid_->coefficients(mode_.friction, mode_.slip_sign, slip ? sigma_guess_ : 1);
    s.normal_force = c.normal_force(s.torque, s.axial_force);
    if (slip && sigma_guess_ * s.normal_force < 0.0) {
      sigma_guess_ = -sigma_guess_;
      continue;
    }
    s.acceleration = c.acceleration(s.torque, s.axial_force);
    s.friction_force = c.friction_force(s.torque, s.axial_force);
    return s;
  }
  set(t, y);  // the state for the report
  jam("no sign of the flank normal force is consistent");
}

void DriveHybrid::channels(double t, const double* y, double* out) {
  ContactForces forces;
  forces.stick = mode_.friction == FrictionMode::stick;
  if (rigid_) {
    const RigidSolution s = solve_rigid(t, y);
    forces.normal = s.normal_force;
    forces.friction = s.friction_force;
    forces.motor_torque = s.torque;
    const double phi = y[0], omega = y[1];
    const double v_load = rigid_->load_per_angle() * omega;
    q_[model_.rotor()] = phi;
    q_[model_.load()] = rigid_->load_per_angle() * phi;
    v_[model_.rotor()] = omega;
    v_[model_.load()] = v_load;
    const ChannelState state{q_,
                             v_,
                             s.axial_force,
                             rigid_->slip_per_speed() * omega,
                             0.0,
                             0.5 * (rigid_->inertia() * omega * omega + rigid_->mass() * v_load * v_load),
                             0.0};
    write_drive_channels(model_, state, forces, y + layout_.energy_offset(), impact_loss_,
                         kinetic0_, elastic0_, out);
    return;
  }
  set(t, y);
  if (p_.backlash == BacklashContact::exact && mode_.contact == ThreadContact::open)
    check_flight(t);
  const ModeSolution s = solve_current();
  forces.normal = s.normal_force;
  forces.friction = s.friction_force;
  forces.motor_torque = s.motor_torque;
  ChannelState state = channel_state(dynamics_);
  if (layout_.bristle() >= 0) {
    state.bristle = y[layout_.bristle()];
    state.elastic += y[layout_.bristle() + 1];  // the bristles' stored energy
  }
  // Stick holds the slip velocity at zero; the state carries the integrator's
  // error in this linear invariant (CVODE's Newton tolerance, ~1e-15 m/s).
  if (forces.stick) state.slip_velocity = 0.0;
  if (model_.dc_motor()) motor_channels(t, y, state);
  write_drive_channels(model_, state, forces, y + layout_.energy_offset(), impact_loss_,
                       kinetic0_, elastic0_, out);
}

std::vector<double> DriveHybrid::breakpoints() const {
  std::vector<double> times = p_.axial_force.breakpoints();
  const Excitation& drive = p_.dc_motor           ? p_.motor_voltage
                            : p_.speed_controlled ? p_.drive_speed
                                                  : p_.drive_torque;
  times.insert(times.end(), drive.breakpoints().begin(), drive.breakpoints().end());
  return times;
}

double DriveHybrid::max_step_hint() const {
  const Excitation& drive = p_.dc_motor           ? p_.motor_voltage
                            : p_.speed_controlled ? p_.drive_speed
                                                  : p_.drive_torque;
  return integrate::max_step_from_time_scales(
      {drive.time_scale(), p_.axial_force.time_scale()});
}

}  // namespace leadscrew::model::drive
