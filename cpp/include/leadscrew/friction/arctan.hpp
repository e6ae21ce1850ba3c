// arctan for the regularized friction laws (eq. 2.25, 3.15, 3.16): the same
// values as std::atan to within rounding, at about half of glibc's latency.
//
// Why: the arctan of the slip velocity (eq. 3.16) or of the slip
// acceleration (eq. 3.15) is evaluated in every right-hand side, and each
// Runge-Kutta stage waits for it. glibc's atan (correctly rounded in
// practice) switches the rounding mode on entry and exit and runs a table
// method with an accuracy test; it costs ~30 ns of latency, the larger part
// of a right-hand side of the friction block.
//
// Method (the classical one of Cody & Waite, "Software manual for the
// elementary functions", ch. 11): with a = |x|,
//   a < 7/16:              atan(a) = a - a q(a^2)
//   7/16  <= a < 11/16:    atan(a) = atan(1/2) + atan(t),  t = (2a - 1)/(2 + a)
//   11/16 <= a < 19/16:    atan(a) = pi/4      + atan(t),  t = (a - 1)/(a + 1)
//   19/16 <= a < 39/16:    atan(a) = atan(3/2) + atan(t),  t = (2a - 3)/(2 + 3a)
//   39/16 <= a < 2^66:     atan(a) = pi/2      + atan(t),  t = -1/a
// so that |t| <= 7/16 everywhere, and atan(t) = t - t s P(s), s = t^2, with
// P of degree 11 (coefficients: Chebyshev fit of (t - atan t)/t^3 on
// s in [0, (7/16)^2], computed for this code with mpmath at 50 digits; fit
// error 4e-18, with the coefficients rounded to double 6e-17 relative to P).
// The constants atan(c) are split hi + lo (double-double).
//
// Error bound (u = 2^-53, vs the exact arctan; checked densely against
// std::atan and at random points against mpmath in
// tests/test_friction_arctan.py):
//  - t: the numerators 2a - 1, a - 1, 2a - 3 are exact (Sterbenz: a lies
//    within a factor 2 of the subtracted constant); the denominators and the
//    division add rounding: t = T (1 + d), |d| <= 2u (c = 1/2, 1), 3u
//    (c = 3/2), u (c = inf), 0 (a < 7/16). atan(t) - atan(T) <= |T| |d|.
//  - atan(t): fit 0.03 u |t|, evaluation of t s P(s) (<= 0.064 |t|) ~6u of
//    it, the two subtractions u |t|; the final addition 0.5 ulp.
//  Per region, with |t| max and ulp(result) over it, that is at most
//  0.98, 0.98, 1.15, 1.01, 1.01 ulp (a < 7/16 ... a >= 39/16).
// Exactly: atan(+-0) = +-0, subnormal x give x (|atan x - x| < |x|^3),
// |x| >= 2^66 and +-inf give +-pi/2 (rounded), NaN gives NaN.
//
// Plain + and * only (no std::fma: without -mfma it is a library call):
// the same bits on every x86-64 build without FMA contraction.
#pragma once

#include <cmath>

namespace leadscrew::friction {

inline double arctan(double x) {
  const double a = std::fabs(x);
  if (!(a < 0x1p66)) {
    if (std::isnan(x)) return x + x;
    return std::copysign(0x1.921fb54442d18p+0, x);  // pi/2 rounded: atan(2^66) rounds to it
  }
  if (a < 0x1p-27) return x;  // |atan x - x| <= |x|^3 / 3 < 2^-55 |x|: rounds to x
  double t, hi, lo;
  bool reduced = true;
  if (a < 0.4375) {
    t = a;
    hi = lo = 0.0;
    reduced = false;
  } else if (a < 0.6875) {
    t = (2.0 * a - 1.0) / (2.0 + a);
    hi = 0x1.dac670561bb4fp-2;  // atan(1/2)
    lo = 0x1.a2b7f222f65e2p-56;
  } else if (a < 1.1875) {
    t = (a - 1.0) / (a + 1.0);
    hi = 0x1.921fb54442d18p-1;  // pi/4
    lo = 0x1.1a62633145c07p-55;
  } else if (a < 2.4375) {
    t = (2.0 * a - 3.0) / (2.0 + 3.0 * a);
    hi = 0x1.f730bd281f69bp-1;  // atan(3/2)
    lo = 0x1.007887af0cbbdp-56;
  } else {
    t = -1.0 / a;
    hi = 0x1.921fb54442d18p+0;  // pi/2
    lo = 0x1.1a62633145c07p-54;
  }
  // P(s) by Estrin's scheme: four levels instead of eleven dependent steps.
  const double s = t * t;
  const double s2 = s * s;
  const double s4 = s2 * s2;
  const double s8 = s4 * s4;
  const double p01 = 0x1.5555555555555p-2 + s * -0x1.99999999998c5p-3;
  const double p23 = 0x1.2492492485503p-3 + s * -0x1.c71c71bd2b8bcp-4;
  const double p45 = 0x1.745d154c84f7ap-4 + s * -0x1.3b1375ce5bdc6p-4;
  const double p67 = 0x1.110c9ce7b0572p-4 + s * -0x1.e170800a46210p-5;
  const double p89 = 0x1.ab59b417b2d3fp-5 + s * -0x1.7001816fd063fp-5;
  const double p1011 = 0x1.0f62bba6a2558p-5 + s * -0x1.e4167464d3de8p-7;
  const double p = (p01 + s2 * p23) + s4 * (p45 + s2 * p67) + s8 * (p89 + s2 * p1011);
  const double correction = (t * s) * p;  // t - atan(t)
  const double value = reduced ? hi - ((correction - lo) - t) : t - correction;
  return std::copysign(value, x);
}

}  // namespace leadscrew::friction
