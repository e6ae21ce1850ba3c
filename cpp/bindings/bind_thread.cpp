#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/model/elements/preloaded_nut.hpp"
#include "leadscrew/thread/thread.hpp"

namespace py = pybind11;

namespace leadscrew::bindings {

namespace {

// The thread's closed forms (thread/thread.hpp): torques, efficiency, self-locking.
void bind_thread_functions(py::module_& m) {
  m.def("raise_torque", &raise_torque, py::arg("thread"), py::arg("mu"), py::arg("load"),
        py::arg("collar_mu") = 0.0, py::arg("collar_diameter") = 0.0);
  m.def("lower_torque", &lower_torque, py::arg("thread"), py::arg("mu"), py::arg("load"),
        py::arg("collar_mu") = 0.0, py::arg("collar_diameter") = 0.0);
  m.def("efficiency", &efficiency, py::arg("thread"), py::arg("mu"),
        py::arg("collar_mu") = 0.0, py::arg("collar_diameter") = 0.0,
        py::arg("backdrive") = false);
  m.def("is_self_locking", &is_self_locking, py::arg("thread"), py::arg("mu"));
  m.def("is_drivable", &is_drivable, py::arg("thread"), py::arg("mu"));
  // Elementwise over an array of mu (the closed-form columns of a sweep: one
  // call instead of one per value); the thread by value, as py::vectorize
  // passes its non-vectorized arguments.
  m.def("efficiency_array",
        py::vectorize([](Thread thread, double mu) { return efficiency(thread, mu); }),
        py::arg("thread"), py::arg("mu"),
        "efficiency(thread, m) [1] for each m of the array mu [1] (forward, no collar); "
        "ValueError for a negative or non-finite m.");
  m.def("preloaded_efficiency_array",
        py::vectorize([](Thread thread, double mu, double load, double preload) {
          return model::elements::preloaded_efficiency(
              thread.lead_angle(), thread.effective_mu(require_nonnegative("mu", mu)),
              require_nonnegative("load", load), require_nonnegative("preload", preload));
        }),
        py::arg("thread"), py::arg("mu"), py::arg("load"), py::arg("preload"),
        "The steady raising efficiency of the rigid drive with a preloaded nut, F tan a / "
        "[(F + P) tan(a + rho') + P tan(rho' - a)] [1], elementwise over mu [1], load F [N] "
        "and preload P [N] (docs/physics/preloaded_nut.md); ValueError for a negative or "
        "non-finite value.");
  m.def("is_drivable_array",
        py::vectorize([](Thread thread, double mu) { return is_drivable(thread, mu); }),
        py::arg("thread"), py::arg("mu"),
        "is_drivable(thread, m) for each m of the array mu [1]; ValueError for a negative "
        "or non-finite m.");
}

}  // namespace

void bind_thread(py::module_& m) {
  py::class_<Thread>(m, "Thread", R"doc(
Thread geometry of a power screw (immutable).

Args:
    pitch: axial distance between neighbouring thread flanks [m], > 0.
    mean_diameter: mean (pitch) diameter d_m [m], > 0.
    starts: number of thread starts, integer >= 1.
    flank_angle: included thread angle beta [rad] in [0, pi): 0 square,
        29 deg Acme, 30 deg ISO metric trapezoidal.
    hand: "right" or "left"; "left" flips the sign of the screw relation.

Raises:
    ValueError: a parameter is non-finite or out of range.
)doc")
      .def(py::init([](double pitch, double mean_diameter, int starts, double flank_angle,
                       const std::string& hand) {
             return Thread(pitch, mean_diameter, starts, flank_angle, parse_hand(hand));
           }),
           py::arg("pitch"), py::arg("mean_diameter"), py::arg("starts") = 1,
           py::arg("flank_angle") = 0.0, py::arg("hand") = "right")
      .def_property_readonly("pitch", &Thread::pitch, "pitch [m]")
      .def_property_readonly("mean_diameter", &Thread::mean_diameter, "mean diameter d_m [m]")
      .def_property_readonly("mean_radius", &Thread::mean_radius, "mean radius r_m [m]")
      .def_property_readonly("starts", &Thread::starts, "number of starts")
      .def_property_readonly("flank_angle", &Thread::flank_angle, "included flank angle [rad]")
      .def_property_readonly("hand", [](const Thread& t) { return hand_name(t.hand()); })
      .def_property_readonly("lead", &Thread::lead, "starts * pitch [m]")
      .def_property_readonly("lead_angle", &Thread::lead_angle,
                             "atan(lead / (pi d_m)) [rad]")
      .def_property_readonly("lead_per_radian", &Thread::lead_per_radian, "lead / (2 pi) [m/rad]")
      .def_property_readonly("hand_sign", &Thread::hand_sign, "+1 right hand, -1 left hand")
      .def("effective_mu", &Thread::effective_mu, py::arg("mu"),
           "mu' = mu / cos(flank_angle / 2)")
      .def("__repr__",
           [](const Thread& t) {
             return "Thread(pitch=" + py::repr(py::float_(t.pitch())).cast<std::string>() +
                    ", mean_diameter=" +
                    py::repr(py::float_(t.mean_diameter())).cast<std::string>() +
                    ", starts=" + std::to_string(t.starts()) + ", flank_angle=" +
                    py::repr(py::float_(t.flank_angle())).cast<std::string>() + ", hand='" +
                    hand_name(t.hand()) + "')";
           })
      .def(py::pickle(
          [](const Thread& t) {
            return py::make_tuple(t.pitch(), t.mean_diameter(), t.starts(), t.flank_angle(),
                                  hand_name(t.hand()));
          },
          [](const py::tuple& s) {
            return Thread(s[0].cast<double>(), s[1].cast<double>(), s[2].cast<int>(),
                          s[3].cast<double>(), parse_hand(s[4].cast<std::string>()));
          }));
  bind_thread_functions(m);
}

}  // namespace leadscrew::bindings
