// CVODE (SUNDIALS) variable-order, variable-step multistep methods.
//
//   "cvode_bdf":   BDF orders 1..5, Newton iteration with a dense direct linear
//                  solver and a finite-difference Jacobian: for stiff problems
//                  (regularized friction with a steep slope, stiff contacts).
//   "cvode_adams": Adams-Moulton orders 1..12, also with Newton iteration (see
//                  cvode.cpp for why not fixed-point): for non-stiff problems
//                  (its small stability regions make it slow on stiff ones).
#pragma once

#include <cvode/cvode.h>

#include "leadscrew/integrate/sundials_integrator.hpp"

namespace leadscrew::integrate {

class CvodeIntegrator final : public sundials::SundialsIntegrator {
 public:
  enum class Method { bdf, adams };
  // Throws InvalidArgument for options the method cannot honour (fixed_step,
  // max_order above 5 for BDF / 12 for Adams).
  CvodeIntegrator(Method method, const IntegratorOptions& options);
  // The constructor's checks of `options` for `method`, without building it.
  static void check_options(Method method, const IntegratorOptions& options);
  // CVODE returns output at a time behind its last step from the Nordsieck
  // array, the polynomial of the current order (CV_NORMAL past tout).
  bool interpolates_output() const override { return true; }

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

  // Difference-quotient Jacobian (CVODE's formula; its built-in one
  // allocates a vector header on every evaluation).
  static int difference_jacobian(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix jacobian,
                                 void* user_data, N_Vector tmp1, N_Vector tmp2, N_Vector tmp3);

  const Method method_;
  long jacobian_rhs_ = 0;  // rhs calls of difference_jacobian since the last (re)start
  // Declared before the memory that uses them: CVODE's memory is freed first
  // (members are destroyed in reverse order, the base's context last).
  sundials::Matrix matrix_;
  sundials::LinearSolver linear_solver_;
  sundials::SolverMemory<CVodeFree> memory_;
};

}  // namespace leadscrew::integrate
