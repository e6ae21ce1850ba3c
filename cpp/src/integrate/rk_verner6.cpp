#include "leadscrew/integrate/rk_verner6.hpp"

#include <arkode/arkode_butcher_erk.h>

#include "leadscrew/core/errors.hpp"

namespace leadscrew::integrate {

namespace {
ButcherTableau make_verner6() {
  ARKodeButcherTable table = ARKodeButcherTable_LoadERK(ARKODE_VERNER_8_5_6);
  if (!table || !table->d)
    throw SimulationError(0.0, "ARKodeButcherTable_LoadERK failed for ARKODE_VERNER_8_5_6",
                          "check the SUNDIALS installation");
  ButcherTableau t;
  t.name = "rk_verner6";
  t.stages = table->stages;
  t.order = table->q;
  t.embedded_order = table->p;
  t.fsal = false;  // c_s = 1 but the last row of a is not b
  const int s = t.stages;
  t.a.assign(static_cast<std::size_t>(s) * s, 0.0);
  t.b.resize(s);
  t.e.resize(s);
  t.c.resize(s);
  for (int i = 0; i < s; ++i) {
    for (int j = 0; j < i; ++j) t.a[i * s + j] = table->A[i][j];
    t.b[i] = table->b[i];
    t.e[i] = table->b[i] - table->d[i];
    t.c[i] = table->c[i];
  }
  ARKodeButcherTable_Free(table);
  t.dense_weights = &hermite_dense_weights;
  return t;
}
}  // namespace

const ButcherTableau& verner6_tableau() {
  static const ButcherTableau tableau = checked_tableau(make_verner6());
  return tableau;
}

}  // namespace leadscrew::integrate
