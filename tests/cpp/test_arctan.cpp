// Native check of leadscrew::friction::arctan (cpp/include/leadscrew/friction/arctan.hpp)
// against std::atan, built and run by tests/test_friction_arctan.py.
//
// Prints
//   MAXULP <set> <max ulp distance to std::atan> <points> <worst x (hex)>
//   SPECIAL <name> PASS|FAIL
//   SAMPLE <x (hex)> <arctan(x) (hex)>   (for the mpmath check in Python)
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

#include "leadscrew/friction/arctan.hpp"

namespace {

using leadscrew::friction::arctan;

// Doubles mapped to integers that are consecutive in the order of the reals
// (+0 and -0 both to 0): the difference is the distance in ulps.
std::int64_t ordered(double x) {
  std::int64_t i = 0;
  std::memcpy(&i, &x, sizeof x);
  return i < 0 ? std::numeric_limits<std::int64_t>::min() - i : i;
}

double from_bits(std::uint64_t bits) {
  double x = 0.0;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

struct Worst {
  const char* name;
  std::int64_t ulps = 0;
  long points = 0;
  double x = 0.0;
  void check(double x_value) {
    const double ours = arctan(x_value), reference = std::atan(x_value);
    std::int64_t distance = ordered(ours) - ordered(reference);
    if (distance < 0) distance = -distance;
    if (std::isnan(ours) != std::isnan(reference)) distance = std::numeric_limits<std::int64_t>::max();
    if (distance > ulps) {
      ulps = distance;
      x = x_value;
    }
    ++points;
  }
  void print() const {
    std::printf("MAXULP %s %lld %ld %a\n", name, static_cast<long long>(ulps), points, x);
  }
};

void special(const char* name, bool ok) { std::printf("SPECIAL %s %s\n", name, ok ? "PASS" : "FAIL"); }

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

int main() {
  std::mt19937_64 random(20130601);

  // Every binade of the double range (subnormals included), both signs:
  // 2048 evenly spaced mantissas and 2048 random ones each.
  Worst binades{"binades"};
  for (std::uint64_t exponent = 0; exponent < 2047; ++exponent)
    for (std::uint64_t sign = 0; sign < 2; ++sign)
      for (std::uint64_t j = 0; j < 4096; ++j) {
        const std::uint64_t mantissa =
            j < 2048 ? (j << 41) | (j * 0x9E3779B97F4A7C15ull >> 52) : random() >> 12;
        binades.check(from_bits(sign << 63 | exponent << 52 | mantissa));
      }
  binades.print();

  // The working range of the friction laws, densely: |x| <= 16.
  Worst dense{"dense"};
  std::uniform_real_distribution<double> uniform(-16.0, 16.0);
  for (int i = 0; i < 4000000; ++i) dense.check(uniform(random));
  dense.print();

  // 20000 consecutive doubles on either side of every branch point.
  Worst edges{"edges"};
  for (const double edge : {0x1p-27, 0.4375, 0.6875, 1.1875, 2.4375, 0x1p66}) {
    for (const double sign : {1.0, -1.0}) {
      double x = sign * edge;
      for (int i = 0; i < 10000; ++i) x = std::nextafter(x, 0.0);
      for (int i = 0; i < 20000; ++i, x = std::nextafter(x, sign * INFINITY)) edges.check(x);
    }
  }
  edges.print();

  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  special("plus_zero", same_bits(arctan(0.0), 0.0));
  special("minus_zero", same_bits(arctan(-0.0), -0.0));
  special("plus_inf", same_bits(arctan(inf), std::atan(inf)));
  special("minus_inf", same_bits(arctan(-inf), std::atan(-inf)));
  special("nan", std::isnan(arctan(nan)) && std::isnan(arctan(-nan)));
  special("max", same_bits(arctan(std::numeric_limits<double>::max()),
                           std::atan(std::numeric_limits<double>::max())));
  special("lowest", same_bits(arctan(std::numeric_limits<double>::lowest()),
                              std::atan(std::numeric_limits<double>::lowest())));
  bool subnormals = true;
  for (const double x : {std::numeric_limits<double>::denorm_min(), 0x1.8p-1060, 0x1.fffffp-1023,
                         std::numeric_limits<double>::min()})
    subnormals = subnormals && same_bits(arctan(x), x) && same_bits(arctan(-x), -x);
  special("subnormal_and_min_identity", subnormals);
  special("odd", [] {
    std::mt19937_64 r(7);
    for (int i = 0; i < 100000; ++i) {
      const double x = from_bits(r() & 0x7fefffffffffffffull);
      if (!same_bits(arctan(-x), -arctan(x))) return false;
    }
    return true;
  }());
  special("monotonic", [] {
    // Non-decreasing over consecutive doubles around every branch point and
    // on a log-spaced walk through the range.
    for (const double edge : {0x1p-27, 0.4375, 0.6875, 1.1875, 2.4375, 0x1p66}) {
      double x = edge;
      for (int i = 0; i < 10000; ++i) x = std::nextafter(x, 0.0);
      double previous = arctan(x);
      for (int i = 0; i < 20000; ++i) {
        x = std::nextafter(x, INFINITY);
        const double value = arctan(x);
        if (value < previous) return false;
        previous = value;
      }
    }
    double previous = arctan(1e-300);
    for (double x = 1e-300; x < 1e300; x *= 1.001) {
      const double value = arctan(x);
      if (value < previous) return false;
      previous = value;
    }
    return true;
  }());

  // Points for the comparison with the exact arctan (mpmath): log-uniform
  // magnitudes, both signs, and the branch points' neighbourhoods.
  std::uniform_real_distribution<double> exponent(-30.0, 70.0);
  for (int i = 0; i < 3000; ++i) {
    const double x = (i % 2 ? -1.0 : 1.0) * std::exp2(exponent(random));
    std::printf("SAMPLE %a %a\n", x, arctan(x));
  }
  std::uniform_real_distribution<double> working(-4.0, 4.0);
  for (int i = 0; i < 3000; ++i) {
    const double x = working(random);
    std::printf("SAMPLE %a %a\n", x, arctan(x));
  }
  for (const double edge : {0.4375, 0.6875, 1.1875, 2.4375}) {
    double x = edge;
    for (int i = 0; i < 50; ++i) x = std::nextafter(x, 0.0);
    for (int i = 0; i < 100; ++i, x = std::nextafter(x, INFINITY))
      std::printf("SAMPLE %a %a\n", x, arctan(x));
  }
  return 0;
}
