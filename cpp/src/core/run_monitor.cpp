#include "leadscrew/core/run_monitor.hpp"

#include <chrono>

namespace leadscrew {

namespace detail {

struct MonitorState {
  RunMonitor* monitor = nullptr;
  unsigned calls = 0;
  std::chrono::steady_clock::time_point next_report;
};

namespace {
thread_local MonitorState state;
thread_local MonitorState* installed = nullptr;
}  // namespace

MonitorState* monitor_state() noexcept { return installed; }

void poll_installed(MonitorState* s, double t) {
  // The clock costs some 20 ns: read it every 64th call only.
  if ((++s->calls & 63u) != 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (now < s->next_report) return;
  s->next_report = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                             std::chrono::duration<double>(s->monitor->interval));
  s->monitor->report(t);
}

}  // namespace detail

MonitorScope::MonitorScope(RunMonitor* monitor) noexcept
    : previous_(detail::installed ? detail::installed->monitor : nullptr) {
  detail::state.monitor = monitor;
  detail::state.calls = 0;
  detail::state.next_report = std::chrono::steady_clock::now() +
                              std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                  std::chrono::duration<double>(monitor ? monitor->interval : 0.0));
  detail::installed = monitor ? &detail::state : nullptr;
}

MonitorScope::~MonitorScope() {
  detail::state.monitor = previous_;
  detail::installed = previous_ ? &detail::state : nullptr;
}

}  // namespace leadscrew
