// Verner's 6(5) pair for the core's own Runge-Kutta engine ("rk_verner6"),
// with cubic Hermite dense output (order 3; event times come from the exact
// continuation, so they keep the method's accuracy).
#pragma once

#include "leadscrew/integrate/explicit_rk.hpp"

namespace leadscrew::integrate {

// The coefficients are Verner's 6(5) pair as tabulated by SUNDIALS
// (ARKODE_VERNER_8_5_6; the ARKODE documentation gives the source), read from
// the library at run time rather than retyped. The fixed-step order test
// checks order 6, and the tableau checks (row sums, weights) run at load.
const ButcherTableau& verner6_tableau();

}  // namespace leadscrew::integrate
