#include "leadscrew/integrate/arkode_erk.hpp"

#include <arkode/arkode_butcher_erk.h>

#include <cstdlib>
#include <memory>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/integrate/integrator_checks.hpp"

namespace leadscrew::integrate {

namespace {
const char* method_name(ArkodeErkIntegrator::Method method) {
  switch (method) {
    case ArkodeErkIntegrator::Method::dopri5:
      return "dopri5";
    case ArkodeErkIntegrator::Method::verner6:
      return "verner6";
  }
  return "";
}

ARKODE_ERKTableID table(ArkodeErkIntegrator::Method method) {
  switch (method) {
    case ArkodeErkIntegrator::Method::dopri5:
      return ARKODE_DORMAND_PRINCE_7_4_5;
    case ArkodeErkIntegrator::Method::verner6:
      return ARKODE_VERNER_8_5_6;
  }
  return ARKODE_ERK_NONE;
}
struct ButcherTableDeleter {
  void operator()(ARKodeButcherTable b) const noexcept { ARKodeButcherTable_Free(b); }
};
using ButcherTable =
    std::unique_ptr<std::remove_pointer_t<ARKodeButcherTable>, ButcherTableDeleter>;

// SUNDIALS <= 6.5 ERKStep treats every table whose last node is c_s = 1 as
// "first same as last" and reuses the last stage as f(t_n+1, y_n+1) even when
// the last row of A is not b (llnl/sundials issue #311, fixed in 6.6). That
// silently drops Verner 6(5) to order 3 (and Fehlberg 8(7) to order 7), as
// the fixed-step order tests show. Appending a stage with node 0 and zero
// weights (it evaluates f(t_n, y_n) once more) keeps the method unchanged and
// makes c_s != 1, so the end-of-step derivative is evaluated afresh. Tables
// that are FSAL (Dormand-Prince) are used as they are.
ButcherTable load_table(ARKODE_ERKTableID id) {
  ButcherTable table(ARKodeButcherTable_LoadERK(id));
  if (!table) return table;
  const int s = table->stages;
  bool fsal = table->c[s - 1] == 1.0;
  for (int j = 0; j < s && fsal; ++j) fsal = table->A[s - 1][j] == table->b[j];
  if (fsal || table->c[s - 1] != 1.0) return table;
  ButcherTable padded(ARKodeButcherTable_Alloc(s + 1, table->d != nullptr));
  if (!padded) return padded;
  padded->q = table->q;
  padded->p = table->p;
  for (int i = 0; i < s; ++i) {
    padded->c[i] = table->c[i];
    padded->b[i] = table->b[i];
    if (table->d) padded->d[i] = table->d[i];
    for (int j = 0; j < s; ++j) padded->A[i][j] = table->A[i][j];
  }
  padded->c[s] = 0.0;
  padded->b[s] = 0.0;
  if (table->d) padded->d[s] = 0.0;
  for (int j = 0; j <= s; ++j) padded->A[s][j] = 0.0;
  for (int i = 0; i < s; ++i) padded->A[i][s] = 0.0;
  return padded;
}
}  // namespace

int ArkodeErkIntegrator::order(Method method) {
  switch (method) {
    case Method::dopri5:
      return 5;
    case Method::verner6:
      return 6;
  }
  return 0;
}

ArkodeErkIntegrator::ArkodeErkIntegrator(Method method, const IntegratorOptions& options)
    : SundialsIntegrator(method_name(method), options, false, true), method_(method) {
  check_options(method, options);
}

void ArkodeErkIntegrator::check_options(Method method, const IntegratorOptions& options) {
  check_fixed_order(options, method_name(method), order(method));
}

void ArkodeErkIntegrator::create_solver(double t0) {
  memory_.reset();
  memory_ = sundials::SolverMemory<ERKStepFree>(
      ERKStepCreate(&sundials::CallbackBridge::rhs, t0, y_.get(), context_.get()));
  void* mem = memory_.get();
  if (!mem)
    throw SimulationError(t0, "ERKStepCreate failed: ARKODE could not allocate its memory",
                          "the machine is out of memory");
  check_setup(ERKStepSetErrHandlerFn(mem, &sundials::CallbackBridge::error_handler, &bridge_),
              "ERKStepSetErrHandlerFn");
  check_setup(ERKStepSetUserData(mem, &bridge_), "ERKStepSetUserData");
  {
    const ButcherTable butcher = load_table(table(method_));
    if (!butcher) check_setup(-20, "ARKodeButcherTable_LoadERK");
    check_setup(ERKStepSetTable(mem, butcher.get()), "ERKStepSetTable");  // copies the table
  }
  check_setup(ERKStepSStolerances(mem, options_.rtol, options_.atol), "ERKStepSStolerances");
  if (options_.fixed_step > 0.0)
    check_setup(ERKStepSetFixedStep(mem, options_.fixed_step), "ERKStepSetFixedStep");
  if (options_.max_step > 0.0)
    check_setup(ERKStepSetMaxStep(mem, options_.max_step), "ERKStepSetMaxStep");
  if (options_.first_step > 0.0)
    check_setup(ERKStepSetInitStep(mem, options_.first_step), "ERKStepSetInitStep");
  check_setup(ERKStepSetMaxHnilWarns(mem, -1), "ERKStepSetMaxHnilWarns");
  if (bridge_.root_count > 0) {
    check_setup(ERKStepRootInit(mem, bridge_.root_count, &sundials::CallbackBridge::roots),
                "ERKStepRootInit");
    check_setup(ERKStepSetNoInactiveRootWarn(mem), "ERKStepSetNoInactiveRootWarn");
  }
}

int ArkodeErkIntegrator::restart_solver(double t0) {
  return ERKStepReInit(memory_.get(), &sundials::CallbackBridge::rhs, t0, y_.get());
}

int ArkodeErkIntegrator::limit_solver(double t_stop, long max_steps) {
  const int flag = ERKStepSetStopTime(memory_.get(), t_stop);
  if (flag < 0) return flag;
  return ERKStepSetMaxNumSteps(memory_.get(), max_steps);
}

int ArkodeErkIntegrator::evolve_solver(double t_out, bool one_step, double* t_reached) {
  sunrealtype t = 0.0;
  const int flag =
      ERKStepEvolve(memory_.get(), t_out, y_.get(), &t, one_step ? ARK_ONE_STEP : ARK_NORMAL);
  *t_reached = t;
  return flag;
}

int ArkodeErkIntegrator::solver_root_info(int* info) {
  return ERKStepGetRootInfo(memory_.get(), info);
}

int ArkodeErkIntegrator::solver_dense_output(double t, N_Vector v) {
  return ERKStepGetDky(memory_.get(), t, 0, v);
}

// After a failure this is the time of the stage where the step failed (ARKODE
// keeps no accessible record of the last accepted time; a post-step hook
// would give it but costs the FSAL reuse, one rhs call per step).
double ArkodeErkIntegrator::solver_time() const {
  sunrealtype t = 0.0;
  ERKStepGetCurrentTime(memory_.get(), &t);
  return t;
}

IntegratorStats ArkodeErkIntegrator::solver_stats() const {
  void* mem = memory_.get();
  IntegratorStats s;
  if (!mem) return s;
  long nst = 0, nfe = 0, netf = 0, nge = 0;
  ERKStepGetNumSteps(mem, &nst);
  ERKStepGetNumRhsEvals(mem, &nfe);
  ERKStepGetNumErrTestFails(mem, &netf);
  if (bridge_.root_count > 0) ERKStepGetNumGEvals(mem, &nge);
  s.steps = nst;
  s.rhs_evaluations = nfe;
  s.root_evaluations = nge;
  s.error_test_failures = netf;
  return s;
}

std::string ArkodeErkIntegrator::flag_name(int flag) const {
  char* name = ERKStepGetReturnFlagName(flag);  // malloc'ed by SUNDIALS
  std::string result = name ? name : "ARK_UNKNOWN_FLAG";
  std::free(name);
  return result;
}

}  // namespace leadscrew::integrate
