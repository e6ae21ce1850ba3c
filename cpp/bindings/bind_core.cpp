#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/parallel.hpp"

namespace py = pybind11;

namespace leadscrew::bindings {

namespace {
// Exception types live as long as the interpreter; they are deliberately never
// released (no static destructor runs after Python has finalized).
PyObject* simulation_error_type = nullptr;
PyObject* jamming_error_type = nullptr;
PyObject* nut_off_screw_error_type = nullptr;
PyObject* no_equilibrium_error_type = nullptr;

void raise_with_attributes(PyObject* type, const SimulationError& e) {
  py::object error = py::handle(type)(e.what());
  error.attr("time") = e.time();
  error.attr("reason") = e.reason();
  PyErr_SetObject(type, error.ptr());
}
}  // namespace

void PythonMonitor::report(double t) {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  if (!progress_.is_none()) progress_(t);
}

void bind_core(py::module_& m) {
  // SimulationError derives from RuntimeError; JammingError and NutOffScrewError
  // from SimulationError.
  simulation_error_type = PyErr_NewException("leadscrew._core.SimulationError",
                                             PyExc_RuntimeError, nullptr);
  jamming_error_type =
      PyErr_NewException("leadscrew._core.JammingError", simulation_error_type, nullptr);
  m.add_object("SimulationError", py::handle(simulation_error_type));
  m.add_object("JammingError", py::handle(jamming_error_type));
  nut_off_screw_error_type = PyErr_NewException("leadscrew._core.NutOffScrewError",
                                                simulation_error_type, nullptr);
  m.add_object("NutOffScrewError", py::handle(nut_off_screw_error_type));
  // NoEquilibriumError derives from ValueError: the start asked for does not exist.
  no_equilibrium_error_type = PyErr_NewException("leadscrew._core.NoEquilibriumError",
                                                 PyExc_ValueError, nullptr);
  m.add_object("NoEquilibriumError", py::handle(no_equilibrium_error_type));
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const NoEquilibrium& e) {
      PyErr_SetString(no_equilibrium_error_type, e.what());
    } catch (const JammingError& e) {
      raise_with_attributes(jamming_error_type, e);
    } catch (const NutOffScrew& e) {
      raise_with_attributes(nut_off_screw_error_type, e);
    } catch (const SimulationError& e) {
      raise_with_attributes(simulation_error_type, e);
    }
  });
  m.def("pooled_helper_count", &pooled_helper_count,
        "Helper threads the process's pool has started so far (the batch's workers\n"
        "beyond the calling thread; asleep between calls).");
}

}  // namespace leadscrew::bindings
