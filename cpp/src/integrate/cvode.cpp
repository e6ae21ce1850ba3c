#include "leadscrew/integrate/cvode.hpp"

#include <cvode/cvode_ls.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cstdlib>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::integrate {

namespace {
const char* method_name(CvodeIntegrator::Method method) {
  return method == CvodeIntegrator::Method::bdf ? "cvode_bdf" : "cvode_adams";
}
}  // namespace

CvodeIntegrator::CvodeIntegrator(Method method, const IntegratorOptions& options)
    : SundialsIntegrator(method_name(method), options, method == Method::bdf), method_(method) {
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
  // CVODE's difference-quotient Jacobian (n extra rhs calls, reused over many
  // steps). For Adams, fixed-point iteration would save the n x n solve, but
  // SUNDIALS 6.4's fixed-point path treats an unrecoverable right-hand-side
  // failure as recoverable (measured: an exception in the rhs was retried
  // until max_steps), and Newton also keeps Adams usable on mildly stiff
  // phases. For the small systems of this package the solve is cheap.
  const sunindextype n = bridge_.size;
  matrix_.reset(SUNDenseMatrix(n, n, ctx));
  if (!matrix_) check_setup(-20, "SUNDenseMatrix");
  linear_solver_.reset(SUNLinSol_Dense(y_.get(), matrix_.get(), ctx));
  if (!linear_solver_) check_setup(-20, "SUNLinSol_Dense");
  check_setup(CVodeSetLinearSolver(mem, linear_solver_.get(), matrix_.get()),
              "CVodeSetLinearSolver");
  if (options_.max_order > 0)
    check_setup(CVodeSetMaxOrd(mem, options_.max_order), "CVodeSetMaxOrd");
  if (options_.max_step > 0.0)
    check_setup(CVodeSetMaxStep(mem, options_.max_step), "CVodeSetMaxStep");
  if (options_.first_step > 0.0)
    check_setup(CVodeSetInitStep(mem, options_.first_step), "CVodeSetInitStep");
  // "t + h = t" warnings would only fill the message buffer.
  check_setup(CVodeSetMaxHnilWarns(mem, -1), "CVodeSetMaxHnilWarns");
  if (bridge_.root_count > 0) {
    check_setup(CVodeRootInit(mem, bridge_.root_count, &sundials::CallbackBridge::roots),
                "CVodeRootInit");
    // A restart exactly at an event has a root function at zero: expected.
    check_setup(CVodeSetNoInactiveRootWarn(mem), "CVodeSetNoInactiveRootWarn");
  }
}

int CvodeIntegrator::restart_solver(double t0) { return CVodeReInit(memory_.get(), t0, y_.get()); }

int CvodeIntegrator::limit_solver(double t_out, long max_steps) {
  // CVODE disables the stop time once it returns there: set it on every call.
  const int flag = CVodeSetStopTime(memory_.get(), t_out);
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

double CvodeIntegrator::solver_time() const {
  sunrealtype t = 0.0;
  CVodeGetCurrentTime(memory_.get(), &t);
  return t;
}

IntegratorStats CvodeIntegrator::solver_stats() const {
  void* mem = memory_.get();
  IntegratorStats s;
  if (!mem) return s;
  long rhs = 0, fd_rhs = 0, jac = 0, nni_fail = 0, netf = 0, nge = 0, nst = 0;
  CVodeGetNumSteps(mem, &nst);
  CVodeGetNumRhsEvals(mem, &rhs);
  CVodeGetNumErrTestFails(mem, &netf);
  CVodeGetNumNonlinSolvConvFails(mem, &nni_fail);
  if (bridge_.root_count > 0) CVodeGetNumGEvals(mem, &nge);
  CVodeGetNumJacEvals(mem, &jac);
  CVodeGetNumLinRhsEvals(mem, &fd_rhs);  // difference-quotient Jacobian columns
  s.steps = nst;
  s.rhs_evaluations = rhs + fd_rhs;
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
