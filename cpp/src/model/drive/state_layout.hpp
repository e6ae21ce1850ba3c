// The event-driven and Moreau-Jean drive systems' state vector y: the
// independent positions, their velocities, LuGre's bristle states and the
// work and loss integrals. Internal to cpp/src/model (see
// docs/architecture.md); inline, as the right-hand side expands y at every call.
#pragma once

#include <vector>

#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model::drive {

// The work and loss integrals, the last entries of y (StateLayout::energy_offset).
enum Energy { kWorkDrive = 0, kWorkAxial, kFrictionLoss, kDampingLoss, kContactLoss, kEnergyCount };

// Between the ODE state y = [independent positions, their velocities (not the
// speed-controlled rotor's), work and loss integrals] and full coordinates.
class StateLayout {
 public:
  // `bristle`: the friction law has LuGre's bristle deflection z, a state
  // of its own after the velocities, followed by the bristles' stored energy
  // (DriveHybrid::rhs).
  // A DC motor (model.dc_motor()) adds its states after those: the armature
  // current (with inductance) and the copper loss integral.
  StateLayout(const DriveModel& model, bool bristle) : model_(model), bristle_(bristle) {
    const bool speed = model.parameters().speed_controlled;
    positions_ = model.independent();
    for (int i : positions_)
      if (!(speed && i == model.rotor())) velocities_.push_back(i);
    if (const elements::DcMotor* dc = model.dc_motor()) motor_states_ = dc->has_state() ? 2 : 1;
    if (const elements::TrainFriction* f = model.train_friction()) {
      if (f->motor_friction_present()) motor_friction_loss_ = motor_offset() + motor_states_;
      if (f->stage) gear_loss_ = motor_offset() + motor_states_ + (motor_friction_loss_ >= 0);
    }
  }
  int size() const { return energy_offset() + kEnergyCount; }
  // The bristle deflection's index (-1: none).
  int bristle() const {
    return bristle_ ? static_cast<int>(positions_.size() + velocities_.size()) : -1;
  }
  // The DC motor's current's index (-1: none, or no inductance) and its
  // copper loss integral's (-1: no DC motor).
  int motor_current() const { return motor_states_ == 2 ? motor_offset() : -1; }
  int copper_loss() const { return motor_states_ > 0 ? motor_offset() + motor_states_ - 1 : -1; }
  // The train's friction stages' loss integrals (train_friction.hpp), after
  // the motor's states: the motor's friction and the stage's (-1: none).
  int motor_friction_loss() const { return motor_friction_loss_; }
  int gear_loss() const { return gear_loss_; }
  int energy_offset() const {
    return motor_offset() + motor_states_ + (motor_friction_loss_ >= 0) + (gear_loss_ >= 0);
  }

  void expand(double t, const double* y, CoordinateVector& q, CoordinateVector& v) const {
    const int n = model_.coordinate_count();
    q.setZero(n);
    v.setZero(n);
    const int np = static_cast<int>(positions_.size());
    for (int k = 0; k < np; ++k) q[positions_[k]] = y[k];
    for (std::size_t k = 0; k < velocities_.size(); ++k) v[velocities_[k]] = y[np + k];
    if (model_.parameters().speed_controlled)
      v[model_.rotor()] = model_.motor().prescribed_speed(t);
    const int d = model_.eliminated();
    if (d >= 0) {
      // The thread without play: e = grad e . q = 0 fixes coordinate d.
      const Eigen::VectorXd& w = model_.play_gradient();
      q[d] = -w.dot(q) / w[d];
      v[d] = -w.dot(v) / w[d];
    }
  }

  void compress(const CoordinateVector& q, const CoordinateVector& v, double* y) const {
    const int np = static_cast<int>(positions_.size());
    for (int k = 0; k < np; ++k) y[k] = q[positions_[k]];
    for (std::size_t k = 0; k < velocities_.size(); ++k) y[np + k] = v[velocities_[k]];
  }

  const std::vector<int>& positions() const { return positions_; }
  const std::vector<int>& velocities() const { return velocities_; }

 private:
  int motor_offset() const {
    return static_cast<int>(positions_.size() + velocities_.size()) + (bristle_ ? 2 : 0);
  }

  const DriveModel& model_;
  bool bristle_;
  int motor_states_ = 0;
  int motor_friction_loss_ = -1, gear_loss_ = -1;
  std::vector<int> positions_, velocities_;
};

}  // namespace leadscrew::model::drive
