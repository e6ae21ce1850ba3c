// A drive advanced piece by piece: created once, advanced to a time t with
// its inputs (drive torque or motor voltage, axial force) held constant over
// each piece (a prescribed speed ramps to its new value over the piece),
// read at the time it reached, and reset. It runs simulate()'s event-driven
// scheme (integrate::EventDrivenRun, the same driver and hybrid system):
// stick/slip, flank and screw-end events are located exactly inside a
// piece, and the complete state (positions, velocities, mode, stick state,
// LuGre's bristles, the work and loss integrals) is kept between pieces, so
// that N pieces cost about one run. The C API (leadscrew/leadscrew.h) and
// the co-simulation interface are built on it.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "leadscrew/integrate/simulation_result.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_simulation.hpp"

namespace leadscrew::integrate {
class EventDrivenRun;
}

namespace leadscrew::model {

class DriveStepper {
 public:
  // The drive of `parameters` at t = 0 (its initial section), run with
  // `options` (simulate()'s; output and check are not used: the stepper
  // keeps no rows). Every integrator simulate() takes for the drive but
  // Moreau-Jean's time stepping. Until an input is set, the loads are the
  // parameters' own time functions. InvalidArgument for a bad parameter or
  // option (the model's and simulate()'s checks).
  DriveStepper(DriveParameters parameters, DriveSimulationOptions options);
  ~DriveStepper();
  DriveStepper(const DriveStepper&) = delete;
  DriveStepper& operator=(const DriveStepper&) = delete;

  // The names set_input takes: the drive's input ("drive_torque" of a
  // torque-controlled drive, "drive_speed" of a speed-controlled one,
  // "motor_voltage" of a DC motor) and "axial_force".
  const std::vector<std::string>& input_names() const;
  // Sets the input `name` to `value` (SI) from time() on, until it is set
  // again or reset(). A torque, a voltage and the axial force are held
  // constant. A prescribed speed is not stepped (a step is an infinite
  // acceleration): it ramps linearly from the speed at time() to `value`
  // over the next advance, reaching it at that advance's end, and is held
  // after (the channels at the advance's end are the ramp's: its
  // acceleration, the left limit); set before the first advance, it is the
  // speed the drive starts at. InvalidArgument for an unknown name (listing
  // the names) and a non-finite value.
  void set_input(const std::string& name, double value);
  // The input's value at time() (the held one, the speed a ramp heads for,
  // or the parameters' load).
  double input(const std::string& name) const;

  // Advances to t (>= time(); t == time() does nothing). Throws
  // InvalidArgument for t < time() or a non-finite t; SimulationError where
  // the run fails (the nut reaches the screw's end: the message says so; a
  // solver failure; max_steps), JammingError where the drive jams. After a
  // failure the stepper stays at the failure's time and refuses to advance
  // (SimulationError naming the first failure) until reset().
  void advance(double t);
  double time() const noexcept;

  // The result channels of simulate() at time(), by name (InvalidArgument
  // for an unknown name, listing the names), or all in channel_names()' order.
  const std::vector<std::string>& channel_names() const;
  double channel(const std::string& name);
  std::vector<double> channels();

  // The events so far, and the integrator's and the LCP's counts.
  const std::vector<integrate::Event>& events() const;
  integrate::SimulationStats stats() const;

  // Back to t = 0: the initial state, the parameters' loads, no failure.
  void reset();

 private:
  struct System;
  std::unique_ptr<System> make_system() const;
  // Continues the run from time() under current_'s loads (after an input
  // changed them).
  void restart_with_current_loads();
  Excitation& load_of(const std::string& name);

  DriveParameters parameters_;  // as given
  // An element's inputs in place of the drive's (a DC motor's voltage;
  // element_section.hpp, RotorDrive), with "axial_force"; empty: none.
  std::vector<std::string> element_inputs_;
  DriveParameters current_;     // with the inputs held since
  DriveSimulationOptions options_;
  std::string integrator_;
  std::unique_ptr<System> system_;
  std::unique_ptr<integrate::EventDrivenRun> run_;
  integrate::SimulationResult record_;  // events (no rows)
  std::string failure_;
  double failure_time_ = 0.0;
  std::vector<double> row_;
  bool speed_pending_ = false;  // set_input("drive_speed") waits for the next advance
  double speed_target_ = 0.0;   // [rad/s]
  // The last speed ramp ends at ramp_end_ at ramp_target_ (inf: none runs).
  double ramp_end_ = std::numeric_limits<double>::infinity();
  double ramp_target_ = 0.0;
  bool advanced_ = false;  // an advance went past t = 0 since the start
  void start_run();        // the run from t = 0 under current_'s loads
};

}  // namespace leadscrew::model
