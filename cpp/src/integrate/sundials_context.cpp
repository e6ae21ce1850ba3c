#include "leadscrew/integrate/sundials_context.hpp"

#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/run_monitor.hpp"
#include "leadscrew/integrate/integrator_checks.hpp"

namespace leadscrew::integrate::sundials {

Context::Context() {
  // SUNDIALS 6.x: SUNContext_Create(void* comm, SUNContext*); 7.x: SUN_COMM_NULL.
  if (SUNContext_Create(nullptr, &context_) != 0 || context_ == nullptr)
    throw SimulationError(0.0, "SUNContext_Create failed: SUNDIALS could not allocate its context",
                          "the machine is out of memory");
}

Context::~Context() {
  if (context_) SUNContext_Free(&context_);
}

namespace {

// The serial vector and dense matrix operations that CVODE and ARKODE call
// on every step, compiled with this package's optimisation. The SUNDIALS 6.4
// of Debian (libsundials-*6 6.4.1+dfsg1-3) is built without optimisation:
// every loop keeps its accumulator in memory (measured on the flexible drive
// with cvode_bdf: the weighted RMS norm alone took 12 % of the run, the
// dense matrix copy and shift 5 %). Same arithmetic as N_V*_Serial and
// SUNMat*_Dense, element by element (so z may be x or y, as there).
// Vectors cloned from one of make_vector's inherit these operations.
sunindextype length(N_Vector v) { return NV_LENGTH_S(v); }
double* data(N_Vector v) { return NV_DATA_S(v); }

void linear_sum(sunrealtype a, N_Vector x, sunrealtype b, N_Vector y, N_Vector z) {
  const sunindextype n = length(x);
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
}
void constant(sunrealtype c, N_Vector z) {
  const sunindextype n = length(z);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c;
}
void product(N_Vector x, N_Vector y, N_Vector z) {
  const sunindextype n = length(x);
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] * yd[i];
}
void quotient(N_Vector x, N_Vector y, N_Vector z) {
  const sunindextype n = length(x);
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] / yd[i];
}
void scale(sunrealtype c, N_Vector x, N_Vector z) {
  const sunindextype n = length(x);
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c * xd[i];
}
void absolute(N_Vector x, N_Vector z) {
  const sunindextype n = length(x);
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = std::fabs(xd[i]);
}
void inverse(N_Vector x, N_Vector z) {
  const sunindextype n = length(x);
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = 1.0 / xd[i];
}
void add_constant(N_Vector x, sunrealtype b, N_Vector z) {
  const sunindextype n = length(x);
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] + b;
}
sunrealtype max_norm(N_Vector x) {
  const sunindextype n = length(x);
  const double* xd = data(x);
  double m = 0.0;
  for (sunindextype i = 0; i < n; ++i) m = std::max(m, std::fabs(xd[i]));
  return m;
}
sunrealtype weighted_square_sum(N_Vector x, N_Vector w) {
  const sunindextype n = length(x);
  const double *xd = data(x), *wd = data(w);
  double sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) sum += (xd[i] * wd[i]) * (xd[i] * wd[i]);
  return sum;
}
sunrealtype wrms_norm(N_Vector x, N_Vector w) {
  return std::sqrt(weighted_square_sum(x, w) / static_cast<double>(length(x)));
}
sunrealtype minimum(N_Vector x) {
  const sunindextype n = length(x);
  const double* xd = data(x);
  double m = xd[0];
  for (sunindextype i = 1; i < n; ++i) m = std::min(m, xd[i]);
  return m;
}
int linear_combination(int count, sunrealtype* c, N_Vector* x, N_Vector z) {
  const sunindextype n = length(z);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) {
    double sum = 0.0;
    for (int k = 0; k < count; ++k) sum += c[k] * data(x[k])[i];
    zd[i] = sum;
  }
  return 0;
}
int scale_add_multi(int count, sunrealtype* a, N_Vector x, N_Vector* y, N_Vector* z) {
  const sunindextype n = length(x);
  const double* xd = data(x);
  for (int k = 0; k < count; ++k) {
    const double* yd = data(y[k]);
    double* zd = data(z[k]);
    for (sunindextype i = 0; i < n; ++i) zd[i] = a[k] * xd[i] + yd[i];
  }
  return 0;
}

void use_compiled_ops(N_Vector v) {
  N_Vector_Ops ops = v->ops;
  ops->nvlinearsum = &linear_sum;
  ops->nvconst = &constant;
  ops->nvprod = &product;
  ops->nvdiv = &quotient;
  ops->nvscale = &scale;
  ops->nvabs = &absolute;
  ops->nvinv = &inverse;
  ops->nvaddconst = &add_constant;
  ops->nvmaxnorm = &max_norm;
  ops->nvwrmsnorm = &wrms_norm;
  ops->nvmin = &minimum;
  ops->nvlinearcombination = &linear_combination;
  ops->nvscaleaddmulti = &scale_add_multi;
  ops->nvwsqrsumlocal = &weighted_square_sum;
}

// Dense matrices: B = A, and A = c A + I (CVODE's Newton matrix I - gamma J).
int copy_matrix(SUNMatrix a, SUNMatrix b) {
  const sunindextype size = SM_LDATA_D(a);
  if (SM_LDATA_D(b) != size) return SUNMAT_ILL_INPUT;
  std::copy(SM_DATA_D(a), SM_DATA_D(a) + size, SM_DATA_D(b));
  return SUNMAT_SUCCESS;
}
int scale_add_identity(sunrealtype c, SUNMatrix a) {
  const sunindextype rows = SM_ROWS_D(a), columns = SM_COLUMNS_D(a);
  double* d = SM_DATA_D(a);
  for (sunindextype j = 0; j < columns; ++j) {
    double* column = d + j * rows;
    for (sunindextype i = 0; i < rows; ++i) column[i] *= c;
    if (j < rows) column[j] += 1.0;
  }
  return SUNMAT_SUCCESS;
}
SUNMatrix clone_matrix(SUNMatrix a);

// The compiled dense-matrix operations (a clone gets them too).
void use_compiled_matrix_ops(SUNMatrix a) {
  a->ops->copy = &copy_matrix;
  a->ops->scaleaddi = &scale_add_identity;
  a->ops->clone = &clone_matrix;
}

SUNMatrix clone_matrix(SUNMatrix a) {
  SUNMatrix b = SUNDenseMatrix(SM_ROWS_D(a), SM_COLUMNS_D(a), a->sunctx);
  if (b) use_compiled_matrix_ops(b);
  return b;
}

}  // namespace

NVector make_vector(int n, const Context& context) {
  NVector v(N_VNew_Serial(static_cast<sunindextype>(n), context.get()));
  if (!v)
    throw SimulationError(0.0, "N_VNew_Serial failed: SUNDIALS could not allocate a vector",
                          "the machine is out of memory");
  use_compiled_ops(v.get());
  return v;
}

Matrix make_dense_matrix(int n, const Context& context) {
  Matrix a(SUNDenseMatrix(static_cast<sunindextype>(n), static_cast<sunindextype>(n),
                          context.get()));
  if (!a)
    throw SimulationError(0.0, "SUNDenseMatrix failed: SUNDIALS could not allocate a matrix",
                          "the machine is out of memory");
  use_compiled_matrix_ops(a.get());
  return a;
}

void CallbackBridge::clear_call() noexcept {
  pending_ = nullptr;
  message_[0] = '\0';
}

void CallbackBridge::clear_all() noexcept {
  clear_call();
  nonfinite_rhs_ = 0;
  outside_ = nullptr;
  outside_rhs_ = 0;
  nonfinite_root_ = false;
}

void CallbackBridge::rethrow_pending() {
  // A refusal only when it ended the call (outside_limit reached): a
  // retried one is no reason for a failure of another kind (max_steps, ...).
  std::exception_ptr e =
      pending_ ? pending_ : (outside_rhs_ >= outside_limit ? outside_ : nullptr);
  if (e) {
    pending_ = outside_ = nullptr;
    outside_rhs_ = 0;
    std::rethrow_exception(e);
  }
}

std::string CallbackBridge::nonfinite_report() const {
  if (nonfinite_rhs_ == 0 && !nonfinite_root_) return "";
  std::ostringstream out;
  out.precision(17);
  if (nonfinite_rhs_ > 0)
    out << "the right-hand side returned a non-finite value (NaN or inf) " << nonfinite_rhs_
        << (nonfinite_rhs_ == 1 ? " time" : " times") << ", first at t = " << nonfinite_t_;
  else
    out << "a root function returned a non-finite value (NaN or inf) at t = " << nonfinite_t_;
  return out.str();
}

int CallbackBridge::rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
  auto* self = static_cast<CallbackBridge*>(user_data);
  try {
    double* f = N_VGetArrayPointer(ydot);
    poll_monitor(t);
    self->system->rhs(t, N_VGetArrayPointer(y), f);
    if (self->outside_ && t > self->outside_t_) {  // got past the failed trial
      self->outside_ = nullptr;
      self->outside_rhs_ = 0;
    }
    if (!all_finite(f, self->size)) {
      if (self->nonfinite_rhs_ == 0 && !self->nonfinite_root_) self->nonfinite_t_ = t;
      ++self->nonfinite_rhs_;
      // recoverable: the solver retries with a smaller step, up to the limit
      return self->nonfinite_rhs_ < nonfinite_limit ? 1 : -1;
    }
    return 0;
  } catch (const RefusedState&) {
    // A trial state off the model's domain, or one without a consistent
    // contact mode (core/errors.hpp): retried with a smaller step.
    if (!self->outside_) self->outside_t_ = t;
    self->outside_ = std::current_exception();
    return ++self->outside_rhs_ < outside_limit ? 1 : -1;
  } catch (...) {
    self->pending_ = std::current_exception();
    return -1;  // unrecoverable: the solver returns, the exception is rethrown
  }
}

int CallbackBridge::project(sunrealtype t, N_Vector y, N_Vector correction, sunrealtype,
                            N_Vector, void* user_data) {
  auto* self = static_cast<CallbackBridge*>(user_data);
  try {
    self->system->project(t, N_VGetArrayPointer(y), N_VGetArrayPointer(correction));
    return all_finite(N_VGetArrayPointer(correction), self->size) ? 0 : -1;
  } catch (...) {
    self->pending_ = std::current_exception();
    return -1;  // unrecoverable: the solver returns, the exception is rethrown
  }
}

int CallbackBridge::roots(sunrealtype t, N_Vector y, sunrealtype* g, void* user_data) {
  auto* self = static_cast<CallbackBridge*>(user_data);
  try {
    self->system->roots(t, N_VGetArrayPointer(y), g);
    if (!all_finite(g, self->root_count)) {
      if (self->nonfinite_rhs_ == 0 && !self->nonfinite_root_) self->nonfinite_t_ = t;
      self->nonfinite_root_ = true;
      return -1;  // root functions have no recoverable failure
    }
    return 0;
  } catch (...) {
    self->pending_ = std::current_exception();
    return -1;
  }
}

void CallbackBridge::error_handler(int /*error_code*/, const char* module, const char* function,
                                   char* message, void* user_data) {
  // Keep the message for the exception instead of printing it to stderr.
  auto* self = static_cast<CallbackBridge*>(user_data);
  std::snprintf(self->message_, message_capacity, "%s (%s): %s", module ? module : "",
                function ? function : "", message ? message : "");
}

namespace {
struct FailureText {
  const char* meaning;
  std::string hint;
};

FailureText describe(int flag, const std::string& method, bool implicit,
                     const IntegratorOptions& options) {
  const std::string stiff_hint =
      implicit ? "" : "; if the step size collapsed the problem may be stiff: use cvode_bdf "
                 "(smooth_integrator = \"cvode_bdf\" inside integrator = \"event_driven\")";
  switch (flag) {
    case -1:
      return {"the total number of internal steps reached max_steps",
              "increase max_steps (now " + std::to_string(options.max_steps) +
                  ") or check whether the solution blows up" + stiff_hint};
    case -2:
      return {"the requested accuracy is beyond floating-point precision",
              "loosen rtol/atol (rtol >= 1e-13 or so)"};
    case -3:
      return {"the local error test failed repeatedly or at the smallest step size",
              "the solution is probably singular or discontinuous here (a blow-up, or a switch "
              "that should be an event with a root function); loosen tolerances only if the "
              "solution is smooth" +
                  stiff_hint};
    case -4:
      return {"the corrector (nonlinear) iteration failed to converge repeatedly",
              method == "cvode_adams"
                  ? std::string("the problem is probably stiff: use cvode_bdf")
                  : std::string("the Jacobian may be singular or discontinuous; reduce "
                                "max_step or tighten tolerances")};
    case -5:
      return {"the linear solver failed to initialize", "check the system size"};
    case -6:
      return {"the linear solver setup (iteration matrix factorization) failed",
              "the iteration matrix is singular: check the model's Jacobian"};
    case -7:
      return {"the linear solve failed", "the iteration matrix is singular: check the model"};
    case -8:
      return {"the right-hand side failed unrecoverably", "check the model at this time"};
    case -9:
      return {"the right-hand side failed at the first call",
              "check the initial state and the model at the initial time"};
    case -10:
      return {"the right-hand side failed repeatedly even with reduced step sizes",
              "check the model: it is undefined (NaN/inf) near this state" + stiff_hint};
    case -11:
      return {"the right-hand side failed and the solver could not recover",
              "check the model: it is undefined (NaN/inf) near this state"};
    case -12:
      return {"a root (event) function failed", "check the root functions at this state"};
    case -22:
      return {"illegal input to the solver", "check the integrator options and t_out"};
    case -27:
      return {"t_out is too close to the current time to start integrating",
              "advance to a later t_out"};
    default:
      return {"the solver failed", "check the model and the integrator options"};
  }
}
}  // namespace

void throw_solver_failure(double t, int flag, const std::string& flag_name,
                          const std::string& method, bool implicit, const CallbackBridge& bridge,
                          const IntegratorOptions& options) {
  const FailureText text = describe(flag, method, implicit, options);
  std::string reason = flag_name + ": " + text.meaning + " (" + method + ")";
  const std::string nonfinite = bridge.nonfinite_report();
  if (!nonfinite.empty()) reason += "; " + nonfinite;
  if (bridge.last_message()[0] != '\0') reason += "; " + std::string(bridge.last_message());
  throw SimulationError(t, reason, text.hint);
}

void accumulate(IntegratorStats& a, const IntegratorStats& b) {
  a.steps += b.steps;
  a.rhs_evaluations += b.rhs_evaluations;
  a.jacobian_evaluations += b.jacobian_evaluations;
  a.root_evaluations += b.root_evaluations;
  a.error_test_failures += b.error_test_failures;
  a.nonlinear_failures += b.nonlinear_failures;
  a.restarts += b.restarts;
}

}  // namespace leadscrew::integrate::sundials
