#include "leadscrew/integrate/cvode.hpp"

#include <cvode/cvode_ls.h>
#include <cvode/cvode_proj.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::integrate {

namespace {
const char* method_name(CvodeIntegrator::Method method) {
  return method == CvodeIntegrator::Method::bdf ? "cvode_bdf" : "cvode_adams";
}

// Direct solver for CVODE's Newton matrix A = I - gamma J of a system whose
// last k states are quadratures (OdeSystem::quadrature_count): their
// Jacobian columns are zero, so with m = n - k
//   A = [[A11, 0], [A21, I]],  x1 = A11^-1 b1,  x2 = b2 - A21 x1.
// Only the m x m block is factored (partial-pivoting LU, Eigen): for the
// flexible drive (12 + 5 states) a third of the dense n x n factorization's
// work, and each solve half of it. With k = 0 it is a plain dense LU.
// Preallocated in make_block_solver; setup and solve do not allocate.
struct BlockSolver {
  int n = 0, m = 0;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;  // of A11
  Eigen::VectorXd x1;

  static BlockSolver* of(SUNLinearSolver s) { return static_cast<BlockSolver*>(s->content); }

  static SUNLinearSolver_Type type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
  static SUNLinearSolver_ID id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
  static int initialize(SUNLinearSolver) { return SUNLS_SUCCESS; }

  static int setup(SUNLinearSolver s, SUNMatrix a) {
    BlockSolver& self = *of(s);
    const Eigen::Map<const Eigen::MatrixXd> full(SUNDenseMatrix_Data(a), self.n, self.n);
    self.lu.compute(full.topLeftCorner(self.m, self.m));
    // A zero pivot: singular Newton matrix; CVODE retries with a smaller step.
    const auto& factors = self.lu.matrixLU();
    for (int i = 0; i < self.m; ++i)
      if (!(factors(i, i) != 0.0) || !std::isfinite(factors(i, i))) return SUNLS_LUFACT_FAIL;
    return SUNLS_SUCCESS;
  }

  static int solve(SUNLinearSolver s, SUNMatrix a, N_Vector x, N_Vector b, sunrealtype) {
    BlockSolver& self = *of(s);
    const Eigen::Map<const Eigen::VectorXd> rhs(N_VGetArrayPointer(b), self.n);
    Eigen::Map<Eigen::VectorXd> out(N_VGetArrayPointer(x), self.n);
    // x1 = U^-1 L^-1 P b1, written out: Eigen's triangular solves are made
    // for large dynamic sizes (measured: 9 % of a flexible-drive run on 12 x 12).
    const Eigen::MatrixXd& lu = self.lu.matrixLU();
    const auto& permutation = self.lu.permutationP().indices();
    const int m = self.m;
    double* x1 = self.x1.data();
    for (int i = 0; i < m; ++i) x1[permutation[i]] = rhs[i];
    for (int j = 0; j < m; ++j) {  // L: unit lower triangle, by columns
      const double xj = x1[j];
      const double* column = lu.data() + static_cast<std::ptrdiff_t>(j) * m;
      for (int i = j + 1; i < m; ++i) x1[i] -= column[i] * xj;
    }
    for (int j = m - 1; j >= 0; --j) {  // U, by columns
      const double* column = lu.data() + static_cast<std::ptrdiff_t>(j) * m;
      x1[j] /= column[j];
      const double xj = x1[j];
      for (int i = 0; i < j; ++i) x1[i] -= column[i] * xj;
    }
    if (self.m < self.n) {
      const Eigen::Map<const Eigen::MatrixXd> full(SUNDenseMatrix_Data(a), self.n, self.n);
      const int k = self.n - self.m;
      out.tail(k) = rhs.tail(k);
      out.tail(k).noalias() -= full.bottomLeftCorner(k, self.m) * self.x1;
    }
    out.head(self.m) = self.x1;
    return SUNLS_SUCCESS;
  }

  static int free(SUNLinearSolver s) {
    if (!s) return SUNLS_SUCCESS;
    delete of(s);
    s->content = nullptr;
    SUNLinSolFreeEmpty(s);
    return SUNLS_SUCCESS;
  }
};

SUNLinearSolver make_block_solver(int n, int quadratures, SUNContext context) {
  auto content = std::make_unique<BlockSolver>();
  content->n = n;
  content->m = n - quadratures;
  content->lu = Eigen::PartialPivLU<Eigen::MatrixXd>(content->m);
  content->x1.resize(content->m);
  SUNLinearSolver s = SUNLinSolNewEmpty(context);
  if (!s) return nullptr;
  s->content = content.release();
  s->ops->gettype = &BlockSolver::type;
  s->ops->getid = &BlockSolver::id;
  s->ops->initialize = &BlockSolver::initialize;
  s->ops->setup = &BlockSolver::setup;
  s->ops->solve = &BlockSolver::solve;
  s->ops->free = &BlockSolver::free;
  return s;
}
}  // namespace

CvodeIntegrator::CvodeIntegrator(Method method, const IntegratorOptions& options)
    : SundialsIntegrator(method_name(method), options, method == Method::bdf), method_(method) {
  check_options(method, options);
}

void CvodeIntegrator::check_options(Method method, const IntegratorOptions& options) {
  const int highest = method == Method::bdf ? 5 : 12;
  if (options.max_order < 0 || options.max_order > highest)
    throw InvalidArgument("max_order = " + std::to_string(options.max_order) +
                          " is invalid: must be 0 (default) or 1.." + std::to_string(highest) +
                          " for " + method_name(method));
  if (options.fixed_step != 0.0)
    throw InvalidArgument("fixed_step = " + format_value(options.fixed_step) +
                          " is invalid: must be 0 for " + method_name(method) +
                          " (variable-step only; fixed steps: the explicit Runge-Kutta methods)");
}

void CvodeIntegrator::create_solver(double t0) {
  memory_.reset();
  linear_solver_.reset();
  matrix_.reset();
  SUNContext ctx = context_.get();
  memory_ = sundials::SolverMemory<CVodeFree>(
      CVodeCreate(method_ == Method::bdf ? CV_BDF : CV_ADAMS, ctx));
  void* mem = memory_.get();
  if (!mem)
    throw SimulationError(t0, "CVodeCreate failed: CVODE could not allocate its memory",
                          "the machine is out of memory");
  // Errors come back as exceptions only: SUNDIALS' messages are captured.
  check_setup(CVodeSetErrHandlerFn(mem, &sundials::CallbackBridge::error_handler, &bridge_),
              "CVodeSetErrHandlerFn");
  check_setup(CVodeInit(mem, &sundials::CallbackBridge::rhs, t0, y_.get()), "CVodeInit");
  check_setup(CVodeSetUserData(mem, &bridge_), "CVodeSetUserData");
  check_setup(CVodeSStolerances(mem, options_.rtol, options_.atol), "CVodeSStolerances");
  // Both methods use Newton iteration with a dense direct linear solver and
  // a difference-quotient Jacobian (n extra rhs calls, reused over many
  // steps). For Adams, fixed-point iteration would save the n x n solve, but
  // SUNDIALS 6.4's fixed-point path treats an unrecoverable right-hand-side
  // failure as recoverable (measured: an exception in the rhs was retried
  // until max_steps), and Newton also keeps Adams usable on mildly stiff
  // phases. For the small systems of this package the solve is cheap.
  const sunindextype n = bridge_.size;
  matrix_ = sundials::make_dense_matrix(static_cast<int>(n), context_);
  linear_solver_.reset(make_block_solver(bridge_.size, bridge_.quadrature_count, ctx));
  if (!linear_solver_) check_setup(-20, "SUNLinSolNewEmpty");
  check_setup(CVodeSetLinearSolver(mem, linear_solver_.get(), matrix_.get()),
              "CVodeSetLinearSolver");
  check_setup(CVodeSetJacFn(mem, &CvodeIntegrator::difference_jacobian), "CVodeSetJacFn");
  // A system's invariants held on the acceleration level drift with the
  // Newton iteration's error, step by step (OdeSystem::has_projection; a
  // stuck flexible drive crept 7.6e-6 m/s off its closed flank in 2 s at
  // rtol 1e-8): each accepted step is offered back to the system, which
  // projects it where it drifts (OdeSystem::project). The error estimate is
  // left whole: its part along the invariants is what bounds the step's
  // violation, hence the projection's correction, to the tolerances (with
  // it projected away, steps of 0.34 s each left a violation 1.7 times the
  // last, the correction enters CVODE's history with the step's, and the
  // 2.6e-9 m correction that ended it rang the seat at 8e-7 m/s). CVODE
  // projects with BDF only; Adams keeps the drift, at its smaller Newton
  // error (8e-9 m/s in 2 s on that drive).
  if (method_ == Method::bdf && bridge_.system->has_projection()) {
    check_setup(CVodeSetProjFn(mem, &sundials::CallbackBridge::project), "CVodeSetProjFn");
    check_setup(CVodeSetProjErrEst(mem, SUNFALSE), "CVodeSetProjErrEst");
  }
  bridge_.owner = this;
  jacobian_rhs_ = 0;
  if (options_.max_order > 0)
    check_setup(CVodeSetMaxOrd(mem, options_.max_order), "CVodeSetMaxOrd");
  // BDF of order 3 to 5 is unstable for long steps on eigenvalues near the
  // imaginary axis (lightly damped stiff modes of the flexible drives);
  // stability limit detection lowers the order only when it sees that.
  if (method_ == Method::bdf) check_setup(CVodeSetStabLimDet(mem, SUNTRUE), "CVodeSetStabLimDet");
  if (options_.max_step > 0.0)
    check_setup(CVodeSetMaxStep(mem, options_.max_step), "CVodeSetMaxStep");
  if (options_.first_step > 0.0)
    check_setup(CVodeSetInitStep(mem, options_.first_step), "CVodeSetInitStep");
  if (options_.max_nonlinear_iterations > 0)
    check_setup(CVodeSetMaxNonlinIters(mem, options_.max_nonlinear_iterations),
                "CVodeSetMaxNonlinIters");
  // "t + h = t" warnings would only fill the message buffer.
  check_setup(CVodeSetMaxHnilWarns(mem, -1), "CVodeSetMaxHnilWarns");
  if (bridge_.root_count > 0) {
    check_setup(CVodeRootInit(mem, bridge_.root_count, &sundials::CallbackBridge::roots),
                "CVodeRootInit");
    // A restart exactly at an event has a root function at zero: expected.
    check_setup(CVodeSetNoInactiveRootWarn(mem), "CVodeSetNoInactiveRootWarn");
  }
}

int CvodeIntegrator::restart_solver(double t0) {
  jacobian_rhs_ = 0;
  return CVodeReInit(memory_.get(), t0, y_.get());
}

int CvodeIntegrator::difference_jacobian(sunrealtype t, N_Vector y, N_Vector fy,
                                         SUNMatrix jacobian, void* user_data, N_Vector tmp1,
                                         N_Vector tmp2, N_Vector tmp3) {
  // Column j: (f(t, y + sigma_j e_j) - f(t, y)) / sigma_j with CVODE's
  // increment sigma_j = max(sqrt(U) |y_j|, sigma_0 / w_j),
  // sigma_0 = 1000 |h| U n ||f||_WRMS (1 if f = 0), U the unit roundoff and
  // w the error weights (CVODE user guide, dense difference-quotient Jacobian).
  auto* bridge = static_cast<sundials::CallbackBridge*>(user_data);
  auto* self = static_cast<CvodeIntegrator*>(bridge->owner);
  void* mem = self->memory_.get();
  const int n = bridge->size;
  sunrealtype h = 0.0;
  CVodeGetCurrentStep(mem, &h);
  CVodeGetErrWeights(mem, tmp3);
  const double* y0 = N_VGetArrayPointer(y);
  const double* f0 = N_VGetArrayPointer(fy);
  double* y1 = N_VGetArrayPointer(tmp1);
  const double* f1 = N_VGetArrayPointer(tmp2);
  const double* w = N_VGetArrayPointer(tmp3);
  constexpr double roundoff = std::numeric_limits<double>::epsilon();
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += (f0[i] * w[i]) * (f0[i] * w[i]);
  const double f_norm = std::sqrt(sum / n);
  const double sigma0 = f_norm != 0.0 ? 1000.0 * std::fabs(h) * roundoff * n * f_norm : 1.0;
  for (int i = 0; i < n; ++i) y1[i] = y0[i];
  // f does not depend on the quadratures: their columns are zero.
  const int m = n - bridge->quadrature_count;
  for (int j = m; j < n; ++j) {
    double* column = SUNDenseMatrix_Column(jacobian, j);
    for (int i = 0; i < n; ++i) column[i] = 0.0;
  }
  for (int j = 0; j < m; ++j) {
    y1[j] = y0[j] + std::max(std::sqrt(roundoff) * std::fabs(y0[j]), sigma0 / w[j]);
    const double sigma = y1[j] - y0[j];  // the increment actually represented
    const int flag = sundials::CallbackBridge::rhs(t, tmp1, tmp2, bridge);
    ++self->jacobian_rhs_;
    if (flag != 0) return flag;
    double* column = SUNDenseMatrix_Column(jacobian, j);
    for (int i = 0; i < n; ++i) column[i] = (f1[i] - f0[i]) / sigma;
    y1[j] = y0[j];
  }
  return 0;
}

int CvodeIntegrator::limit_solver(double t_stop, long max_steps) {
  // CVODE disables the stop time once it returns there: set it on every call.
  const int flag = CVodeSetStopTime(memory_.get(), t_stop);
  if (flag < 0) return flag;
  return CVodeSetMaxNumSteps(memory_.get(), max_steps);
}

int CvodeIntegrator::evolve_solver(double t_out, bool one_step, double* t_reached) {
  sunrealtype t = 0.0;
  const int flag = CVode(memory_.get(), t_out, y_.get(), &t, one_step ? CV_ONE_STEP : CV_NORMAL);
  *t_reached = t;
  return flag;
}

int CvodeIntegrator::solver_root_info(int* info) { return CVodeGetRootInfo(memory_.get(), info); }

int CvodeIntegrator::solver_dense_output(double t, N_Vector v) {
  return CVodeGetDky(memory_.get(), t, 0, v);
}

double CvodeIntegrator::solver_time() const {
  sunrealtype t = 0.0;
  CVodeGetCurrentTime(memory_.get(), &t);
  return t;
}

IntegratorStats CvodeIntegrator::solver_stats() const {
  void* mem = memory_.get();
  IntegratorStats s;
  if (!mem) return s;
  long rhs = 0, jac = 0, nni_fail = 0, netf = 0, nge = 0, nst = 0;
  CVodeGetNumSteps(mem, &nst);
  CVodeGetNumRhsEvals(mem, &rhs);
  CVodeGetNumErrTestFails(mem, &netf);
  CVodeGetNumNonlinSolvConvFails(mem, &nni_fail);
  if (bridge_.root_count > 0) CVodeGetNumGEvals(mem, &nge);
  CVodeGetNumJacEvals(mem, &jac);
  s.steps = nst;
  s.rhs_evaluations = rhs + jacobian_rhs_;
  s.jacobian_evaluations = jac;
  s.root_evaluations = nge;
  s.error_test_failures = netf;
  s.nonlinear_failures = nni_fail;
  return s;
}

std::string CvodeIntegrator::flag_name(int flag) const {
  char* name = CVodeGetReturnFlagName(flag);  // malloc'ed by SUNDIALS
  std::string result = name ? name : "CV_UNKNOWN_FLAG";
  std::free(name);
  return result;
}

}  // namespace leadscrew::integrate
