// Python access to the ODE integrators (submodule "integrate"): for tests and
// for users who want the core's integrators with a Python right-hand side.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/integrate/ode.hpp"

namespace py = pybind11;

namespace leadscrew::bindings {

namespace {
using integrate::Integrator;
using integrate::IntegratorOptions;
using integrate::IntegratorStats;
using integrate::OdeSystem;

// Glue: an OdeSystem whose f(t, y) and g(t, y) are Python callables. Slow by
// nature (a Python call per evaluation). Runs with the GIL held.
class PythonOdeSystem final : public OdeSystem {
 public:
  PythonOdeSystem(py::function fun, int size, py::object events, int root_count,
                  int quadrature_count)
      : fun_(std::move(fun)),
        events_(std::move(events)),
        size_(size),
        root_count_(root_count),
        quadrature_count_(quadrature_count) {
    if (size < 1)
      throw InvalidArgument("size = " + std::to_string(size) + " is invalid: must be >= 1");
    if (quadrature_count < 0 || quadrature_count >= size)
      throw InvalidArgument("quadrature_count = " + std::to_string(quadrature_count) +
                            " is invalid: must be in [0, size - 1] = [0, " +
                            std::to_string(size - 1) + "]");
    if (root_count < 0 || (root_count > 0 && events_.is_none()))
      throw InvalidArgument("root_count = " + std::to_string(root_count) +
                            " is invalid: must be >= 0, and 0 without an events callable");
  }
  int size() const override { return size_; }
  int root_count() const override { return root_count_; }
  int quadrature_count() const override { return quadrature_count_; }
  void rhs(double t, const double* y, double* ydot) override {
    copy_out(fun_(t, state(y)), size_, "fun(t, y)", ydot);
  }
  void roots(double t, const double* y, double* g) override {
    copy_out(events_(t, state(y)), root_count_, "events(t, y)", g);
  }

 private:
  py::array_t<double> state(const double* y) const {
    return py::array_t<double>(static_cast<py::ssize_t>(size_), y);  // a copy
  }
  static void copy_out(const py::object& result, int n, const char* what, double* out) {
    auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(result);
    if (!values || values.size() != n)
      throw InvalidArgument(std::string(what) + " returned " +
                            (values ? std::to_string(values.size()) : std::string("a non-array")) +
                            " values, invalid: must return " + std::to_string(n));
    const double* data = values.data();
    for (int i = 0; i < n; ++i) out[i] = data[i];
  }

  py::function fun_;
  py::object events_;
  int size_;
  int root_count_;
  int quadrature_count_;
};

// An integrator with the Python object of its system (kept alive: the
// integrator holds it by reference) and its output state.
struct BoundIntegrator {
  std::unique_ptr<Integrator> integrator;
  py::object system;
  Eigen::VectorXd state;
};

py::dict stats_dict(const IntegratorStats& s) {
  py::dict d;
  d["steps"] = s.steps;
  d["rhs_evaluations"] = s.rhs_evaluations;
  d["jacobian_evaluations"] = s.jacobian_evaluations;
  d["root_evaluations"] = s.root_evaluations;
  d["error_test_failures"] = s.error_test_failures;
  d["nonlinear_failures"] = s.nonlinear_failures;
  d["restarts"] = s.restarts;
  return d;
}

// The integrator made by make_integrator, driven from Python.
void bind_integrator_class(py::module_& sub) {
  py::class_<BoundIntegrator>(sub, "Integrator", R"doc(
An ODE integrator (make it with make_integrator).

initialize(system, t0, y0) allocates; reinitialize(t0, y0) restarts without
allocating; advance(t_out, one_step=False) integrates towards t_out, never
past it, stopping at the first root of the system's root functions, and
returns (t, root_found, y).
)doc")
      .def_property_readonly("name", [](const BoundIntegrator& self) { return self.integrator->name(); })
      .def(
          "initialize",
          [](BoundIntegrator& self, py::object system, double t0, const Eigen::VectorXd& y0) {
            OdeSystem& ode = system.cast<OdeSystem&>();
            self.integrator->initialize(ode, t0, y0);
            self.system = std::move(system);  // the integrator keeps it by reference
            self.state.resize(ode.size());
          },
          py::arg("system"), py::arg("t0"), py::arg("y0"))
      .def(
          "reinitialize",
          [](BoundIntegrator& self, double t0, const Eigen::VectorXd& y0) {
            self.integrator->reinitialize(t0, y0);
          },
          py::arg("t0"), py::arg("y0"))
      .def(
          "advance",
          [](BoundIntegrator& self, double t_out, bool one_step) {
            const integrate::AdvanceResult r =
                self.integrator->advance(t_out, self.state, one_step);
            return py::make_tuple(r.t, r.status == integrate::AdvanceStatus::root_found,
                                  Eigen::VectorXd(self.state));
          },
          py::arg("t_out"), py::arg("one_step") = false)
      .def(
          "advance_to_output",
          [](BoundIntegrator& self, double t_out, double t_stop) {
            const integrate::AdvanceResult r =
                self.integrator->advance_to_output(t_out, t_stop, self.state);
            return py::make_tuple(r.t, r.status == integrate::AdvanceStatus::root_found,
                                  Eigen::VectorXd(self.state));
          },
          py::arg("t_out"), py::arg("t_stop"),
          "Like advance, but steps may pass t_out (never t_stop >= t_out) when the method "
          "interpolates output (see interpolates_output); returns (t, root_found, y) with y "
          "at t_out from the interpolant.")
      .def_property_readonly(
          "interpolates_output",
          [](const BoundIntegrator& self) { return self.integrator->interpolates_output(); },
          "True if output times need not end steps (the interpolant has the steps' order).")
      .def(
          "dense_output",
          [](BoundIntegrator& self, double t) {
            self.integrator->dense_output(t, self.state);
            return Eigen::VectorXd(self.state);
          },
          py::arg("t"), "The state at t within the last internal step (dense output).")
      .def_property_readonly(
          "root_info", [](const BoundIntegrator& self) { return self.integrator->root_info(); },
          "per root function: +1 rising, -1 falling, 0 not triggered")
      .def_property_readonly("stats", [](const BoundIntegrator& self) {
        return stats_dict(self.integrator->stats());
      });
}

// make_integrator and the integrators' names.
void bind_make_integrator(py::module_& sub) {
  sub.def(
      "make_integrator",
      [](const std::string& method, double rtol, double atol, double max_step, double first_step,
         long max_steps, int max_order, double fixed_step) {
        IntegratorOptions options =
            integrator_options(rtol, atol, max_steps, max_step, first_step, max_order);
        options.fixed_step = fixed_step;
        return BoundIntegrator{integrate::make_integrator(method, options), py::none(), {}};
      },
      py::arg("method"), py::arg("rtol") = IntegratorOptions{}.rtol,
      py::arg("atol") = IntegratorOptions{}.atol, py::arg("max_step") = 0.0,
      py::arg("first_step") = 0.0, py::arg("max_steps") = IntegratorOptions{}.max_steps,
      py::arg("max_order") = 0, py::arg("fixed_step") = 0.0,
      "Make an integrator by name (see integrator_names). Raises ValueError for an unknown "
      "name or an invalid option.");
  sub.def("integrator_names", &integrate::integrator_names, "Names of the integrators.");
}

}  // namespace

void bind_integrate(py::module_& m) {
  py::module_ sub = m.def_submodule("integrate", "ODE integrators of the core");

  py::class_<OdeSystem>(sub, "OdeSystem", "An ODE y' = f(t, y) with root functions g(t, y).")
      .def_property_readonly("size", &OdeSystem::size)
      .def_property_readonly("root_count", &OdeSystem::root_count)
      .def_property_readonly("quadrature_count", &OdeSystem::quadrature_count);

  py::class_<PythonOdeSystem, OdeSystem>(sub, "PythonOdeSystem", R"doc(
ODE system from Python callables.

Args:
    fun: f(t, y) -> array of `size` values.
    size: number of states, >= 1.
    events: g(t, y) -> array of `root_count` values, or None.
    root_count: number of root functions, >= 0.
    quadrature_count: number of trailing states fun does not depend on
        (integrals of the others); CVODE leaves them out of its Newton
        matrix. 0 <= quadrature_count < size.
)doc")
      .def(py::init<py::function, int, py::object, int, int>(), py::arg("fun"), py::arg("size"),
           py::arg("events") = py::none(), py::arg("root_count") = 0,
           py::arg("quadrature_count") = 0);
  bind_integrator_class(sub);
  bind_make_integrator(sub);
}

}  // namespace leadscrew::bindings
