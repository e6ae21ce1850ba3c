#include "bindings.hpp"

namespace py = pybind11;

namespace leadscrew::bindings {

void bind_lcp(py::module_& m) { (void)m; }

}  // namespace leadscrew::bindings
