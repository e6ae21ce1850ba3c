// ARKODE (SUNDIALS) ERKStep: explicit embedded Runge-Kutta pairs with
// adaptive (or fixed) steps and Hermite dense output for root finding.
//
//   "dopri5":    Dormand-Prince 5(4), 7 stages (FSAL), the method of MATLAB's
//                ode45 and scipy's RK45.
//   "verner6":   Verner 6(5), 8 stages.
// ARKODE's Fehlberg 8(7) is left out on purpose: its error estimate is zero
// whenever f depends on t only, so it is unreliable on forced systems (see
// integrator_names()).
// Explicit: for non-stiff problems (a stiff one exhausts max_steps; the hint
// then says to use cvode_bdf).
#pragma once

#include <arkode/arkode_erkstep.h>

#include "leadscrew/integrate/sundials_integrator.hpp"

namespace leadscrew::integrate {

class ArkodeErkIntegrator final : public sundials::SundialsIntegrator {
 public:
  enum class Method { dopri5, verner6 };
  // Throws InvalidArgument for options the method cannot honour (max_order).
  ArkodeErkIntegrator(Method method, const IntegratorOptions& options);
  // The constructor's checks of `options` for `method`, without building it.
  static void check_options(Method method, const IntegratorOptions& options);
  // Classical order of the propagated solution.
  static int order(Method method);

 private:
  void create_solver(double t0) override;
  int restart_solver(double t0) override;
  int limit_solver(double t_stop, long max_steps) override;
  int evolve_solver(double t_out, bool one_step, double* t_reached) override;
  int solver_root_info(int* info) override;
  int solver_dense_output(double t, N_Vector v) override;
  double solver_time() const override;
  IntegratorStats solver_stats() const override;
  std::string flag_name(int flag) const override;

  const Method method_;
  sundials::SolverMemory<ERKStepFree> memory_;
};

}  // namespace leadscrew::integrate
