// Submodule leadscrew._core.lcp: the LCP solvers (and the Coulomb-friction LCP
// builders). Conversion, GIL release and docstrings only; python/leadscrew/lcp.py
// is the public interface.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>

#include "bindings.hpp"
#include "leadscrew/lcp/enumerate.hpp"
#include "leadscrew/lcp/lcp.hpp"
#include "leadscrew/lcp/workspace.hpp"

namespace py = pybind11;

namespace leadscrew::bindings {

namespace {

using MatrixRef = Eigen::Ref<const Eigen::MatrixXd>;
using VectorRef = Eigen::Ref<const Eigen::VectorXd>;

py::tuple solve_lcp(const MatrixRef& M, const VectorRef& q, const std::string& method,
                    double tol, int max_iter, const std::optional<Eigen::VectorXd>& z0,
                    double relaxation) {
  lcp::Options options;
  options.method = lcp::parse_method(method);
  options.tol = tol;
  options.max_iter = max_iter;
  options.relaxation = relaxation;
  options.warm_start = z0.has_value();
  Eigen::VectorXd z = z0 ? *z0 : Eigen::VectorXd::Zero(q.size());
  Eigen::VectorXd w = Eigen::VectorXd::Zero(q.size());
  lcp::Workspace workspace(static_cast<int>(q.size()));
  lcp::Result result;
  {
    py::gil_scoped_release release;
    result = lcp::solve(M, q, z, w, options, workspace);
  }
  return py::make_tuple(z, w, lcp::status_name(result.status), result.iterations,
                        result.residual);
}

}  // namespace

void bind_lcp(py::module_& m) {
  py::module_ lcp = m.def_submodule("lcp", "LCP solvers (private: use leadscrew.lcp)");
  lcp.def("solve", &solve_lcp, py::arg("M"), py::arg("q"), py::arg("method"), py::arg("tol"),
          py::arg("max_iter"), py::arg("z0"), py::arg("relaxation"),
          "Solve the LCP (M, q); returns (z, w, status, iterations, residual). "
          "max_iter 0 is the method's default; z0 None starts cold.");
  lcp.def("complementarity_residual", &lcp::complementarity_residual, py::arg("z"),
          py::arg("w"), "max_i |min(z_i, w_i)| + max(0, -min z) + max(0, -min w)");
  lcp.def(
      "default_max_iterations",
      [](const std::string& method, int n) {
        return lcp::default_max_iterations(lcp::parse_method(method), n);
      },
      py::arg("method"), py::arg("n"), "The iteration budget that max_iter 0 stands for.");
  lcp.attr("MAX_ENUMERATE_SIZE") = lcp::kMaxEnumerateSize;
}

}  // namespace leadscrew::bindings
