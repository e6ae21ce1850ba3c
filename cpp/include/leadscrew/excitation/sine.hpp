// sin for the sine excitation F(t) = V sin(omega t + phase) + offset (the
// load of the friction block, eq. 3.9, and of the drives): the same values as
// std::sin to within rounding, without glibc's call and its slow paths.
//
// Why: every right-hand side of a sine-loaded model evaluates the load once
// per Runge-Kutta stage; a profile of the block with the arctan velocity law
// (eq. 3.16, rk_dopri5) put glibc's sin at ~15 % of all instructions. (The
// load depends on t only, so the processor overlaps much of it with the
// state's chain: measured, this made the block 2-6 % faster, while this
// sine has ~0.7 of glibc's latency and ~0.5 of its cost per call.)
//
// Method, for |x| < 2^18 (beyond that, and for inf and NaN, std::sin):
//  1. k = nearest integer to x 2/pi (the 1.5 * 2^52 shifter; the low bits of
//     the shifted value are k, the quadrant is k mod 4);
//  2. r = x - k pi/2 by Cody & Waite ("Software manual for the elementary
//     functions", ch. 8) with pi/2 = P1 + P2 + P3: P1 and P2 carry 35
//     significant bits each, so that k P1 and k P2 (|k| < 2^18) are exact
//     products, P3 is the next 53 bits; x - k P1 is exact (both are multiples
//     of ulp(x) <= 2^-35 and the difference is below 1 < 2^53 ulp(x));
//     hi = x - k P1 - k P2 rounded, lo = its exact rounding error - k P3
//     rounded: r = hi + lo goes into the polynomials;
//  3. with z = hi^2 and (q = k mod 4) sin(x) = sin r, cos r, -sin r, -cos r:
//       sin(hi + lo) = hi + (hi z S(z) + lo (1 - z/2))
//       cos(hi + lo) = (1 - z/2) + (z^2 C(z) - lo hi)
//     where 1 - z/2 is split into its rounded value and its exact rounding
//     error, and S (degree 6) and C (degree 5) are Chebyshev fits of
//     (sin r - r)/r^3 and (cos r - 1 + r^2/2)/r^4 on r^2 in [0, 0.7854^2]
//     (pi/4 plus the slack of the rounded k), computed for this code with
//     mpmath at 50 digits from the Taylor series.
//
// Error bound (u = 2^-53; checked in tests/test_excitation_sine.py against
// std::sin densely and against mpmath):
//  - Reduction: |r - (x - k pi/2)| <= |k| |pi/2 - P1 - P2 - P3| (2^-130.4 |k|)
//    + rounding of k P3 (half an ulp of a number below 2^-58) + rounding of
//    its sum with hi's error e (|e| <= ulp(hi)/2): <= 2^-110 + 2^-106 |r|.
//    The smallest |r| over all doubles |x| < 2^18 is 2^-60.5 (x = 45.553093477052, k = 29;
//    found by going through every k with mpmath), and over every k the
//    reduction error is at most 0.003 ulp of sin x. (With 33-bit P1, P2 up to
//    2^20 the same count gives 11 ulp: hence the bound 2^18.)
//  - Polynomials: fit with the coefficients rounded to double, relative to
//    the result: sin 2^-57.3 (0.05 ulp), cos 2^-60 (0.01 ulp).
//  - Evaluation, to first order: sin: ~4 roundings on hi z S(z)
//    (<= 0.081 at |hi| = pi/4), 0.33 ulp of sin(pi/4), lo (cos hi - 1 + z/2)
//    and lo^2 dropped (< 0.001 ulp) and the final addition 0.5 ulp: 0.9 ulp;
//    cos: the rounding of z = hi^2 enters 1 - z/2 with weight 1/2 (0.31 ulp at
//    |hi| = pi/4), ~4 roundings on z^2 C(z) (<= 0.016: 0.06 ulp) and the
//    final addition 0.5 ulp: 0.88 ulp. So 0.95 ulp of the exact sin in all.
//    Where |lo| comes near |hi| (|r| < 2^-50, hi + lo is not renormalized)
//    the terms in z are below 2^-100 |r|: the result is hi + lo rounded.
//    Observed: 0.73 ulp at most (5400 points against mpmath).
// Exactly: sin(+-0) = +-0; |x| < 2^-26 (subnormals included) gives x
// (|sin x - x| < |x|^3/6 < ulp(x)/6); NaN gives NaN, +-inf NaN (as std::sin,
// which also sets errno and FE_INVALID).
//
// Plain + and * only (no std::fma: without -mfma it is a library call): the
// same bits on every x86-64 build without FMA contraction.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

namespace leadscrew::excitation {

inline double sine(double x) {
  const double magnitude = std::fabs(x);
  if (!(magnitude < 0x1p18)) return std::sin(x);  // large, inf, NaN: glibc's full reduction
  if (magnitude < 0x1p-26) return x;              // sin x rounds to x; keeps the sign of zero

  // 1. k and the quadrant. |x 2/pi| < 2^18 << 2^51: adding 1.5 * 2^52 rounds
  //    to the nearest integer, which stands in the low mantissa bits.
  constexpr double shifter = 0x1.8p52;
  const double shifted = x * 0x1.45f306dc9c883p-1 + shifter;  // x * 2/pi
  const double k = shifted - shifter;
  std::uint64_t shifted_bits = 0;
  std::memcpy(&shifted_bits, &shifted, sizeof shifted);
  const unsigned quadrant = static_cast<unsigned>(shifted_bits) & 3u;

  // 2. r = x - k pi/2 = hi + lo, hi = t - k P2 rounded.
  constexpr double pio2_1 = 0x1.921fb54440000p+0;  // 35 bits
  constexpr double pio2_2 = 0x1.68c234c4c0000p-39;  // the next 35 bits
  constexpr double pio2_3 = 0x1.98a2e03707345p-77;  // the next 53 bits
  const double t = x - k * pio2_1;                  // exact
  const double w = k * pio2_2;                      // exact
  const double hi = t - w;
  // Exact error of hi: Dekker's fast two-sum where |t| >= |w|; otherwise
  // |t - w| < 2 |w| < 2^-20 is a multiple of 2^-73 (the last bit of P2),
  // so hi is exact and this gives 0.
  const double hi_error = (t - hi) - w;
  // |lo| <= ulp(hi)/2 + 2^-58: not renormalized against hi (|hi| can be
  // below 2^-58), which the polynomials below do not need.
  const double lo = hi_error - k * pio2_3;

  // 3. The polynomials (Estrin: short dependency chains) and the quadrant's
  //    one; compilers turn the choice into a branch, well predicted where
  //    successive calls (Runge-Kutta stages) lie close together.
  const double z = hi * hi;
  const double z2 = z * z;
  const double z4 = z2 * z2;
  const double sin_poly =
      (-0x1.5555555555555p-3 + z * 0x1.1111111111110p-7) +
      z2 * (-0x1.a01a01a019938p-13 + z * 0x1.71de3a5460946p-19) +
      z4 * ((-0x1.ae645412c3273p-26 + z * 0x1.61217f09bcb04p-33) + z2 * -0x1.ab17d2facc8bdp-41);
  const double cos_poly =
      (0x1.5555555555555p-5 + z * -0x1.6c16c16c16967p-10) +
      z2 * (0x1.a01a019f4eaf1p-16 + z * -0x1.27e4fa17d8c71p-22) +
      z4 * (0x1.1eeb68e7eb073p-29 + z * -0x1.907da2754caa9p-37);
  const double half_z = 0.5 * z;  // exact
  const double one_minus_half_z = 1.0 - half_z;
  const double one_minus_half_z_error = (1.0 - one_minus_half_z) - half_z;  // exact (|half_z| < 1)
  const double sin_r = hi + ((hi * z) * sin_poly + lo * one_minus_half_z);
  const double cos_r = one_minus_half_z + ((z2 * cos_poly + one_minus_half_z_error) - lo * hi);
  const double value = (quadrant & 1u) ? cos_r : sin_r;
  return (quadrant & 2u) ? -value : value;
}

}  // namespace leadscrew::excitation
