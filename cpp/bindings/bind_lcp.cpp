// Submodule leadscrew._core.lcp: the LCP solvers (and the Coulomb-friction LCP
// builders). Conversion, GIL release and docstrings only; python/leadscrew/lcp.py
// is the public interface.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>

#include "bindings.hpp"
#include "leadscrew/friction/coulomb_lcp.hpp"
#include "leadscrew/lcp/enumerate.hpp"
#include "leadscrew/lcp/lcp.hpp"
#include "leadscrew/lcp/lemke.hpp"
#include "leadscrew/lcp/workspace.hpp"

namespace py = pybind11;

namespace leadscrew::bindings {

namespace {

using MatrixRef = Eigen::Ref<const Eigen::MatrixXd>;
using VectorRef = Eigen::Ref<const Eigen::VectorXd>;

// (z, w, status, iterations, residual), what leadscrew.lcp builds its LcpResult from.
py::tuple result_tuple(const Eigen::VectorXd& z, const Eigen::VectorXd& w,
                       const lcp::Result& result) {
  return py::make_tuple(z, w, lcp::status_name(result.status), result.iterations,
                        result.residual);
}

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
  return result_tuple(z, w, result);
}

py::tuple solve_lemke_generic(const MatrixRef& M, const VectorRef& q, double tol, int max_iter) {
  lcp::Options options;
  options.tol = tol;
  options.max_iter = max_iter;
  Eigen::VectorXd z = Eigen::VectorXd::Zero(q.size()), w = Eigen::VectorXd::Zero(q.size());
  lcp::Workspace workspace(static_cast<int>(q.size()));
  lcp::Result result;
  {
    py::gil_scoped_release release;
    result = lcp::solve_lemke_generic(M, q, z, w, options, workspace);
  }
  return result_tuple(z, w, result);
}

py::tuple single_friction_lcp(double delassus, double free_acceleration, double mu,
                              double normal_force) {
  const auto lcp = friction::single_friction_lcp(delassus, free_acceleration, mu, normal_force);
  return py::make_tuple(Eigen::MatrixXd(lcp.A), Eigen::VectorXd(lcp.b));
}

py::tuple single_friction_state(const VectorRef& z, const VectorRef& w, double mu,
                                double normal_force) {
  const auto state = friction::single_friction_state(z, w, mu, normal_force);
  return py::make_tuple(state.friction_force, state.acceleration);
}

py::tuple friction_lcp(const MatrixRef& delassus, const VectorRef& free_acceleration,
                       const VectorRef& mu, const VectorRef& normal_force) {
  const Eigen::Index n = delassus.rows();
  Eigen::MatrixXd A(2 * n, 2 * n);
  Eigen::VectorXd b(2 * n);
  friction::friction_lcp(delassus, free_acceleration, mu, normal_force, A, b);
  return py::make_tuple(A, b);
}

py::tuple friction_state(const VectorRef& z, const VectorRef& w, const VectorRef& mu,
                         const VectorRef& normal_force) {
  Eigen::VectorXd friction_force(mu.size()), acceleration(mu.size());
  friction::friction_state(z, w, mu, normal_force, friction_force, acceleration);
  return py::make_tuple(friction_force, acceleration);
}

py::tuple contact_lcp(const MatrixRef& delassus, const VectorRef& free_acceleration,
                      const VectorRef& mu) {
  const Eigen::Index n = mu.size();
  Eigen::MatrixXd A(3 * n, 3 * n);
  Eigen::VectorXd b(3 * n);
  friction::contact_lcp(delassus, free_acceleration, mu, A, b);
  return py::make_tuple(A, b);
}

py::tuple contact_state(const VectorRef& z, const VectorRef& w, const VectorRef& mu) {
  const Eigen::Index n = mu.size();
  Eigen::VectorXd normal_force(n), friction_force(n), normal_acceleration(n),
      tangential_acceleration(n);
  friction::contact_state(z, w, mu, normal_force, friction_force, normal_acceleration,
                          tangential_acceleration);
  return py::make_tuple(normal_force, friction_force, normal_acceleration,
                        tangential_acceleration);
}

}  // namespace

void bind_lcp(py::module_& m) {
  py::module_ lcp = m.def_submodule("lcp", "LCP solvers (private: use leadscrew.lcp)");
  lcp.def("solve", &solve_lcp, py::arg("M"), py::arg("q"), py::arg("method"), py::arg("tol"),
          py::arg("max_iter"), py::arg("z0"), py::arg("relaxation"),
          "Solve the LCP (M, q); returns (z, w, status, iterations, residual). "
          "max_iter 0 is the method's default; z0 None starts cold.");
  lcp.def("solve_lemke_generic", &solve_lemke_generic, py::arg("M"), py::arg("q"),
          py::arg("tol"), py::arg("max_iter"),
          "Lemke on its size-generic code path, also for n <= 8 (where solve runs the "
          "fixed-size one), without the NaN/inf scan; for tests. Returns (z, w, status, "
          "iterations, residual).");
  lcp.def("complementarity_residual", &lcp::complementarity_residual, py::arg("z"),
          py::arg("w"), "max_i |min(z_i, w_i)| + max(0, -min z) + max(0, -min w)");
  lcp.def(
      "default_max_iterations",
      [](const std::string& method, int n) {
        return lcp::default_max_iterations(lcp::parse_method(method), n);
      },
      py::arg("method"), py::arg("n"), "The iteration budget that max_iter 0 stands for.");

  // Coulomb-friction LCP builders (leadscrew/friction/coulomb_lcp.hpp).
  lcp.def("single_friction_lcp", &single_friction_lcp, py::arg("delassus"),
          py::arg("free_acceleration"), py::arg("mu"), py::arg("normal_force"),
          "Thesis eq. (3.10)-(3.14) for one contact; returns (A, b).");
  lcp.def("single_friction_state", &single_friction_state, py::arg("z"), py::arg("w"),
          py::arg("mu"), py::arg("normal_force"),
          "(lambda_T, g_T'') from a solution of single_friction_lcp.");
  lcp.def("friction_lcp", &friction_lcp, py::arg("delassus"), py::arg("free_acceleration"),
          py::arg("mu"), py::arg("normal_force"),
          "The 2n-LCP of n coupled friction contacts; returns (A, b).");
  lcp.def("friction_state", &friction_state, py::arg("z"), py::arg("w"), py::arg("mu"),
          py::arg("normal_force"), "(lambda_T, g_T'') from a solution of friction_lcp.");
  lcp.def("contact_lcp", &contact_lcp, py::arg("delassus"), py::arg("free_acceleration"),
          py::arg("mu"), "The 3n-LCP of n planar contacts with friction; returns (A, b).");
  lcp.def("contact_state", &contact_state, py::arg("z"), py::arg("w"), py::arg("mu"),
          "(lambda_N, lambda_T, g_N'', g_T'') from a solution of contact_lcp.");
  lcp.attr("MAX_ENUMERATE_SIZE") = lcp::kMaxEnumerateSize;
  lcp.attr("MAX_FIXED_LEMKE_SIZE") = lcp::kMaxFixedLemkeSize;
}

}  // namespace leadscrew::bindings
