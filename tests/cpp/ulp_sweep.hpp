// Harness of the native checks of the core's own elementary functions
// against the C library (tests/cpp/test_sine.cpp; the own arctan's check was
// removed with it in issue 18), built and run by tests/test_excitation_sine.py
// (tests/helpers/native_program.py puts this directory on the include path).
//
// Output lines, parsed by tests/helpers/native_program.py:
//   MAXULP <set> <max ulp distance to the reference> <points> <worst x (hex)>
//   SPECIAL <name> PASS|FAIL
//   SAMPLE <x (hex)> <ours(x) (hex)>   (for the mpmath check in Python)
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

namespace ulp_sweep {

// Doubles mapped to integers that are consecutive in the order of the reals
// (+0 and -0 both to 0): the difference is the distance in ulps.
inline std::int64_t ordered(double x) {
  std::int64_t i = 0;
  std::memcpy(&i, &x, sizeof x);
  return i < 0 ? std::numeric_limits<std::int64_t>::min() - i : i;
}

inline double from_bits(std::uint64_t bits) {
  double x = 0.0;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

inline void special(const char* name, bool ok) {
  std::printf("SPECIAL %s %s\n", name, ok ? "PASS" : "FAIL");
}

// The largest ulp distance between `ours` and `reference` (callables
// double -> double) over the points checked, and where it occurs; a NaN on
// one side only counts as the largest distance there is.
template <class Ours, class Reference>
struct Worst {
  const char* name;
  Ours ours;
  Reference reference;
  std::int64_t ulps = 0;
  long points = 0;
  double x = 0.0;

  Worst(const char* set_name, Ours ours_function, Reference reference_function)
      : name(set_name), ours(ours_function), reference(reference_function) {}

  void check(double x_value) {
    const double value = ours(x_value), expected = reference(x_value);
    std::int64_t distance = ordered(value) - ordered(expected);
    if (distance < 0) distance = -distance;
    if (std::isnan(value) != std::isnan(expected))
      distance = std::numeric_limits<std::int64_t>::max();
    if (distance > ulps) {
      ulps = distance;
      x = x_value;
    }
    ++points;
  }
  // Every binade of the double range (exponent fields 0 to 2046, subnormals
  // included), both signs: count(exponent field) points each, the j-th with
  // the mantissa bits mantissa(j).
  template <class Count, class Mantissa>
  void every_binade(Count count, Mantissa mantissa) {
    for (std::uint64_t exponent = 0; exponent < 2047; ++exponent)
      for (std::uint64_t sign = 0; sign < 2; ++sign)
        for (std::uint64_t j = 0, n = count(exponent); j < n; ++j)
          check(from_bits(sign << 63 | exponent << 52 | mantissa(j)));
  }
  // n consecutive doubles on either side of `center`, both signs.
  void around(double center, int n) {
    for (const double sign : {1.0, -1.0}) {
      double x_value = sign * center;
      for (int i = 0; i < n; ++i) x_value = std::nextafter(x_value, 0.0);
      for (int i = 0; i < 2 * n; ++i, x_value = std::nextafter(x_value, sign * INFINITY))
        check(x_value);
    }
  }
  void print() const {
    std::printf("MAXULP %s %lld %ld %a\n", name, static_cast<long long>(ulps), points, x);
  }
};

// Whether f keeps its order (non-decreasing if `rising`, else non-increasing)
// over the 2n + 1 consecutive doubles from n below `center` (towards 0).
template <class F>
bool monotonic_around(F f, double center, int n, bool rising = true) {
  double x = center;
  for (int i = 0; i < n; ++i) x = std::nextafter(x, 0.0);
  double previous = f(x);
  for (int i = 0; i < 2 * n; ++i) {
    x = std::nextafter(x, INFINITY);
    const double value = f(x);
    if (rising ? value < previous : value > previous) return false;
    previous = value;
  }
  return true;
}

template <class F>
void sample(F f, double x) {
  std::printf("SAMPLE %a %a\n", x, f(x));
}

// n samples of magnitude 2^e, e uniform in [lowest, highest), signs alternating.
template <class F>
void log_uniform_samples(F f, std::mt19937_64& random, double lowest, double highest, int n) {
  std::uniform_real_distribution<double> exponent(lowest, highest);
  for (int i = 0; i < n; ++i) sample(f, (i % 2 ? -1.0 : 1.0) * std::exp2(exponent(random)));
}

// n samples uniform in [lowest, highest).
template <class F>
void uniform_samples(F f, std::mt19937_64& random, double lowest, double highest, int n) {
  std::uniform_real_distribution<double> uniform(lowest, highest);
  for (int i = 0; i < n; ++i) sample(f, uniform(random));
}

// The 2n consecutive doubles from n below `center` (towards 0) upwards.
template <class F>
void samples_around(F f, double center, int n) {
  double x = center;
  for (int i = 0; i < n; ++i) x = std::nextafter(x, 0.0);
  for (int i = 0; i < 2 * n; ++i, x = std::nextafter(x, INFINITY)) sample(f, x);
}

}  // namespace ulp_sweep
