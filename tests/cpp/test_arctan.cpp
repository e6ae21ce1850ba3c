// Native check of leadscrew::friction::arctan (cpp/include/leadscrew/friction/arctan.hpp)
// against std::atan, built and run by tests/test_friction_arctan.py.
//
// Prints
//   MAXULP <set> <max ulp distance to std::atan> <points> <worst x (hex)>
//   SPECIAL <name> PASS|FAIL
//   SAMPLE <x (hex)> <arctan(x) (hex)>   (for the mpmath check in Python)
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "leadscrew/friction/arctan.hpp"
#include "ulp_sweep.hpp"

namespace {

using leadscrew::friction::arctan;
using namespace ulp_sweep;

const auto ours = [](double x) { return arctan(x); };
const auto reference = [](double x) { return std::atan(x); };

}  // namespace

int main() {
  std::mt19937_64 random(20130601);

  // Every binade of the double range (subnormals included), both signs:
  // 2048 evenly spaced mantissas and 2048 random ones each.
  Worst binades("binades", ours, reference);
  binades.every_binade([](std::uint64_t) { return 4096; }, [&](std::uint64_t j) {
    return j < 2048 ? (j << 41) | (j * 0x9E3779B97F4A7C15ull >> 52) : random() >> 12;
  });
  binades.print();

  // The working range of the friction laws, densely: |x| <= 16.
  Worst dense("dense", ours, reference);
  std::uniform_real_distribution<double> uniform(-16.0, 16.0);
  for (int i = 0; i < 4000000; ++i) dense.check(uniform(random));
  dense.print();

  // 20000 consecutive doubles on either side of every branch point.
  Worst edges("edges", ours, reference);
  for (const double edge : {0x1p-27, 0.4375, 0.6875, 1.1875, 2.4375, 0x1p66})
    edges.around(edge, 10000);
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
    for (const double edge : {0x1p-27, 0.4375, 0.6875, 1.1875, 2.4375, 0x1p66})
      if (!monotonic_around(ours, edge, 10000)) return false;
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
  log_uniform_samples(ours, random, -30.0, 70.0, 3000);
  uniform_samples(ours, random, -4.0, 4.0, 3000);
  for (const double edge : {0.4375, 0.6875, 1.1875, 2.4375}) samples_around(ours, edge, 50);
  return 0;
}
