// A load given by samples: a random vibration realised from its power
// spectral density, or a measured record. Both are evaluated by cubic
// Hermite interpolation between knots (values and slopes), which is C1:
// no breakpoint at the knots, one index computation and a cubic per call.
#pragma once

#include <cstdint>
#include <vector>

namespace leadscrew {

// Stationary Gaussian vibration with a one-sided PSD given at breakpoints
// (log-log interpolation between them), realised as a random-phase multisine
// on the frequency grid k / duration inside [frequencies.front(),
// frequencies.back()]: periodic with period `duration`.
struct RandomVibrationSpec {
  std::vector<double> frequencies;  // [Hz], > 0, strictly increasing, >= 2
  std::vector<double> psd;          // [unit^2/Hz], > 0
  double seed = 0.0;                // an integer in [0, 2^53]
  double duration = 10.0;           // [s], the period of the realisation
};

// A measured record through (times[i], values[i]) times `scale`, its slopes
// Catmull-Rom's (central differences, one-sided at the ends); held at its
// end values outside [times.front(), times.back()], or, with `repeat`,
// continued periodically with period times.back() - times.front() + the
// mean spacing (the last sample runs into the first one).
struct MeasuredSpec {
  std::vector<double> times;   // [s], strictly increasing, >= 2
  std::vector<double> values;  // the load's unit
  double scale = 1.0;
  bool repeat = false;
};

struct SampledSignal {
  std::vector<double> times, values, slopes;  // the knots (a periodic signal repeats its first)
  double period = 0.0;     // 0: held outside the knots
  double step = 0.0;       // > 0 where the knots are uniform: the index is computed, not searched
  double time_scale = 0.0; // the shortest time over which it changes shape
  double target_rms = 0.0; // a random vibration's sqrt(integral of its PSD); 0 for a record

  double value(double t) const;
  double derivative(double t) const;

 private:
  // The knot interval holding t (wrapped into the period), and t's fraction of it.
  void locate(double t, std::size_t& i, double& s) const;
};

SampledSignal realise(const RandomVibrationSpec& spec);
SampledSignal realise(const MeasuredSpec& spec);

// The integral of a PSD over its breakpoints' range, log-log interpolated
// (each segment S1 (f / f1)^b integrated in closed form).
double psd_integral(const std::vector<double>& frequencies, const std::vector<double>& psd);

}  // namespace leadscrew
