// A watcher of long runs on the calling thread: progress and interruption.
//
// The drivers and the solvers' callbacks call poll_monitor(t) with the
// simulated time they reached. Without a monitor installed on the thread
// that costs a thread-local load and a branch. With one, every 64th call
// reads the clock, and once per `interval` of wall time the monitor's
// report(t) runs: the Python binding shows progress there and checks for
// Ctrl-C, throwing to end the run (the exception leaves simulate() like any
// other failure, every resource released). A SUNDIALS callback that throws
// makes the solver return (sundials::CallbackBridge), so a run stops within
// one right-hand side of the report.
#pragma once

namespace leadscrew {

class RunMonitor {
 public:
  virtual ~RunMonitor() = default;
  // The simulated time reached [s]; may throw to stop the run.
  virtual void report(double t) = 0;
  // Wall time between reports [s].
  double interval = 0.1;
};

// Installs `monitor` for the runs on this thread while it lives (nested
// scopes restore the outer one).
class MonitorScope {
 public:
  explicit MonitorScope(RunMonitor* monitor) noexcept;
  ~MonitorScope();
  MonitorScope(const MonitorScope&) = delete;
  MonitorScope& operator=(const MonitorScope&) = delete;

 private:
  RunMonitor* previous_;
};

namespace detail {
struct MonitorState;
MonitorState* monitor_state() noexcept;
void poll_installed(MonitorState* state, double t);
}  // namespace detail

// Reports t to the thread's monitor when its interval has passed.
inline void poll_monitor(double t) {
  if (detail::MonitorState* state = detail::monitor_state()) detail::poll_installed(state, t);
}

}  // namespace leadscrew
