// Dormand-Prince 5(4) for the core's own Runge-Kutta engine ("rk_dopri5"):
// the pair of ode45 / RK45, with Shampine's continuous extension of order 4.
#pragma once

#include "leadscrew/integrate/explicit_rk.hpp"

namespace leadscrew::integrate {

// J. R. Dormand, P. J. Prince, "A family of embedded Runge-Kutta formulae",
// J. Comput. Appl. Math. 6 (1980) 19-26, table 2 (RK5(4)7M); the dense output
// is that of L. F. Shampine, "Some practical Runge-Kutta formulas", Math.
// Comp. 46 (1986) 135-150, in the form of Hairer, Norsett & Wanner, Solving
// ODE I, II.6 (eq. 6.12).
const ButcherTableau& dopri5_tableau();

}  // namespace leadscrew::integrate
