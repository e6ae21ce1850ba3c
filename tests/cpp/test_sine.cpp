// Native check of leadscrew::excitation::sine (cpp/include/leadscrew/excitation/sine.hpp)
// against std::sin, built and run by tests/test_excitation_sine.py.
//
// Prints
//   MAXULP <set> <max ulp distance to std::sin> <points> <worst x (hex)>
//   SPECIAL <name> PASS|FAIL
//   SAMPLE <x (hex)> <sine(x) (hex)>   (for the mpmath check in Python)
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "leadscrew/excitation/sine.hpp"
#include "ulp_sweep.hpp"

namespace {

using leadscrew::excitation::sine;
using namespace ulp_sweep;

constexpr double kReductionBound = 0x1p18;  // sine.hpp: own reduction below it
constexpr double kHalfPi = 0x1.921fb54442d18p+0;

// The double nearest to k pi/2 (to within an ulp: the sweeps around it go far
// beyond): k (P1 + P2) with the 35-bit parts of sine.hpp is exact to 2^-70 k.
double near_multiple(long k) {
  const double kd = static_cast<double>(k);
  return kd * 0x1.921fb54440000p+0 + kd * 0x1.68c234c4c0000p-39;
}

const auto ours = [](double x) { return sine(x); };
const auto reference = [](double x) { return std::sin(x); };

}  // namespace

int main() {
  std::mt19937_64 random(20130601);

  // Every binade below the reduction bound (subnormals included), both signs:
  // 1024 evenly spaced mantissas and 2048 random ones each (6.4 million
  // points); the binades above it (std::sin itself) sparsely.
  Worst binades("binades", ours, reference);
  const std::uint64_t bound_exponent = 1023 + 18;
  binades.every_binade(
      [&](std::uint64_t exponent) { return exponent < bound_exponent ? 3072 : 16; },
      [&](std::uint64_t j) {
        return j < 1024 ? (j << 42) | (j * 0x9E3779B97F4A7C15ull >> 54) : random() >> 12;
      });
  binades.print();

  // The working range of the loads (omega t + phase up to a few hundred
  // rad), densely, and the whole reduced range uniformly.
  Worst dense("dense", ours, reference);
  std::uniform_real_distribution<double> working(-400.0, 400.0);
  for (int i = 0; i < 3000000; ++i) dense.check(working(random));
  std::uniform_real_distribution<double> reduced(-kReductionBound, kReductionBound);
  for (int i = 0; i < 1000000; ++i) dense.check(reduced(random));
  dense.print();

  // The hardest reductions: consecutive doubles around multiples of pi/2,
  // where r = x - k pi/2 cancels. Every k up to 2000 (2000 doubles each),
  // every 16th k up to the bound (40 each), and the k with the closest
  // approaches of doubles to k pi/2 below 2^18 (29, 28958, 58654: found with
  // mpmath; 226 and 452 for x near 355 and 710), 200000 doubles each.
  Worst multiples("multiples", ours, reference);
  for (long k = 1; k <= 2000; ++k) multiples.around(near_multiple(k), 500);
  const long k_max = static_cast<long>(kReductionBound / kHalfPi);
  for (long k = 2001; k <= k_max; k += 16) multiples.around(near_multiple(k), 10);
  for (const long k : {29L, 226L, 452L, 28958L, 58654L, k_max})
    multiples.around(near_multiple(k), 50000);
  multiples.print();

  // Branch points: the bounds 2^-26 and 2^18, and the quadrant switches at
  // odd multiples of pi/4 (where k is rounded either way).
  Worst edges("edges", ours, reference);
  for (const double edge : {0x1p-26, 0x1p18}) edges.around(edge, 20000);
  for (long j = 0; j < 400; ++j) edges.around((2 * j + 1) * 0.5 * kHalfPi, 500);
  edges.print();

  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  special("plus_zero", same_bits(sine(0.0), 0.0));
  special("minus_zero", same_bits(sine(-0.0), -0.0));
  special("plus_inf", std::isnan(sine(inf)));
  special("minus_inf", std::isnan(sine(-inf)));
  special("nan", std::isnan(sine(nan)) && std::isnan(sine(-nan)));
  special("max", same_bits(sine(std::numeric_limits<double>::max()),
                           std::sin(std::numeric_limits<double>::max())));
  bool subnormals = true;
  for (const double x : {std::numeric_limits<double>::denorm_min(), 0x1.8p-1060, 0x1.fffffp-1023,
                         std::numeric_limits<double>::min(), 0x1.fffffffffffffp-27})
    subnormals = subnormals && same_bits(sine(x), x) && same_bits(sine(-x), -x);
  special("subnormal_and_tiny_identity", subnormals);
  special("odd", [&] {
    std::uniform_real_distribution<double> exponent(-30.0, 18.0);
    for (int i = 0; i < 200000; ++i) {
      const double x = std::exp2(exponent(random));
      if (!same_bits(sine(-x), -sine(x))) return false;
    }
    return true;
  }());
  special("range", [&] {
    // |sin| <= 1 exactly, and sin(pi/2 double) rounds to 1.
    for (int i = 0; i < 200000; ++i)
      if (!(std::fabs(sine(reduced(random))) <= 1.0)) return false;
    return sine(kHalfPi) == 1.0 && sine(-kHalfPi) == -1.0;
  }());
  special("monotonic_across_quadrant_switches", [] {
    // sin rises on (-pi/2, pi/2) + 2 m pi and falls on (pi/2, 3 pi/2) + 2 m pi:
    // consecutive doubles around the switches (2j+1) pi/4 keep the order.
    for (long j = 0; j < 400; ++j) {
      const double center = (2 * j + 1) * 0.5 * kHalfPi;
      // (2j+1) pi/4 lies in a rising stretch for j mod 4 in {0, 3}.
      const bool rising = (j % 4 == 0) || (j % 4 == 3);
      if (!monotonic_around(ours, center, 2000, rising)) return false;
    }
    return true;
  }());

  // Points for the comparison with the exact sin (mpmath): log-uniform
  // magnitudes, both signs; the working range; the hardest reductions.
  log_uniform_samples(ours, random, -30.0, 18.0, 3000);
  uniform_samples(ours, random, -8.0, 8.0, 2000);
  for (const long k : {1L, 2L, 3L, 4L, 29L, 226L, 452L, 28958L, 58654L, k_max})
    samples_around(ours, near_multiple(k), 20);
  return 0;
}
