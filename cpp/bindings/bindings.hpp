// One binding function per area; module.cpp calls them in order. Binding files
// hold no logic: argument conversion, GIL release and docstrings only.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "leadscrew/core/run_monitor.hpp"
#include "leadscrew/excitation/excitation.hpp"
#include "leadscrew/integrate/ode.hpp"
#include "leadscrew/integrate/simulation_result.hpp"

namespace leadscrew::bindings {


void bind_core(pybind11::module_& m);    // error types, the helper threads (wake, count)
void bind_thread(pybind11::module_& m);  // Thread and closed-form mechanics
void bind_lcp(pybind11::module_& m);     // LCP solvers (submodule "lcp")
void bind_excitation(pybind11::module_& m);
void bind_friction(pybind11::module_& m);  // the friction laws' registry
void bind_model(pybind11::module_& m);     // friction block, simulate, results
void bind_drive(pybind11::module_& m);     // lead-screw drive models

// Integrator options from the keyword arguments every simulate binding takes.
integrate::IntegratorOptions integrator_options(double rtol, double atol, long max_steps,
                                                double max_step, double first_step, int max_order);

// A simulation's counts as a dict (steps, rhs_evaluations, events, ...,
// wall_time), as Result.stats shows them.
pybind11::dict stats_dict(const integrate::SimulationStats& s);

// Converts a Python load description (an Excitation, a number, or a callable
// of t) into an Excitation; `name` goes into the error message.
Excitation to_excitation(pybind11::handle value, const std::string& name);
void bind_integrate(pybind11::module_& m);  // ODE integrators (submodule "integrate")

// The monitor of a simulation called from Python (core/run_monitor.hpp):
// every report checks for Ctrl-C (KeyboardInterrupt ends the run) and passes
// the simulated time to `progress` unless it is None. Made and destroyed
// with the GIL held; report() takes it.
class PythonMonitor final : public RunMonitor {
 public:
  explicit PythonMonitor(pybind11::object progress) : progress_(std::move(progress)) {}
  void report(double t) override;

 private:
  pybind11::object progress_;
};

}  // namespace leadscrew::bindings
