#include <array>
#include <map>
#include <optional>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "leadscrew/integrate/simulation_result.hpp"
#include "leadscrew/model/friction_block.hpp"

namespace py = pybind11;

namespace leadscrew::bindings {

py::dict stats_dict(const integrate::SimulationStats& s) {
  // The keys are made once (and never freed, so that nothing touches Python
  // at exit): a short simulation takes a few microseconds, and creating ten
  // key strings per call was a tenth of that.
  static const auto* keys = new std::array<py::str, 10>{
      py::str("steps"),        py::str("rhs_evaluations"),      py::str("events"),
      py::str("lcp_solves"),   py::str("restarts"),             py::str("nonlinear_iterations"),
      py::str("jacobian_evaluations"), py::str("error_test_failures"),
      py::str("nonlinear_failures"),   py::str("wall_time")};
  const long counts[9] = {s.steps,        s.rhs_evaluations,      s.events,
                          s.lcp_solves,   s.restarts,             s.nonlinear_iterations,
                          s.jacobian_evaluations, s.error_test_failures, s.nonlinear_failures};
  py::dict d;
  for (std::size_t i = 0; i < 9; ++i) d[(*keys)[i]] = py::int_(counts[i]);
  d[(*keys)[9]] = py::float_(s.wall_time);
  return d;
}

namespace {

// channels as one (n_channels, n_points) array
py::array_t<double> channel_matrix(const integrate::SimulationResult& r) {
  const py::ssize_t rows = static_cast<py::ssize_t>(r.channel_count());
  const py::ssize_t cols = static_cast<py::ssize_t>(r.point_count());
  py::array_t<double> out({rows, cols});
  double* data = out.mutable_data();
  for (py::ssize_t k = 0; k < rows; ++k)
    r.copy_channel(static_cast<std::size_t>(k), data + k * cols);
  return out;
}

}  // namespace

integrate::IntegratorOptions integrator_options(double rtol, double atol, long max_steps,
                                                double max_step, double first_step, int max_order) {
  integrate::IntegratorOptions options;
  options.rtol = rtol;
  options.atol = atol;
  options.max_steps = max_steps;
  options.max_step = max_step;
  options.first_step = first_step;
  options.max_order = max_order;
  return options;
}

namespace {

// The friction block and its integrators (model/friction_block.hpp).
void bind_friction_block(py::module_& m) {
  py::class_<model::FrictionBlock>(m, "FrictionBlock")
      .def(py::init([](double mass, double mu, double g, py::handle force, double u0, double v0,
                       std::optional<double> mu_static, double stiffness, double pull_speed,
                       py::handle transverse_velocity) {
             std::optional<Excitation> transverse;
             if (!transverse_velocity.is_none())
               transverse = to_excitation(transverse_velocity, "transverse_velocity");
             return model::FrictionBlock(mass, mu, g, to_excitation(force, "force"), u0, v0,
                                         mu_static ? *mu_static : -1.0, stiffness, pull_speed,
                                         std::move(transverse));
           }),
           py::arg("mass"), py::arg("mu"), py::arg("g") = 9.81, py::arg("force") = 0.0,
           py::arg("initial_position") = 0.0, py::arg("initial_velocity") = 0.0,
           py::arg("mu_static") = py::none(), py::arg("stiffness") = 0.0,
           py::arg("pull_speed") = 0.0, py::arg("transverse_velocity") = py::none())
      .def_readonly("mass", &model::FrictionBlock::mass)
      .def_readonly("mu", &model::FrictionBlock::mu)
      .def_readonly("g", &model::FrictionBlock::g)
      .def_readonly("force", &model::FrictionBlock::force)
      .def_readonly("initial_position", &model::FrictionBlock::initial_position)
      .def_readonly("initial_velocity", &model::FrictionBlock::initial_velocity)
      .def_readonly("mu_static", &model::FrictionBlock::mu_static)
      .def_readonly("stiffness", &model::FrictionBlock::stiffness)
      .def_readonly("pull_speed", &model::FrictionBlock::pull_speed)
      .def_readonly("transverse_velocity", &model::FrictionBlock::transverse_velocity)
      .def_property_readonly("normal_force", &model::FrictionBlock::normal_force);

  m.def("block_integrators", [](const std::string& friction) {
    return model::integrators_for(friction);
  });

  m.def(
      "simulate_block",
      [](const model::FrictionBlock& block, double t_end, const std::string& friction,
         const std::string& integrator, const std::map<std::string, double>& law, double rtol,
         double atol, double dt,
         double theta, std::vector<double> t_eval, long max_steps, long max_events,
         double max_step, double first_step, int max_order, bool check, py::object progress) {
        model::BlockSimulationOptions options;
        options.check = check;
        options.friction = friction;
        options.integrator = integrator;
        options.law_values.assign(law.begin(), law.end());
        options.integrator_options =
            integrator_options(rtol, atol, max_steps, max_step, first_step, max_order);
        options.dt = dt;
        options.theta = theta;
        options.max_events = max_events;
        options.output.t_end = t_end;
        options.output.t_eval = std::move(t_eval);
        PythonMonitor monitor(std::move(progress));
        MonitorScope scope(&monitor);
        // A Python callable load re-acquires the GIL itself.
        py::gil_scoped_release release;
        return model::simulate(block, options);
      },
      py::arg("block"), py::arg("t_end"), py::arg("friction"), py::arg("integrator"),
      py::arg("law"), py::arg("rtol"), py::arg("atol"), py::arg("dt"), py::arg("theta"),
      py::arg("t_eval"), py::arg("max_steps"), py::arg("max_events"), py::arg("max_step"),
      py::arg("first_step"), py::arg("max_order"), py::arg("check") = true,
      py::arg("progress") = py::none());
}

}  // namespace

void bind_model(py::module_& m) {
  py::class_<integrate::SimulationResult>(m, "SimulationResult")
      .def_property_readonly("time",
                             [](const integrate::SimulationResult& r) {
                               return py::array_t<double>(r.time.size(), r.time.data());
                             })
      .def_property_readonly("point_count", &integrate::SimulationResult::point_count,
                             "The rows (time points), without converting them.")
      .def_property_readonly("channel_names",
                             [](const integrate::SimulationResult& r) { return r.channel_names; })
      .def_property_readonly("channels", &channel_matrix)
      .def(
          "channel",
          [](const integrate::SimulationResult& r, const std::string& name) -> py::object {
            const int k = r.channel_index(name);
            if (k < 0) return py::none();
            py::array_t<double> out(static_cast<py::ssize_t>(r.point_count()));
            r.copy_channel(static_cast<std::size_t>(k), out.mutable_data());
            return out;
          },
          py::arg("name"), "One channel as a new array, or None if there is no such channel.")
      .def_property_readonly("events",
                             [](const integrate::SimulationResult& r) {
                               py::list events;
                               for (const auto& e : r.events)
                                 events.append(py::make_tuple(e.time, e.kind));
                               return events;
                             })
      .def_property_readonly("stats", [](const integrate::SimulationResult& r) {
        return stats_dict(r.stats);
      })
      .def_readonly("integrator", &integrate::SimulationResult::integrator)
      .def_readonly("friction", &integrate::SimulationResult::friction)
      .def_property_readonly("checks", [](const integrate::SimulationResult& r) {
        py::dict out;
        for (const auto& c : r.checks) {
          py::dict entry;
          entry["what"] = c.what;
          entry["applies"] = c.applies;
          entry["passed"] = c.passed;
          entry["value"] = c.value;
          entry["bound"] = c.bound;
          entry["margin"] = c.bound - c.value;
          entry["time"] = c.time;
          entry["unit"] = c.unit;
          out[py::str(c.name)] = entry;
        }
        return out;
      });
  bind_friction_block(m);
}

}  // namespace leadscrew::bindings
