// One interface for every ODE integrator of the core (one file per method,
// behind make_integrator): the smooth phases of the event-driven scheme and the
// regularized and compliant models all run through it.
//
// An integrator is set up once for a system (initialize: allocates), restarted
// after an event without allocating (reinitialize), and advanced to an output
// time or to the first root of the system's root functions (advance).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

namespace leadscrew::integrate {

class OdeSystem;

// Stages 2..S of an explicit Runge-Kutta step of size h from (t, y), stage 1
// in k[0..n): k_i = f(t + c_i h, y + h sum_j a_ij k_j) into k[(i-1) n ..),
// y_stage left holding the last stage's argument. a is S x S row-major.
// See rk_stage_kernels.hpp.
using RkStageKernel = void (*)(OdeSystem& system, const double* a, const double* c, double t,
                               const double* y, double h, double* k, double* y_stage);

// A smooth ODE y' = f(t, y) with optional root (event) functions g(t, y).
class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  virtual int size() const = 0;
  // ydot = f(t, y). Must not allocate.
  virtual void rhs(double t, const double* y, double* ydot) = 0;
  // Number of root functions (0: no root finding).
  virtual int root_count() const { return 0; }
  // g = g(t, y), root_count() values. Must not allocate.
  virtual void roots(double /*t*/, const double* /*y*/, double* /*g*/) {}
  // Number of trailing states that are quadratures: integrals that f does
  // not depend on (the drive's work and loss integrals). Their Jacobian
  // columns are zero, so the implicit methods factor only the leading block
  // of the Newton matrix [[I - g A, 0], [-g B, I]]; the error test still
  // covers them. 0 <= quadrature_count() < size().
  virtual int quadrature_count() const { return 0; }
  // Invariants the right-hand side keeps only through its derivative (a
  // constraint held on the acceleration level): an implicit method's Newton
  // iteration, stopped at its tolerance, lets them drift step by step, and
  // nothing pulls them back. A system that has such invariants projects each
  // accepted step onto them (CVODE's BDF: CVodeSetProjFn): `correction`
  // receives the change of y that puts y back (zeros: none). Must not
  // allocate.
  virtual bool has_projection() const { return false; }
  virtual void project(double /*t*/, const double* /*y*/, double* /*correction*/) {}
  // The stage loop of an explicit Runge-Kutta method of `stage_count` stages
  // with this system's rhs inlined (rk_kernels::stage_kernel_for<Own, N>
  // for a final class Own of size N), or null: the integrator's own loop,
  // one virtual rhs call per stage. The same numbers either way.
  // The loop casts its system argument to Own: call it only with the object
  // that returned it (a wrapper, such as event_driven's RootGuard, must not
  // pass on its inner system's loop; it returns null).
  virtual RkStageKernel explicit_rk_stages(int /*stage_count*/) const { return nullptr; }
};

struct IntegratorOptions {
  double rtol = 1e-8;
  double atol = 1e-10;
  double max_step = 0.0;     // 0: unbounded
  double first_step = 0.0;   // 0: chosen by the integrator
  long max_steps = 1000000;  // total internal steps before SimulationError
  int max_order = 0;         // 0: the method's default (CVODE BDF 5, Adams 12)
  double fixed_step = 0.0;   // > 0: fixed step size where the method supports it
  // Newton iterations per implicit step before a convergence failure (CVODE;
  // 0: its default, 3). Set by a model whose right-hand side is strongly
  // nonlinear on its fast scales (the drive with eq. 3.15's law).
  int max_nonlinear_iterations = 0;
  // The explicit engines' stiffness stop (RK_STIFF: a step held by stability
  // that would not reach t_out within max_steps). Off where t_out is only a
  // bound and a root ends the integration (the regularized law's approach to
  // its fold, hybrid_jamming.cpp: its end in the time s is a sentinel, 1e12
  // times the run's rest, which no step size reaches within any budget).
  bool stop_when_stiff = true;
};

struct IntegratorStats {
  long steps = 0;
  long rhs_evaluations = 0;
  long jacobian_evaluations = 0;
  long root_evaluations = 0;
  long error_test_failures = 0;
  long nonlinear_failures = 0;
  long restarts = 0;  // reinitialize calls
};

enum class AdvanceStatus { reached, root_found };

struct AdvanceResult {
  double t = 0.0;
  AdvanceStatus status = AdvanceStatus::reached;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string name() const = 0;
  // Allocates the workspace for `system` (kept by reference) and sets the
  // initial state.
  virtual void initialize(OdeSystem& system, double t0,
                          const Eigen::Ref<const Eigen::VectorXd>& y0) = 0;
  // Restart from (t0, y0) after a discontinuity (event); no allocation.
  virtual void reinitialize(double t0, const Eigen::Ref<const Eigen::VectorXd>& y0) = 0;
  // Integrate towards t_out, never past it. Stops early at the first root of
  // the system's root functions (then root_info() tells which, with direction
  // +1 rising / -1 falling, 0 not triggered). y receives the state at the
  // returned time. one_step = true returns after one internal step (for
  // output at every step). Throws SimulationError (time, flag name, hint).
  virtual AdvanceResult advance(double t_out, Eigen::Ref<Eigen::VectorXd> y,
                                bool one_step = false) = 0;
  // True if the method's interpolant has the accuracy of its steps, so that
  // output times need not end steps (CVODE: the Nordsieck polynomial of the
  // current order). False: output needs exact stops (a cubic Hermite
  // interpolant of a higher-order Runge-Kutta step is less accurate than the
  // step); advance_to_output then simply stops at t_out.
  virtual bool interpolates_output() const { return false; }
  // Like advance, but the method may step past t_out (never past t_stop >=
  // t_out, the next discontinuity) and returns the state at t_out from its
  // interpolant. A root before t_out ends the call there as in advance.
  // Throws InvalidArgument if t_stop < t_out.
  virtual AdvanceResult advance_to_output(double t_out, double t_stop,
                                          Eigen::Ref<Eigen::VectorXd> y);
  virtual const std::vector<int>& root_info() const = 0;
  virtual IntegratorStats stats() const = 0;
  // The state at t within the last internal step, from the method's dense
  // output (interpolant), without moving the integrator. Throws
  // InvalidArgument if t is outside that step or the method has none.
  virtual void dense_output(double t, Eigen::Ref<Eigen::VectorXd> y);
};

// Names (integrator_names() is the authoritative list):
//   "cvode_bdf"   SUNDIALS CVODE, BDF orders 1-5, Newton + dense LU: stiff problems
//   "cvode_adams" SUNDIALS CVODE, Adams orders 1-12, Newton + dense LU: non-stiff
//   "dopri5"      SUNDIALS ARKODE ERKStep, Dormand-Prince 5(4) (as ode45)
//   "verner6"     SUNDIALS ARKODE ERKStep, Verner 6(5)
//   "rk_dopri5"   the core's own engine (explicit_rk.hpp), Dormand-Prince 5(4)
//   "rk_verner6"  the core's own engine, Verner 6(5)
// The rk_ methods cost a few ns per stage beyond f and ~0.2 us per restart
// (SUNDIALS: ~1 us per step, 10-40 us per restart on 2 states), keep the step
// size across reinitialize and locate roots on the exact step continuation:
// the choice for event-driven, non-stiff phases.
// Common semantics: max_steps counts all steps since initialize (restarts
// included); roots are seen as sign changes between step ends, so a root
// function that depends on t while f is ~0 needs max_step below the spacing
// of its roots; a root function exactly 0 at a (re)start does not report
// that root again. Throws InvalidArgument naming the allowed values for an
// unknown name, or naming an invalid option.
std::unique_ptr<Integrator> make_integrator(const std::string& name,
                                            const IntegratorOptions& options);
const std::vector<std::string>& integrator_names();

// Throws InvalidArgument naming the first invalid option, its value and the
// allowed range (make_integrator calls it; method-specific limits such as
// max_order are checked by the method).
void validate_options(const IntegratorOptions& options);

// The checks make_integrator(name, options) makes beyond validate_options,
// without building the method: the name and the method's own limits
// (max_order of a one-step method, CVODE's order range, fixed_step only for
// the explicit Runge-Kutta methods). Throws InvalidArgument as make_integrator.
void check_method_limits(const std::string& name, const IntegratorOptions& options);

}  // namespace leadscrew::integrate
