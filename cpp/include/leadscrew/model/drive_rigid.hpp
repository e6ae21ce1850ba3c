// The rigid drive without play as a one-degree-of-freedom system (thesis
// section 4.1.1 and 4.3; docs/physics/rigid_drive.md, sections 5 and 6).
//
// The thread eliminates the load's coordinate, so the only state is the
// rotor's angle phi and speed omega. The model has no springs and no dampers:
// the generalized forces are the drive torque M(t) on the rotor and the axial
// force F(t) on the load, nothing else. In each exact-Coulomb mode (free,
// stick, slip in either direction) with an assumed sign sigma of the flank
// normal force, the friction factor is a constant, so the constrained solve is
// linear in (M, F): the rotor acceleration is a M + b F (eq. 4.10 for
// sigma = +1, eq. 4.11 for sigma = -1), and so are the normal and friction
// forces (stick: eq. 3.1 projected on the flank). The coefficients are computed
// once per mode by the general constrained solve of DriveDynamics with unit
// loads (so the two paths share one set of equations) and a right-hand side
// costs two load evaluations and a few multiplications.
//
// It applies to the torque-driven rigid drive without play with exact Coulomb
// friction outside the Painleve regime (mu' |G_NT| < G_NN: one consistent
// normal-force sign in every slip state); everything else takes the general
// path.
#pragma once

#include <string>

#include <array>
#include <limits>
#include <optional>

#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model {

// Linear response of one mode to the loads: value = per_torque M + per_force F.
struct LoadCoefficients {
  double per_torque = 0.0;
  double per_force = 0.0;
  double operator()(double torque, double force) const noexcept {
    return per_torque * torque + per_force * force;
  }
};

struct RigidModeCoefficients {
  LoadCoefficients acceleration;    // rotor acceleration [rad/s^2]
  LoadCoefficients normal_force;    // lambda_N on the screw [N]
  LoadCoefficients friction_force;  // lambda_T on the screw [N]
};

// What a scan of load-driven functions found (first_load_crossing).
struct LoadCrossing {
  // The crossing (found), or where the scan stopped without one: +inf where
  // it reached t_end (none in the run), else its horizon, from which a scan
  // goes on.
  double time = std::numeric_limits<double>::infinity();
  bool found = false;
};

// The first time in (t0, t_end] at which one of `count` load-driven functions
// f_k(t) = functions[k](M(t), F(t)) falls below zero (f_k >= 0 at t0 is
// assumed; a function already <= 0 there and falling crosses at t0), or none
// (time +inf) if none does; a scan stops at a horizon of kLoadScanSteps
// steps (a mode that lasts for 1e5 load periods scans on from there: one
// scan to t_end took O(t_end) per mode start and ended a run of the shipped
// default scene at t_end = 3e5 s in an error). In a mode of the rigid drive the thread forces are linear in
// the loads (RigidModeCoefficients), and in stick the state is frozen, so the
// stick-cone margin and the normal force's side are such functions of time
// alone: a step bound of a fraction of the load period cannot see an
// excursion shorter than a step, this scan can. It steps by certified lower
// bounds f_k(t + h) >= f_k(t) + f_k'(t) h - K_k h^2 / 2 with K_k >= |f_k''|
// (a sine's |A| w^2, a table's 0 between its knots, which bound the scan's
// steps), so no sign change is passed unseen; an excursion shorter than
// 1e-12 of the loads' time scale is taken for a touch. The zero is then
// located by Illinois to round-off. nullopt: a load gives no bound on its
// curvature (a callable); the caller keeps the root function sampled at the
// integrator's steps. Every loop is bounded.
constexpr long kLoadScanSteps = 10000;
std::optional<LoadCrossing> first_load_crossing(const Excitation& torque, const Excitation& force,
                                          const LoadCoefficients* functions, int count,
                                          double t0, double t_end);

class RigidDriveModes {
 public:
  // True if the model is the torque-driven rigid drive without play with exact
  // Coulomb friction and no Painleve regime (dynamics: the model's workspace).
  static bool applies(const DriveModel& model, const DriveDynamics& dynamics);
  // The same with the rotor's torque from any motor but a speed-controlled
  // one (a DC motor's k_t i: the coefficients are per unit torque whatever
  // gives it) and a model without the train's friction stages or with them
  // (DriveHybrid::TrainSolver), whose penalty end stops (force elements of
  // the load's state alone) it takes besides: one more axial force.
  static bool applies_to_thread(const DriveModel& model, const DriveDynamics& dynamics);
  // Why applies_to_thread fails for a model whose parameters the train's
  // stages admit on the event-driven scheme (elements::train_event_driven_
  // obstacle: the rigid concept without play, plain Coulomb): a force
  // element besides the end stops, or the thread's Painleve regime, which
  // only the masses tell ("" where it holds).
  static std::string train_obstacle(const DriveModel& model, const DriveDynamics& dynamics);

  // Computes the coefficients of every mode with dynamics (its state is reset).
  RigidDriveModes(const DriveModel& model, DriveDynamics& dynamics);

  // Coefficients of a mode: friction none, stick or slip (slip_sign +-1), and
  // the sign of the normal force assumed in it.
  const RigidModeCoefficients& coefficients(FrictionMode friction, int slip_sign,
                                            int sigma) const noexcept {
    return table_[index(friction, slip_sign)][sigma > 0 ? 0 : 1];
  }

  // Load displacement and slip velocity per unit rotor angle and speed:
  // u_load = load_per_angle phi (the thread, eq. 4.1), gamma_T = slip_per_speed omega.
  double load_per_angle() const noexcept { return load_per_angle_; }
  double slip_per_speed() const noexcept { return slip_per_speed_; }
  double inertia() const noexcept { return inertia_; }  // J [kg m^2]
  double mass() const noexcept { return mass_; }        // m [kg]

 private:
  static int index(FrictionMode friction, int slip_sign) noexcept {
    if (friction == FrictionMode::stick) return 1;
    if (friction == FrictionMode::slip) return slip_sign > 0 ? 2 : 3;
    return 0;
  }

  std::array<std::array<RigidModeCoefficients, 2>, 4> table_{};
  double load_per_angle_ = 0.0, slip_per_speed_ = 0.0, inertia_ = 0.0, mass_ = 0.0;
};

}  // namespace leadscrew::model
