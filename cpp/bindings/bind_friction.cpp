#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>

#include "bindings.hpp"
#include "leadscrew/friction/law.hpp"

namespace py = pybind11;

namespace leadscrew::bindings {

void bind_friction(py::module_& m) {
  m.def(
      "friction_laws",
      []() {
        py::list laws;
        for (const friction::LawType& type : friction::law_types()) {
          py::list parameters;
          for (const friction::ParameterInfo& p : type.parameters) {
            py::dict entry;
            entry["key"] = p.key;
            entry["unit"] = p.unit;
            entry["doc"] = p.doc;
            entry["default"] = std::isnan(p.default_value) ? py::object(py::none())
                                                           : py::object(py::float_(p.default_value));
            entry["default_from"] = p.default_from ? py::object(py::str(p.default_from))
                                                   : py::object(py::none());
            entry["low"] = p.low;
            entry["high"] = p.high;
            entry["low_open"] = p.low_open;
            entry["high_open"] = p.high_open;
            entry["at_least"] = p.at_least ? py::object(py::str(p.at_least))
                                           : py::object(py::none());
            parameters.append(entry);
          }
          py::dict law;
          law["name"] = type.name;
          law["doc"] = type.doc;
          law["parameters"] = parameters;
          law["time_stepping"] = type.time_stepping;
          law["ode"] = type.ode;
          laws.append(law);
        }
        return laws;
      },
      "The friction laws of the registry (cpp/src/friction/registry.cpp): per law its name, "
      "what it is, its parameters (key, unit, doc, default, default_from, range, at_least) and "
      "which integrators fit (time_stepping: Moreau-Jean; ode: the ODE methods).");
  m.def(
      "check_friction_law",
      [](const std::string& name, const friction::LawValues& values, const std::string& prefix) {
        friction::make_law(name, values, prefix);
      },
      py::arg("name"), py::arg("values"), py::arg("prefix") = "friction.",
      "Raises ValueError naming '<prefix><key>', the value and the range where the law "
      "`name` does not take `values` ((key, value) pairs): an unknown key, a missing required "
      "one, a value out of range or below the key it may not fall below (mu_static >= mu).");
}

}  // namespace leadscrew::bindings
