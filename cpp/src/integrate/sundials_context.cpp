#include "leadscrew/integrate/sundials_context.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "leadscrew/core/errors.hpp"

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

NVector make_vector(int n, const Context& context) {
  NVector v(N_VNew_Serial(static_cast<sunindextype>(n), context.get()));
  if (!v)
    throw SimulationError(0.0, "N_VNew_Serial failed: SUNDIALS could not allocate a vector",
                          "the machine is out of memory");
  return v;
}

void CallbackBridge::clear_call() noexcept {
  pending_ = nullptr;
  message_[0] = '\0';
}

void CallbackBridge::clear_all() noexcept {
  clear_call();
  nonfinite_rhs_ = 0;
  nonfinite_root_ = false;
}

void CallbackBridge::rethrow_pending() {
  if (pending_) {
    std::exception_ptr e = pending_;
    pending_ = nullptr;
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

namespace {
bool all_finite(const double* v, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}
}  // namespace

int CallbackBridge::rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
  auto* self = static_cast<CallbackBridge*>(user_data);
  try {
    double* f = N_VGetArrayPointer(ydot);
    self->system->rhs(t, N_VGetArrayPointer(y), f);
    if (!all_finite(f, self->size)) {
      if (self->nonfinite_rhs_ == 0 && !self->nonfinite_root_) self->nonfinite_t_ = t;
      ++self->nonfinite_rhs_;
      // recoverable: the solver retries with a smaller step, up to the limit
      return self->nonfinite_rhs_ < nonfinite_limit ? 1 : -1;
    }
    return 0;
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
      implicit ? "" : "; if the step size collapsed the problem may be stiff: use cvode_bdf";
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
