// The event-driven and Moreau-Jean drive systems' state vector y: the
// independent positions, their velocities, the elements' internal states
// (declaration.hpp) and the work and loss integrals. Internal to cpp/src/model (see
// docs/architecture.md); inline, as the right-hand side expands y at every call.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "declaration.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_dynamics.hpp"

namespace leadscrew::model::drive {

// The work and loss integrals, the last entries of y (StateLayout::energy_offset).
enum Energy { kWorkDrive = 0, kWorkAxial, kFrictionLoss, kDampingLoss, kContactLoss, kEnergyCount };

// Between the ODE state y = [independent positions, their velocities (not the
// speed-controlled rotor's), the elements' internal states, work and loss
// integrals] and full coordinates.
class StateLayout {
 public:
  // `law`: the friction law that runs on the thread, whose own states
  // (Law::state_names: LuGre's bristles) it declares (constrained_solver.cpp's
  // lugre_bristles kind). The elements' states follow the velocities, in the order of their declarations
  // (declaration.hpp: the registry's, element_registry.cpp), each
  // element's in the order it declared them; their channels are numbered
  // the same way (ChannelState::values).
  StateLayout(const DriveModel& model, const friction::Law& law)
      : model_(model), declarations_(declare_elements(model, law)) {
    const bool speed = model.parameters().speed_controlled;
    positions_ = model.independent();
    for (int i : positions_)
      if (!(speed && i == model.rotor())) velocities_.push_back(i);
    int state = static_cast<int>(positions_.size() + velocities_.size());
    int channel = 0;
    for (Declaration& d : declarations_) {
      d.first_state = state;
      // (-1 where it declares none: a declaration of a bound alone, as a
      // preloaded nut's flank_normal without lift-off, numbered as the next
      // element's first channel, had the nut write its preload into that
      // element's channel: a worm stage's gear_loss read the preload in
      // newtons as joules, failing energy_balance by exactly it.)
      d.first_channel = d.channels.empty() ? -1 : channel;
      state += static_cast<int>(d.states.size());
      channel += static_cast<int>(d.channels.size());
    }
    energy_offset_ = state;
    if (channel > kMaxElementChannels)
      throw std::logic_error("the drive's elements declare " + std::to_string(channel) +
                             " channels, more than kMaxElementChannels (declaration.hpp)");
  }
  int size() const { return energy_offset_ + kEnergyCount; }
  int energy_offset() const { return energy_offset_; }
  const DriveModel& model() const { return model_; }

  // The model's declarations (declaration.hpp), slots allocated.
  const std::vector<Declaration>& declarations() const { return declarations_; }
  // The slots of the model's elements' states (model/element.hpp), per
  // element: its first state in y and their count ({-1, 0}: none), for
  // DriveDynamics::set_element_slots.
  std::vector<std::pair<int, int>> element_slots() const {
    std::vector<std::pair<int, int>> slots(model_.elements().elements.size(), {-1, 0});
    for (const Declaration& d : declarations_)
      if (d.element >= 0)
        slots[static_cast<std::size_t>(d.element)] = {d.first_state,
                                                      static_cast<int>(d.states.size())};
    return slots;
  }
  // The declaration of registered kind `kind` (nullptr: the model has none).
  const Declaration* declaration(int kind) const {
    for (const Declaration& d : declarations_)
      if (d.kind == kind) return &d;
    return nullptr;
  }
  // A declared state's index in y, a declared channel's in
  // ChannelState::values, by name (-1: not declared). For the build of a
  // run's system only: its users keep the index.
  int find_state(const std::string& name) const {
    for (const Declaration& d : declarations_)
      for (std::size_t k = 0; k < d.states.size(); ++k)
        if (name == d.states[k]) return d.first_state + static_cast<int>(k);
    return -1;
  }
  int find_channel(const std::string& name) const {
    for (const Declaration& d : declarations_)
      for (std::size_t k = 0; k < d.channels.size(); ++k)
        if (name == d.channels[k].name) return d.first_channel + static_cast<int>(k);
    return -1;
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
  const DriveModel& model_;
  std::vector<Declaration> declarations_;
  int energy_offset_ = 0;
  std::vector<int> positions_, velocities_;
};

}  // namespace leadscrew::model::drive
