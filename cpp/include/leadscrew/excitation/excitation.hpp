// Time functions for loads (drive torque, axial force, excitation force),
// shared by every model: constant, sine, piecewise-linear table, and a general
// callable (the slow fallback: the Python bindings wrap a Python function).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "leadscrew/excitation/sampled.hpp"
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

// A random vibration or a measured record (sampled.hpp), with the definition
// it was made from (for definition() and describe()). Immutable and shared:
// a copy of the load (the parameters, a model's build) copies a pointer, not
// its samples (a 10 s realisation of a 2 kHz profile is 6 MB).
struct SampledExcitation {
  struct Data {
    SampledSignal signal;
    std::string kind;  // "random" or "measured"
    std::vector<double> parameters, times, values;
  };
  std::shared_ptr<const Data> data;
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
  Excitation(const RandomVibrationSpec& random);  // validates, realises (sampled.hpp)
  Excitation(const MeasuredSpec& measured);

  // By name, as Python's Excitation(kind, parameters, times, values):
  // "constant" [value], "sine" [amplitude, omega, phase = 0, offset = 0],
  // "table" (times, values), "random" ([seed, duration], frequencies [Hz] as
  // times, psd as values), "measured" ([scale, repeat (0 or 1)], times,
  // values). Wrong counts raise InvalidArgument.
  static Excitation from_kind(const std::string& kind, const std::vector<double>& parameters,
                              const std::vector<double>& times, const std::vector<double>& values);

  // The definition as from_kind takes it: kind "constant" (parameters
  // [value]), "sine" ([amplitude, omega, phase, offset]) or "table" (times,
  // values), "random" or "measured" (as from_kind takes them); "callable"
  // for a callable, which has no other.
  struct Definition {
    std::string kind;
    std::vector<double> parameters, times, values;
  };
  Definition definition() const;

  double operator()(double t) const {
    switch (definition_.index()) {
      case 0:
        return std::get<0>(definition_).value;
      case 1:
        return sine_value(std::get<1>(definition_), t);
      case 3:
        return std::get<3>(definition_).data->signal.value(t);
      default:
        return general_value(t);
    }
  }

  // d/dt of the function: exact for constant, sine, table (the slope to
  // the right of a knot) and a sampled signal (its cubic's); a central
  // difference for a callable.
  double derivative(double t) const;

  // derivative(t) of a load the model differentiates and cannot follow
  // through a step: a prescribed speed, whose step is an infinite
  // acceleration. For a callable (the one kind that can step: a table ramps
  // between knots the integrators stop at) one call more than derivative();
  // where the difference's three values look like a step, jump_near
  // confirms it (a smooth extremum or a kink does not pass) and
  // SimulationError names `name`, the step's time and values, and a ramp,
  // a table or Moreau-Jean's impulses as what follows it.
  double continuous_derivative(double t, const std::string& name) const;

  // Shortest time over which the function changes shape between its
  // breakpoints, what an integrator has to resolve there: a sine's period;
  // a random vibration's period at its highest frequency, twice a record's
  // shortest sample spacing;
  // +inf for a constant and for a table (linear between its knots, which are
  // breakpoints: however short an interval, no step straddles it); 0 for a
  // callable, which gives no hint. Integrators cap their steps by a fraction
  // of it so that root functions driven by a load cannot change sign twice
  // within a step.
  double time_scale() const;

  // A step of a callable within [t - window, t + window]: where its value
  // jumps, found by bisection down to adjacent doubles (at most 102 calls),
  // with the values on either side. A jump keeps its size as the bracket
  // shrinks; a continuous function's change shrinks with it, however steep
  // (a ramp over 1e-9 s is no jump). A change smaller than the function's
  // slope over the window, or within 1000 ulps of its values, is not
  // reported. nullopt for a constant, a sine and a table (continuous).
  struct Jump {
    double time = 0.0;    // the first double after the step
    double before = 0.0;  // f just before it
    double after = 0.0;   // f at time
  };
  std::optional<Jump> jump_near(double t, double window) const;

  // Times at which the function or its first derivative jumps (table knots):
  // integrators restart there to keep their order.
  const std::vector<double>& breakpoints() const noexcept { return breakpoints_; }
  std::string describe() const;

  // A random vibration's sqrt(integral of its PSD) (its target RMS); 0 for
  // every other kind.
  double target_rms() const;

 private:
  // Inline: each Runge-Kutta stage of a sine-loaded model waits for it.
  // excitation::sine instead of std::sin: the same values to within 1 ulp
  // (sine.hpp), without glibc's call.
  static double sine_value(const SineExcitation& s, double t) {
    return s.amplitude * excitation::sine(s.omega * t + s.phase) + s.offset;
  }
  double general_value(double t) const;
  // The half width of a callable's central difference at t.
  static double difference_step(double t);

  // The callable last: its index is kCallable.
  static constexpr std::size_t kCallable = 4;
  std::variant<ConstantExcitation, SineExcitation, TableExcitation, SampledExcitation,
               CallableExcitation>
      definition_;
  std::vector<double> breakpoints_;
};

}  // namespace leadscrew
