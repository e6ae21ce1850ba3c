// What the SUNDIALS-based integrators (CVODE, ARKODE ERKStep) share: the
// state vector and callback bridge, restarts without allocation, the total
// step budget, statistics across restarts, and the translation of failure
// flags into SimulationError. Each method supplies the solver calls.
#pragma once

#include <string>
#include <vector>

#include "leadscrew/integrate/ode.hpp"
#include "leadscrew/integrate/sundials_context.hpp"

namespace leadscrew::integrate::sundials {

class SundialsIntegrator : public Integrator {
 public:
  std::string name() const final { return name_; }
  void initialize(OdeSystem& system, double t0,
                  const Eigen::Ref<const Eigen::VectorXd>& y0) final;
  void reinitialize(double t0, const Eigen::Ref<const Eigen::VectorXd>& y0) final;
  AdvanceResult advance(double t_out, Eigen::Ref<Eigen::VectorXd> y, bool one_step = false) final;
  AdvanceResult advance_to_output(double t_out, double t_stop,
                                  Eigen::Ref<Eigen::VectorXd> y) final;
  const std::vector<int>& root_info() const final { return root_info_; }
  IntegratorStats stats() const final;
  // CVodeGetDky / ERKStepGetDky (order 0) within the last internal step.
  void dense_output(double t, Eigen::Ref<Eigen::VectorXd> y) final;

 protected:
  // `explicit_steps`: an explicit method (ERKStep), whose budget is watched
  // (check_budget) where options.stop_when_stiff.
  SundialsIntegrator(std::string name, const IntegratorOptions& options, bool implicit,
                     bool explicit_steps = false);

  // Creates the solver memory for the state in y_ at t0 and applies the options.
  virtual void create_solver(double t0) = 0;
  // Restarts the solver from the state in y_ at t0 without allocating.
  virtual int restart_solver(double t0) = 0;
  // Never step past t_stop; at most max_steps internal steps in this call.
  virtual int limit_solver(double t_stop, long max_steps) = 0;
  // One CVode / ERKStepEvolve call; the state goes to y_.
  virtual int evolve_solver(double t_out, bool one_step, double* t_reached) = 0;
  virtual int solver_root_info(int* info) = 0;
  // The interpolated state at t into v (CVodeGetDky / ERKStepGetDky, k = 0).
  virtual int solver_dense_output(double t, N_Vector v) = 0;
  virtual double solver_time() const = 0;
  // Counters since the last create/restart (SUNDIALS resets them on ReInit).
  virtual IntegratorStats solver_stats() const = 0;
  // The solver's name for a return flag, e.g. "CV_TOO_MUCH_WORK".
  virtual std::string flag_name(int flag) const = 0;
  // Throws SimulationError for a failed setup call (flag < 0).
  void check_setup(int flag, const char* call) const;

  const IntegratorOptions options_;
  Context context_;
  NVector y_;
  NVector work_;  // dense output
  CallbackBridge bridge_;

 private:
  void load_state(double t0, const Eigen::Ref<const Eigen::VectorXd>& y0);
  // advance and advance_to_output: towards t_out, never past t_stop.
  AdvanceResult advance_until(double t_out, double t_stop, Eigen::Ref<Eigen::VectorXd> y,
                              bool one_step);
  // One evolve towards t_out within what max_steps leaves (an explicit
  // method's in pieces, stopped where the rest cannot fit the budget).
  int evolve_within_budget(double t_out, double t_stop, bool one_step, double* t_reached);
  // An explicit method's watch on its budget (ARK_STIFF where the rest to
  // t_stop cannot fit it).
  void check_budget(double t_stop, double t_now);
  static constexpr long kBudgetPiece = 10000;

  const std::string name_;
  const bool implicit_;
  const bool watch_budget_;
  bool initialized_ = false;
  double t_ = 0.0;
  std::vector<int> root_info_;
  IntegratorStats before_restart_;  // counters of the solver runs before the last restart
  long budget_mark_steps_ = 0;  // check_budget's last piece: its end's steps and time
  double budget_mark_time_ = 0.0;
  int short_pieces_ = 0;
  long restarts_ = 0;
};

}  // namespace leadscrew::integrate::sundials
