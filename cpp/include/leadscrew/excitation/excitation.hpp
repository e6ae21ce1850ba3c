// Time functions for loads (drive torque, axial force, excitation force),
// shared by every model: constant, sine, piecewise-linear table, and a general
// callable (the slow fallback: the Python bindings wrap a Python function).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "leadscrew/excitation/sine.hpp"

namespace leadscrew {

struct ConstantExcitation {
  double value = 0.0;
};

// amplitude * sin(omega t + phase) + offset
struct SineExcitation {
  double amplitude = 0.0;
  double omega = 0.0;   // [rad/s]
  double phase = 0.0;   // [rad]
  double offset = 0.0;
};

// Piecewise-linear through (times[i], values[i]); held constant outside.
struct TableExcitation {
  std::vector<double> times;
  std::vector<double> values;
};

// f(t); may throw (the exception propagates out of the simulation).
struct CallableExcitation {
  std::function<double(double)> function;
  std::string description = "callable";
};

class Excitation {
 public:
  Excitation() : definition_(ConstantExcitation{0.0}) {}
  Excitation(ConstantExcitation c);
  Excitation(SineExcitation s);
  Excitation(TableExcitation table);  // validates: sizes, strictly increasing finite times
  Excitation(CallableExcitation f);

  // By name, as Python's Excitation(kind, parameters, times, values):
  // "constant" [value], "sine" [amplitude, omega, phase = 0, offset = 0],
  // "table" (times, values). Wrong counts raise InvalidArgument.
  static Excitation from_kind(const std::string& kind, const std::vector<double>& parameters,
                              const std::vector<double>& times, const std::vector<double>& values);

  double operator()(double t) const {
    switch (definition_.index()) {
      case 0:
        return std::get<0>(definition_).value;
      case 1:
        return sine_value(std::get<1>(definition_), t);
      default:
        return general_value(t);
    }
  }

  // d/dt of the function: exact for constant, sine and table (the slope to
  // the right of a knot); a central difference for a callable.
  double derivative(double t) const;

  // Shortest time over which the function changes shape (a sine's period,
  // the shortest table interval; +inf for a constant, 0 for a callable, which
  // gives no hint). Integrators cap their steps by a fraction of it so that
  // root functions driven by a load cannot change sign twice within a step.
  double time_scale() const;

  // Times at which the function or its first derivative jumps (table knots):
  // integrators restart there to keep their order.
  const std::vector<double>& breakpoints() const noexcept { return breakpoints_; }
  std::string describe() const;

 private:
  // Inline: each Runge-Kutta stage of a sine-loaded model waits for it.
  // excitation::sine instead of std::sin: the same values to within 1 ulp
  // (sine.hpp), without glibc's call.
  static double sine_value(const SineExcitation& s, double t) {
    return s.amplitude * excitation::sine(s.omega * t + s.phase) + s.offset;
  }
  double general_value(double t) const;

  std::variant<ConstantExcitation, SineExcitation, TableExcitation, CallableExcitation>
      definition_;
  std::vector<double> breakpoints_;
};

}  // namespace leadscrew
