// Ownership of SUNDIALS objects (context, vectors, matrices, linear and
// nonlinear solvers, integrator memory) and the bridge from SUNDIALS' C
// callbacks to an OdeSystem.
//
// This is the only place that creates a SUNContext: SUNDIALS 6.4 takes a
// communicator pointer (NULL), 7.x takes SUN_COMM_NULL; moving to 7.x changes
// sundials_context.cpp only.
#pragma once

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nonlinearsolver.h>
#include <sundials/sundials_types.h>

#include <exception>
#include <memory>
#include <string>
#include <type_traits>

#include "leadscrew/integrate/ode.hpp"

namespace leadscrew::integrate::sundials {

// Owns a SUNContext. One per integrator: a SUNContext is not thread safe, and
// integrators may run on different threads.
class Context {
 public:
  Context();
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  SUNContext get() const noexcept { return context_; }

 private:
  SUNContext context_ = nullptr;
};

struct NVectorDeleter {
  void operator()(N_Vector v) const noexcept { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix a) const noexcept { SUNMatDestroy(a); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver s) const noexcept { SUNLinSolFree(s); }
};
struct NonlinearSolverDeleter {
  void operator()(SUNNonlinearSolver s) const noexcept { SUNNonlinSolFree(s); }
};

using NVector = std::unique_ptr<std::remove_pointer_t<N_Vector>, NVectorDeleter>;
using Matrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using NonlinearSolver =
    std::unique_ptr<std::remove_pointer_t<SUNNonlinearSolver>, NonlinearSolverDeleter>;

// A serial vector of length n (throws SimulationError if SUNDIALS cannot
// allocate it). Its hot operations (and those of its clones) are compiled
// with this package, not taken from the SUNDIALS library (see
// sundials_context.cpp for why).
NVector make_vector(int n, const Context& context);
// An n x n dense matrix, with its copy and shift (A = c A + I) operations
// (and its clones') compiled likewise.
Matrix make_dense_matrix(int n, const Context& context);

// Owns an integrator's memory block (CVODE: CVodeFree, ARKODE: ERKStepFree).
template <void (*Free)(void**)>
class SolverMemory {
 public:
  SolverMemory() = default;
  explicit SolverMemory(void* memory) : memory_(memory) {}
  ~SolverMemory() { reset(); }
  SolverMemory(const SolverMemory&) = delete;
  SolverMemory& operator=(const SolverMemory&) = delete;
  SolverMemory& operator=(SolverMemory&& other) noexcept {
    if (this != &other) {
      reset();
      memory_ = other.memory_;
      other.memory_ = nullptr;
    }
    return *this;
  }
  void reset() noexcept {
    if (memory_) Free(&memory_);
    memory_ = nullptr;
  }
  void* get() const noexcept { return memory_; }

 private:
  void* memory_ = nullptr;
};

// Calls an OdeSystem from SUNDIALS' C callbacks (user_data points to the
// bridge). C++ exceptions must not unwind through SUNDIALS' C frames: an
// exception thrown by the system is kept and rethrown once the solver has
// returned. A NaN or inf right-hand side is reported to SUNDIALS as a
// recoverable failure (it retries with a smaller step: right for a trial step
// that overshot into a region where the model is undefined) and remembered for
// the error message, so a non-finite value never enters the trajectory. After
// nonfinite_limit such values since the last (re)start the failure becomes
// unrecoverable: a model that is undefined beyond some time would otherwise
// be approached in ever smaller steps until max_steps is exhausted.
// A RefusedState exception from the right-hand side (a state off the model's
// domain, or without a consistent contact mode: core/errors.hpp) is
// recoverable too: a trial state of an overshooting step, such as an
// implicit method's Newton iterate with an outdated Jacobian, is no reason
// to stop. A retry ends before the failed trial's time T; outside_limit
// failures before the solver gets past T mean that the solution itself
// reaches the boundary of the domain there: the failure becomes
// unrecoverable and the refusal is rethrown.
class CallbackBridge {
 public:
  static constexpr int message_capacity = 512;
  static constexpr int nonfinite_limit = 64;
  static constexpr int outside_limit = 4;

  OdeSystem* system = nullptr;
  void* owner = nullptr;  // the integrator (for callbacks that need more than the system)
  int size = 0;
  int root_count = 0;
  int quadrature_count = 0;  // trailing states f does not depend on

  // Before a solver call: forgets a previous call's exception and message.
  void clear_call() noexcept;
  // At a (re)start: also forgets the non-finite values seen so far.
  void clear_all() noexcept;
  // Rethrows an exception the system threw during the last solver call, or
  // the refusal (RefusedState) that made it unrecoverable.
  void rethrow_pending();
  // A sentence on the non-finite values the system produced (empty: none).
  std::string nonfinite_report() const;
  // SUNDIALS' own message about the last failure (captured, never printed).
  const char* last_message() const noexcept { return message_; }

  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data);
  static int roots(sunrealtype t, N_Vector y, sunrealtype* g, void* user_data);
  // CVODE's projection (CVProjFn): OdeSystem::project (the error estimate is
  // not projected: CvodeIntegrator::create_solver).
  static int project(sunrealtype t, N_Vector y, N_Vector correction, sunrealtype tolerance,
                     N_Vector error, void* user_data);
  static void error_handler(int error_code, const char* module, const char* function,
                            char* message, void* user_data);

 private:
  std::exception_ptr pending_;
  std::exception_ptr outside_;  // the last refusal (null: none, or got past it)
  double outside_t_ = 0.0;      // the time of the first of them (T above)
  int outside_rhs_ = 0;         // refusals before getting past T
  int nonfinite_rhs_ = 0;   // count since the last (re)start
  bool nonfinite_root_ = false;
  double nonfinite_t_ = 0.0;  // time of the first one
  char message_[message_capacity] = {0};
};

// Throws SimulationError(t, "<FLAG_NAME>: <meaning>[; detail]", hint) for a
// failed CVODE/ARKODE return flag. flag_name is the solver's name for the
// flag; implicit tells whether the method already is an implicit (stiff) one.
[[noreturn]] void throw_solver_failure(double t, int flag, const std::string& flag_name,
                                       const std::string& method, bool implicit,
                                       const CallbackBridge& bridge,
                                       const IntegratorOptions& options);

// Adds the counters of b to a.
void accumulate(IntegratorStats& a, const IntegratorStats& b);

}  // namespace leadscrew::integrate::sundials
