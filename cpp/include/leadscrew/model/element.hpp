// An element of the drive with a state, an event or a part in the
// Moreau-Jean step (Drake's ForceElement, MuJoCo's plugins): what it
// declares and computes, behind one interface, so that the plant
// (DriveDynamics) and the solvers (the event-driven DriveHybrid, the
// Moreau-Jean DriveMoreau) never name it. docs/architecture.md, "An element
// is one file".
//
// An Element is part of the immutable DriveModel (built from its scene
// section, element_section.hpp, by its section's `build`); what changes
// within a run, its discrete mode (a current limiter's, a brake's fade) and
// what its last Moreau-Jean step left (ElementMode), is kept by the run in
// DriveDynamics (Pinocchio's Data), with its internal states, which live in
// the run's state vector y (its declaration's `states`).
//
// An element sees the drive at an ElementState: the time, the full
// coordinates and velocities, its own states. It
//   declares   its states in y (and their values at the run's start,
//              initial_states), its result channels with their unit and
//              their role in the energy account (work, stored, loss), its
//              terms of the result checks' bounds (drive/declaration.hpp);
//   acts       by generalized forces on the coordinates (add_forces), a
//              function of the state and its mode; a motor's on the rotor
//              is the drive's torque (drives_rotor);
//   evolves    by the rates of its states and its terms of the account's
//              work and loss integrals (rates);
//   switches   at its roots (root_count, roots, root_directions; handle,
//              start, after_mode_change) in the event-driven scheme;
//   steps      in Moreau-Jean by its impulse over the step, affine in the
//              step's end velocities, impulse = constant + slope . v+ on each
//              coordinate (step_impulse: the constant enters the step's
//              right-hand side, -slope the iteration matrix's diagonal), and
//              its states' and the account's update at the step's end
//              (step_end); where the step left its mode's domain (a current
//              beyond a limit), step_mode changes the mode and the step is
//              taken again;
//   reports    its channels' values at an output row (output) and its
//              stored energy (stored_energy);
//   checks     its own physics on a returned result (check_result).
// The calls are virtual: a few per right-hand side, root, output row or
// step, none per scalar; a model without such elements pays nothing.
#pragma once

#include <string>
#include <vector>

namespace leadscrew::integrate {
struct SimulationResult;
}

namespace leadscrew::model {

namespace drive {
struct Declaration;
}
struct DriveSimulationOptions;

// The drive's state as an element sees it.
struct ElementState {
  double t = 0.0;
  const double* q = nullptr;    // the full coordinates
  const double* v = nullptr;    // their velocities
  const double* own = nullptr;  // its declared states (y's, in its order)
};

// An element's discrete mode within a run and what its last Moreau-Jean
// step left for the output row (its meaning is the element's own).
struct ElementMode {
  int mode = 0;
  int side = 0;
  double last[2] = {0.0, 0.0};
};

// What an event of an element's roots did.
struct ElementEvent {
  std::string kind;          // its description ("" if nothing to report)
  bool decide_mode = false;  // the thread's mode is decided anew (a force jumped)
};

// Moreau-Jean's view of a step from t to t + h: its start (the positions,
// velocities and own states at t) at the time its forces take, t + theta
// h; its length h and theta.
struct ElementStep {
  ElementState start;
  double h = 0.0, theta = 1.0;
};

class Element {
 public:
  virtual ~Element() = default;

  // Its name (the registry's, element_registry.cpp: its kind).
  virtual const char* name() const = 0;
  // Its states in y, channels and terms of the checks (drive/declaration.hpp).
  virtual void declare(drive::Declaration& declaration) const = 0;

  // Its states at the run's start, written into `own` (its block of y,
  // zeros before: a state it leaves alone starts at 0). `s`: the start's
  // time, coordinates and velocities (s.own: zeros). at_equilibrium: the run
  // starts at rest in static equilibrium (initial.state = "equilibrium"):
  // its states are the steady ones at rest, which its forces then hold the
  // drive with (the equilibrium's solve asks before it knows s.q: they may
  // depend on s.t and s.v alone); else the relaxed start (a DC motor's
  // driver switched on at t = 0: its current 0).
  virtual void initial_states(const ElementState& s, bool at_equilibrium, double* own) const {
    (void)s, (void)at_equilibrium, (void)own;
  }

  // Adds its generalized forces at the state to `forces` (one per coordinate).
  virtual void add_forces(const ElementState& s, const ElementMode& mode, double* forces) const {
    (void)s, (void)mode, (void)forces;
  }
  // Its force on the rotor is the drive's torque (a motor's: drive_torque).
  virtual bool drives_rotor() const { return false; }
  // Its forces depend on the loads alone, not on its states or the drive's
  // (the rigid drive's load-driven roots may plan ahead).
  virtual bool forces_from_loads_alone() const { return true; }

  // The rates of its states (own_rates: its block of y') and its terms of
  // the account's integrals (energy: drive/state_layout.hpp's Energy; a
  // motor books the drive's work, kWorkDrive, in place of its torque's).
  virtual void rates(const ElementState& s, const ElementMode& mode, double* own_rates,
                     double* energy) const {
    (void)s, (void)mode, (void)own_rates, (void)energy;
  }
  // Its channels' values at an output row, in the order it declared them.
  virtual void output(const ElementState& s, const ElementMode& mode, double* values) const {
    (void)s, (void)mode, (void)values;
  }
  // What a step's energy balance takes from it at a state [J]: its stored
  // energy plus the loss integrals among its states minus the work
  // integrals among them (a DC motor's L i^2 / 2 + copper loss).
  virtual double energy_terms(const ElementState& s) const {
    (void)s;
    return 0.0;
  }

  // The event-driven scheme: its roots (a fixed count), their values and
  // the directions that end its mode (0: both).
  virtual int root_count() const { return 0; }
  virtual void roots(const ElementState& s, const ElementMode& mode, double* g) const {
    (void)s, (void)mode, (void)g;
  }
  virtual void root_directions(int* directions) const { (void)directions; }
  // At one of its roots: its mode changes, and its own states may (own:
  // writable, y's; the driver expands y anew afterwards).
  virtual ElementEvent handle(const ElementState& s, ElementMode& mode, double* own) const {
    (void)s, (void)mode, (void)own;
    return {};
  }
  // At a (re)start of a run: its mode from the state.
  virtual void start(const ElementState& s, ElementMode& mode) const { (void)s, (void)mode; }
  // After the thread's mode changed at an event (an impact's jump).
  virtual void after_mode_change(const ElementState& s, ElementMode& mode) const {
    (void)s, (void)mode;
  }

  // Moreau-Jean. A step is taken first in the mode step_first gives (from
  // the mode the last step left).
  virtual ElementMode step_first(const ElementMode& mode) const { return mode; }
  // Its impulse over the step beyond h times its force at the step's start
  // (add_forces at t + theta h, which the step's right-hand side has), affine
  // in the step's end velocities v+: constant + slope . v+ per coordinate
  // (added to; -slope joins the
  // iteration matrix's diagonal).
  virtual void step_impulse(const ElementStep& step, const ElementMode& mode, double* constant,
                            double* slope) const {
    (void)step, (void)mode, (void)constant, (void)slope;
  }
  // Its whole impulse on the rotor over the step at v+ = 0 (the rotor's
  // friction contact balances it: a motor's): h times the mean torque.
  virtual double step_rotor_impulse(const ElementStep& step, const ElementMode& mode) const {
    (void)step, (void)mode;
    return 0.0;
  }
  // At the step's end positions q_next and velocities v_next: its states'
  // new values (own_next,
  // from step.start.own), its terms of the account's integrals (energy,
  // added to) and what its output row reports (mode.last).
  virtual void step_end(const ElementStep& step, const double* q_next, const double* v_next,
                        ElementMode& mode, double* own_next, double* energy) const {
    (void)step, (void)q_next, (void)v_next, (void)mode, (void)own_next, (void)energy;
  }
  // After step_end in mode `taken`: true where the step left that mode's
  // domain (a current beyond its limit); `retake` is then the mode to take
  // the step again in (at most kMaxStepRetakes times).
  virtual bool step_mode(const ElementStep& step, const ElementMode& taken,
                         ElementMode& retake) const {
    (void)step, (void)taken, (void)retake;
    return false;
  }
  // Its mode at a Moreau-Jean run's start.
  virtual void step_start(const ElementState& s, ElementMode& mode) const { start(s, mode); }
  // Its channels' values at an output row of Moreau-Jean (default: output).
  virtual void step_output(const ElementState& s, const ElementMode& mode, double* values) const {
    output(s, mode, values);
  }
  // Its torque on the rotor that a Moreau-Jean row's drive_torque reports
  // (a motor's, drives_rotor).
  virtual double step_drive_torque(const ElementState& s, const ElementMode& mode) const {
    (void)s, (void)mode;
    return 0.0;
  }

  // Its checks of a returned result, appended to result.checks
  // (time_stepping: Moreau-Jean's rows, at theta).
  virtual void check_result(const DriveSimulationOptions& options, bool time_stepping,
                            integrate::SimulationResult& result) const {
    (void)options, (void)time_stepping, (void)result;
  }
};

// The most times a Moreau-Jean step is taken again for its elements' modes.
constexpr int kMaxStepRetakes = 4;
// The most internal states the elements of a model declare together.
constexpr int kMaxElementStates = 16;

}  // namespace leadscrew::model
