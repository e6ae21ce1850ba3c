// Error types of the numerical core.
//
// The bindings translate them into Python exceptions:
//   std::invalid_argument (and InvalidArgument) -> ValueError
//   NoEquilibrium                             -> leadscrew.NoEquilibriumError (a ValueError)
//   SimulationError                           -> leadscrew.SimulationError
//   JammingError                              -> leadscrew.JammingError (a SimulationError)
//   NutOffScrew                               -> leadscrew.NutOffScrewError (a SimulationError)
#pragma once

#include <stdexcept>
#include <string>

namespace leadscrew {

// Bad input: the message names the parameter (or key path), the value and the
// valid range.
class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A start in static equilibrium that the loads do not admit: at t = 0 the
// thread cannot hold them at rest (the friction force it would need lies
// outside the friction cone). The message says which forces and why.
class NoEquilibrium : public InvalidArgument {
 public:
  using InvalidArgument::InvalidArgument;
};

// A solver failed during a simulation: the time it got to and the reason.
class SimulationError : public std::runtime_error {
 public:
  SimulationError(double time, const std::string& reason, const std::string& hint = "")
      : std::runtime_error(compose(time, reason, hint)), time_(time), reason_(reason) {}
  double time() const noexcept { return time_; }
  const std::string& reason() const noexcept { return reason_; }

 private:
  static std::string compose(double time, const std::string& reason, const std::string& hint);
  double time_;
  std::string reason_;
};

// What a right-hand side refuses of the state it was given (OutsideDomain,
// JammingAtState). Thrown there, the state may be a trial state of a step
// that overshot (a stage of an explicit step, an implicit method's predictor
// or Newton iterate), not the trajectory's: every integrator retries with a
// smaller step, as for a non-finite right-hand side, and raises the error
// only where shorter steps meet it too. A marker: the errors are
// SimulationErrors through their other base.
class RefusedState {
 public:
  virtual ~RefusedState() = default;
};

// A state outside the model's domain (the nut off the screw); a refused
// state (above) where a right-hand side throws it.
class OutsideDomain : public SimulationError, public RefusedState {
 public:
  using SimulationError::SimulationError;
};

// The nut ran off the screw: its end reached the screw's end (a drive's
// domain ends there: beyond it the thread no longer holds the nut). Thrown
// at the located event, or by a right-hand side at a trial state (an
// OutsideDomain: retried, and raised only where the integrator gives up
// there). leadscrew.NutOffScrewError, so that a caller (a study driving to
// the end of the travel) tells it from a solver's failure without reading
// the message.
class NutOffScrew : public OutsideDomain {
 public:
  using OutsideDomain::OutsideDomain;
};

// A self-locking drive that jams dynamically: no consistent flank-contact mode
// exists (Painleve paradox). Never continued with a trajectory.
class JammingError : public SimulationError {
 public:
  using SimulationError::SimulationError;
};

// No consistent flank-contact mode at the state the drive was given (the
// normal force's sign): a JammingError, and a refused state (above) where a
// right-hand side meets it, so that an integrator's trial state (a stage of
// a step too long, far off the trajectory) does not end the run. A fuzz
// run's flexible LuGre drive "jammed" at rk_dopri5's first trial stage,
// velocities of 6.8e4, where every other integrator answered.
class JammingAtState : public JammingError, public RefusedState {
 public:
  using JammingError::JammingError;
};

}  // namespace leadscrew
