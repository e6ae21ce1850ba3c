// An element of the drive with events of its own in the event-driven driver
// (DriveHybrid): its root functions, what happens at them, its start at a
// (re)start of the run, its internal states' rates, its energy terms and its
// output values. Internal to cpp/src/model (docs/architecture.md, "An element
// with events").
//
// DriveHybrid holds a list of them, built once from the model in
// DriveHybrid::make_elements (hybrid_rhs.cpp) from the registry
// (element_registry.cpp, one line per kind), in its order; a model with none has an empty list and pays nothing, one with any
// never takes the rigid solver (mode_solver.cpp). Their root functions
// follow the driver's own g0..g4 (friction, flanks, the screw's end), each
// element's in one block (first_root), in the list's order. Each kind is a
// class derived from DriveHybrid::Element in a file of its own, with its
// declaration (declaration.hpp: its states in y, its channels):
//   model_element.cpp     a model's element behind model/element.hpp (the
//                         DC motor, the base excitation), through one adapter
//   hybrid_end_stops.cpp  the end stops, penalty and exact: their roots,
//                         impacts, closed contacts and force
//   hybrid_preloaded_nut.cpp  a lift-off preloaded nut's channels
// An element reads the driver's state through the protected accessors below
// (the coordinates and the dynamics at the state last set); its calls are
// virtual (a few per right-hand side, root or event) and allocate nothing
// in the right-hand side, the roots and the output rows.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "channels.hpp"
#include "hybrid.hpp"

namespace leadscrew::model::drive {

class DriveHybrid::Element {
 public:
  explicit Element(DriveHybrid& hybrid) : h_(hybrid) {}
  virtual ~Element() = default;
  Element(const Element&) = delete;
  Element& operator=(const Element&) = delete;

  // What an event of its roots did (handle).
  struct Event {
    std::string kind;          // its description ("" if nothing to report)
    bool decide_mode = false;  // the mechanical mode is decided anew (a force jumped)
  };

  // Its root functions: how many (fixed for the run), their values at the
  // state last set (g[0..root_count()), its own block) and the directions in
  // which they end its current state (0: both).
  virtual int root_count() const = 0;
  virtual void roots(double t, double* g) const = 0;
  virtual void root_directions(int* directions) const = 0;

  // At an event where one of its roots fired (root_info: its own block, as
  // integrate::HybridSystem's): its state changes, y may change (an impact,
  // a value snapped onto a limit). Elements are called in the list's order,
  // before the thread's mode; where none of the fired roots asks for the
  // mode to be decided anew (and no root of the thread's), the driver
  // returns the elements' descriptions at once.
  virtual Event handle(double t, double* y, const int* root_info) = 0;
  // After the mechanical mode changed at an event (an impact's jump of the
  // velocities may end its state at once).
  virtual void after_mode_change(double t, const double* y) {
    (void)t;
    (void)y;
  }

  // At a start of the run (select_initial_mode, after the thread's mode is
  // chosen): its state from the state last set. A resumed run (the stepper's
  // next piece, DriveHybrid::resume) starts its new elements the same way:
  // what they hold is decided anew from the state.
  virtual void start(double t, const double* y) {
    (void)t;
    (void)y;
  }

  // The right-hand side (ConstrainedSolver::rhs), after the mechanical part:
  // its internal states' rates, its terms of the work and loss integrals
  // (energy: StateLayout's), and what it holds (a closed stop's rates).
  virtual void rates(double t, const double* y, double* ydot, double* energy) const {
    (void)t;
    (void)y;
    (void)ydot;
    (void)energy;
  }
  // An output row: its declared channels' values (state.values from
  // first_channel(), in the order it declared them), at the thread's and
  // the motor's forces of the row.
  virtual void output(double t, const double* y, const ContactForces& forces,
                      ChannelState& state) const {
    (void)t;
    (void)y;
    (void)forces;
    (void)state;
  }
  // The driver opened the exact stop it holds the load at (no mode of the
  // rotor's friction contact has it push: hybrid_rotor_stops.cpp).
  virtual void release_hold() {}
  // Its forces depend on the loads alone (not on its own state): the
  // rigid drive's load-driven roots (hybrid_load_roots.cpp) may plan ahead.
  virtual bool forces_from_loads_alone() const { return true; }

  // Its first root's index in the driver's g, its first state's in y and
  // its first channel's in ChannelState::values (its declaration's,
  // declaration.hpp; -1: it declared none), set once by the driver.
  int first_root() const { return first_root_; }
  int first_state() const { return first_state_; }
  int first_channel() const { return first_channel_; }
  void set_slots(int root, int state, int channel) {
    first_root_ = root;
    first_state_ = state;
    first_channel_ = channel;
  }

 protected:
  // The driver's state, as last set (DriveHybrid::set or the mode solver's
  // expand).
  const DriveModel& model() const { return h_.model_; }
  const DriveDynamics& dynamics() const { return h_.dynamics_; }
  // The mode of the model's element k (model/element.hpp), the run's.
  ElementMode& dynamics_mode(std::size_t k) const { return h_.dynamics_.element_mode(k); }
  const StateLayout& layout() const { return h_.layout_; }
  // The thread's mode (contact, stick or slip, the slip's sign).
  const Mode& mode() const { return h_.mode_; }
  const CoordinateVector& q() const { return h_.q_; }
  const CoordinateVector& v() const { return h_.v_; }
  CoordinateVector& q() { return h_.q_; }
  CoordinateVector& v() { return h_.v_; }
  // Expands y at t into the coordinates and the dynamics' state.
  void set(double t, const double* y) { h_.set(t, y); }
  double bounce_threshold() const { return h_.bounce_threshold_; }
  // The impacts' loss booked so far [J] (an element's impact adds to it).
  double& impact_loss() { return h_.impact_loss_; }
  // A closed exact stop's held coordinate in every mode's solve (-1: none;
  // ModeSpec::held_load), and the current mode solved at the state set.
  void hold_load(int coordinate) { h_.held_load_ = coordinate; }
  ModeSolution solve_current() const { return h_.solve_current(); }
  // The mode's solve as its spec with the loads replaced (a unit impulse's
  // response: DriveDynamics::solve_with_forces).
  ModeSolution solve_with(const ModeSpec& spec, const CoordinateVector& forces) const {
    return h_.dynamics_.solve_with_forces(spec, forces);
  }
  ModeSpec spec(int sigma) const { return h_.spec(sigma); }
  double stick_mu() const { return h_.stick_mu(); }
  // The rotor's friction contact (nullptr: none), its mode, and whether a
  // mode fits an impulse's rotor speed change dw (hybrid_rotor_stops.cpp).
  const elements::TrainFriction* rotor_train() const { return h_.rotor_train_; }
  moreau_contacts::RotorMode& rotor_mode() { return h_.rotor_mode_; }
  bool rotor_impulse_consistent(const moreau_contacts::RotorMode& mode, double dw,
                                bool at_rest) const {
    return h_.rotor_impulse_consistent(mode, dw, at_rest);
  }
  // Dynamic jamming (the Painleve regime) at the state set: JammingError.
  [[noreturn]] void jam(const std::string& what) const { h_.jam(what); }

 private:
  DriveHybrid& h_;
  int first_root_ = 0, first_state_ = -1, first_channel_ = -1;
};

// A kind's factory (nullptr where the model has none of it), per registered
// kind in the registry's order (element_registry.cpp; nullptr: a kind
// without events).
using ElementFactory = std::unique_ptr<DriveHybrid::Element> (*)(DriveHybrid& hybrid,
                                                                 const DriveModel& model);
const std::vector<ElementFactory>& element_factories();

// The event-driven driver's element for the model's element (model/element.hpp)
// named `name` (nullptr: the model has none; model_element.cpp): its
// roots, events, rates and output through the element interface, its
// state and mode the dynamics' (DriveDynamics::element_state, element_mode).
std::unique_ptr<DriveHybrid::Element> make_model_element(DriveHybrid& hybrid,
                                                         const DriveModel& model,
                                                         const char* name);
// The same for the model's element `index` (DriveElements::elements).
std::unique_ptr<DriveHybrid::Element> make_model_element(DriveHybrid& hybrid,
                                                         const DriveModel& model,
                                                         std::size_t index);

}  // namespace leadscrew::model::drive
