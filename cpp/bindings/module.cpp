#include "bindings.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "leadscrew numerical core (private: use the leadscrew package)";
  leadscrew::bindings::bind_core(m);
  leadscrew::bindings::bind_thread(m);
  leadscrew::bindings::bind_lcp(m);
  leadscrew::bindings::bind_excitation(m);
  leadscrew::bindings::bind_friction(m);
  leadscrew::bindings::bind_model(m);
  leadscrew::bindings::bind_drive(m);
  leadscrew::bindings::bind_integrate(m);
}
