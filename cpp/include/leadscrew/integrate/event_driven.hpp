// Event-driven integration of piecewise-smooth (hybrid) systems, the scheme of
// exact Coulomb friction (Pfeiffer & Glocker): in each discrete mode (stick,
// slip+, slip-, contact open/closed, ...) a smooth ODE is integrated to the
// requested tolerance by one of the ODE integrators; root functions signal
// that the mode must change; at the root the system chooses the new mode (by
// an LCP) and may project or jump the state (impacts); the integrator
// restarts there, so no step straddles a discontinuity and no order is lost.
//
// A system with a single mode and no roots is simply integrated: the
// regularized and compliant models use the same driver.
#pragma once

#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "leadscrew/integrate/ode.hpp"
#include "leadscrew/integrate/simulation_result.hpp"

namespace leadscrew::integrate {

class HybridSystem : public OdeSystem {
 public:
  // Chooses the mode consistent with (t, y) from scratch, at the start.
  virtual void select_initial_mode(double t, double* y) = 0;
  // Called at a root (root_info as Integrator::root_info). Chooses the new
  // mode, may change y (projection, impact). Returns the event's kind, or ""
  // if nothing changed (a spurious root: the integrator just continues).
  virtual std::string handle_event(double t, double* y, const std::vector<int>& root_info) = 0;
  // Which crossings of each root function end the current mode: +1 rising
  // only, -1 falling only, 0 both. A root found in the other direction is no
  // event and integration simply continues. (A slip that starts from rest has
  // zero slip acceleration at its start, so its slip velocity leaves zero
  // quadratically and round-off can show a crossing back: direction decides.)
  virtual void root_directions(int* directions) const {
    for (int i = 0; i < root_count(); ++i) directions[i] = 0;
  }
  // Output channels.
  virtual const std::vector<std::string>& channel_names() const = 0;
  virtual void channels(double t, const double* y, double* out) = 0;
  // Times at which the right-hand side is not smooth (load table knots): the
  // integrator restarts there.
  virtual std::vector<double> breakpoints() const { return {}; }
  virtual long lcp_solves() const { return 0; }
  virtual long nonlinear_iterations() const { return 0; }
  // Largest step that resolves the root functions (0: no limit). In a stick
  // phase the state does not change, so nothing but this keeps an
  // integrator from stepping over two sign changes of a load-driven root.
  virtual double max_step_hint() const { return 0.0; }
};

// A step bound from the time scales of the loads driving a system:
// 1/kStepsPerLoadPeriod of the shortest one (0: no bound).
double max_step_from_time_scales(std::initializer_list<double> time_scales);
constexpr double kStepsPerLoadPeriod = 16.0;

struct EventDrivenOptions {
  std::string integrator = "cvode_adams";
  IntegratorOptions integrator_options;
  // Bound on the number of events: a Zeno-like accumulation of events raises
  // SimulationError instead of hanging.
  long max_events = 100000;
};

// The event-driven scheme as a run that can be advanced piece by piece:
// simulate_event_driven is one run advanced to its end, and a stepper
// (model/drive_stepper.hpp) advances one run in as many pieces as it is
// asked for, keeping the integrator, the system's mode and the state
// between them. `system` outlives the run (or is replaced by restart()).
class EventDrivenRun {
 public:
  // Chooses the system's initial mode at (t0, y0) and initializes the ODE method.
  EventDrivenRun(HybridSystem& system, double t0, const Eigen::Ref<const Eigen::VectorXd>& y0,
                 const EventDrivenOptions& options);
  ~EventDrivenRun();
  EventDrivenRun(const EventDrivenRun&) = delete;
  EventDrivenRun& operator=(const EventDrivenRun&) = delete;

  // Integrates from time() to output.t_end (> time()), locating every event
  // inside, and appends to `result` its output rows in (time(), t_end]
  // (output.t_eval: those times; empty: every step and event) and its
  // events; the first call also the row at the start. Throws
  // SimulationError as the scheme fails (the run cannot go on after it).
  void advance(const OutputRequest& output, SimulationResult& result);
  // The state changed discontinuously at time() (the loads changed): the
  // ODE method restarts there on `system` (the same or a new one, whose
  // mode the caller has chosen), keeping its step-size history and counts.
  void restart(HybridSystem& system);

  double time() const noexcept { return t_; }
  const Eigen::VectorXd& state() const noexcept { return y_; }
  // The state to change before restart() (a system's new mode may project it).
  Eigen::VectorXd& state() noexcept { return y_; }
  long events() const noexcept { return events_; }
  // The integrator's and the system's counts so far, in result.stats
  // (wall_time left as it is).
  void fill_stats(SimulationResult& result) const;

 private:
  class Guard;
  void attach(HybridSystem& system);
  bool counts_as_event(const std::vector<int>& info);
  void handle_root(SimulationResult& result);

  HybridSystem* system_;
  EventDrivenOptions options_;
  std::unique_ptr<Integrator> integrator_;
  std::unique_ptr<Guard> guard_;
  Eigen::VectorXd y_;
  double t_;
  long events_ = 0;
  bool started_ = false;
  std::vector<int> directions_;
  // The counts of the integrations before a restart on another system.
  IntegratorStats carried_;
  long carried_lcp_solves_ = 0, carried_iterations_ = 0;
};

SimulationResult simulate_event_driven(HybridSystem& system, double t0,
                                       const Eigen::Ref<const Eigen::VectorXd>& y0,
                                       const OutputRequest& output,
                                       const EventDrivenOptions& options);

}  // namespace leadscrew::integrate
