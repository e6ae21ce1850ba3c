#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "leadscrew/core/errors.hpp"

namespace py = pybind11;

namespace leadscrew::bindings {

namespace {

// A Python function of t, called with the GIL held (simulations release it).
// The py::function is destroyed under the GIL as well.
CallableExcitation wrap_python_callable(py::function function) {
  auto holder = std::shared_ptr<py::function>(new py::function(std::move(function)),
                                              [](py::function* f) {
                                                py::gil_scoped_acquire gil;
                                                delete f;
                                              });
  CallableExcitation callable;
  callable.description = "callable " + py::repr(*holder).cast<std::string>();
  callable.function = [holder](double t) {
    py::gil_scoped_acquire gil;
    return (*holder)(t).cast<double>();
  };
  return callable;
}

}  // namespace

Excitation to_excitation(py::handle value, const std::string& name) {
  if (py::isinstance<Excitation>(value)) return value.cast<Excitation>();
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
    try {
      return Excitation(ConstantExcitation{value.cast<double>()});
    } catch (const InvalidArgument&) {
      throw InvalidArgument(name + " = " + py::repr(value).cast<std::string>() +
                            " is invalid: must be finite");
    }
  }
  if (PyCallable_Check(value.ptr()))
    return Excitation(wrap_python_callable(py::reinterpret_borrow<py::function>(value)));
  throw InvalidArgument(name + " = " + py::repr(value).cast<std::string>() +
                        " is invalid: must be a number, a Constant, Sine, Table, "
                        "RandomVibration or Measured, or a callable f(t)");
}

void bind_excitation(py::module_& m) {
  py::class_<Excitation>(m, "Excitation", "A load as a function of time (C++ core).")
      .def(py::init(&Excitation::from_kind),
           py::arg("kind"), py::arg("parameters") = std::vector<double>{},
           py::arg("times") = std::vector<double>{}, py::arg("values") = std::vector<double>{})
      .def("__call__", [](const Excitation& e, double t) { return e(t); }, py::arg("t"))
      .def("__call__",
           [](const Excitation& e, py::array_t<double, py::array::c_style | py::array::forcecast> t) {
             py::array_t<double> out(t.request().shape);
             double* values = out.mutable_data();
             const double* times = t.data();
             for (py::ssize_t k = 0; k < t.size(); ++k) values[k] = e(times[k]);
             return out;
           },
           py::arg("t"))
      .def_property_readonly("breakpoints", &Excitation::breakpoints)
      .def_property_readonly("target_rms", &Excitation::target_rms,
                             "A random vibration's sqrt(integral of its PSD); 0 otherwise.")
      .def("describe", &Excitation::describe);
}

}  // namespace leadscrew::bindings
