// One binding function per area; module.cpp calls them in order. Binding files
// hold no logic: argument conversion, GIL release and docstrings only.
#pragma once

#include <pybind11/pybind11.h>

namespace leadscrew::bindings {

void bind_core(pybind11::module_& m);    // error types
void bind_thread(pybind11::module_& m);  // Thread and closed-form mechanics
void bind_lcp(pybind11::module_& m);     // LCP solvers (submodule "lcp")
void bind_excitation(pybind11::module_& m);
void bind_simulate(pybind11::module_& m);
void bind_integrate(pybind11::module_& m);  // ODE integrators (submodule "integrate")

}  // namespace leadscrew::bindings
