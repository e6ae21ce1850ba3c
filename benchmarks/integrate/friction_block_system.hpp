// The benchmark problem: a block on a rough plane, spring-restrained and
// sine-forced, with Coulomb friction (equal static and kinetic coefficient),
// simulated event-driven: each stick/slip transition is a root, a mode change
// and a restart of the integrator.
#pragma once

#include <cmath>
#include <vector>

#include "leadscrew/integrate/ode.hpp"

namespace bench {

using leadscrew::integrate::AdvanceStatus;
using leadscrew::integrate::Integrator;
using leadscrew::integrate::OdeSystem;

constexpr double pi = 3.14159265358979323846;

// m x'' = F0 sin(W t) - k x - Fc sign(v) while slipping; at rest (stick)
// while |F0 sin(W t) - k x| <= Fc (equal static and kinetic friction).
struct FrictionBlock final : OdeSystem {
  double m = 1.0, k = 40.0, Fc = 0.3 * 9.81, F0 = 2.0 * 0.3 * 9.81, W = 2.0 * pi * 2.5;
  int mode = 0;  // 0 stick, +1 slipping forward, -1 backward
  int size() const override { return 2; }
  int root_count() const override { return 2; }
  double force(double t, double x) const { return F0 * std::sin(W * t) - k * x; }
  void rhs(double t, const double* y, double* ydot) override {
    if (mode == 0) {
      ydot[0] = 0.0;
      ydot[1] = 0.0;
    } else {
      ydot[0] = y[1];
      ydot[1] = (force(t, y[0]) - Fc * mode) / m;
    }
  }
  void roots(double t, const double* y, double* g) override {
    if (mode == 0) {
      const double f = force(t, y[0]);
      g[0] = f - Fc;  // breaks away forward
      g[1] = f + Fc;  // breaks away backward
    } else {
      g[0] = y[1];  // comes to rest (or reverses)
      g[1] = 1.0;
    }
  }
};

struct BlockRun {
  std::vector<double> events;
  double x_end = 0.0, v_end = 0.0;
};

constexpr int max_events = 1000;

// The event-driven simulation; the integrator is initialized already.
inline void simulate_block(Integrator& integrator, FrictionBlock& block, double t_end, BlockRun& run) {
  Eigen::Vector2d y(0.0, 0.0);
  block.mode = 0;
  integrator.reinitialize(0.0, y);
  run.events.clear();
  for (int i = 0; i < max_events; ++i) {
    const auto r = integrator.advance(t_end, y);
    if (r.status == AdvanceStatus::reached) break;
    run.events.push_back(r.t);
    if (block.mode == 0) {
      block.mode = integrator.root_info()[0] != 0 ? 1 : -1;
    } else {
      const double f = block.force(r.t, y[0]);
      block.mode = std::fabs(f) <= block.Fc ? 0 : (f > 0 ? 1 : -1);
    }
    y[1] = 0.0;
    integrator.reinitialize(r.t, y);
  }
  run.x_end = y[0];
  run.v_end = y[1];
}

}  // namespace bench
