#include "leadscrew/excitation/sampled.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <string>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Samples per period of the highest frequency at least: the cubic Hermite
// interpolant of exact values and slopes is then within (2 pi / 10)^4 / 384
// = 4e-4 of a sinusoid's amplitude at the top of the band (-0.003 dB).
constexpr double kSamplesPerPeriod = 10.0;
constexpr std::size_t kMaxSamples = std::size_t{1} << 24;

std::string indexed(const char* name, std::size_t i) {
  return std::string(name) + "[" + std::to_string(i) + "]";
}

// In place, unnormalised, e^{+2 pi i k n / N}: the inverse DFT times N.
void inverse_fft(std::vector<std::complex<double>>& a) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {  // bit reversal
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  std::vector<std::complex<double>> twiddle(n / 2);
  for (std::size_t k = 0; k < n / 2; ++k)
    twiddle[k] = std::polar(1.0, 2.0 * kPi * static_cast<double>(k) / static_cast<double>(n));
  for (std::size_t length = 2; length <= n; length <<= 1) {
    const std::size_t stride = n / length;
    for (std::size_t start = 0; start < n; start += length)
      for (std::size_t k = 0; k < length / 2; ++k) {
        const std::complex<double> u = a[start + k];
        const std::complex<double> v = a[start + k + length / 2] * twiddle[k * stride];
        a[start + k] = u + v;
        a[start + k + length / 2] = u - v;
      }
  }
}

// The PSD at f, log-log interpolated between its breakpoints.
double psd_at(const std::vector<double>& f, const std::vector<double>& s, double x) {
  const std::size_t j = std::min<std::size_t>(
      static_cast<std::size_t>(std::upper_bound(f.begin(), f.end(), x) - f.begin()),
      f.size() - 1);
  const std::size_t i = j == 0 ? 0 : j - 1;
  const double b = std::log(s[i + 1] / s[i]) / std::log(f[i + 1] / f[i]);
  return s[i] * std::pow(x / f[i], b);
}

void check_spec(const RandomVibrationSpec& spec) {
  const auto& f = spec.frequencies;
  if (f.size() != spec.psd.size())
    throw InvalidArgument("frequencies and psd must have the same length (got " +
                          std::to_string(f.size()) + " and " + std::to_string(spec.psd.size()) +
                          ")");
  if (f.size() < 2)
    throw InvalidArgument("frequencies must hold at least two breakpoints (got " +
                          std::to_string(f.size()) + ")");
  for (std::size_t i = 0; i < f.size(); ++i) {
    require_positive(indexed("frequencies", i), f[i]);
    require_positive(indexed("psd", i), spec.psd[i]);
    if (i > 0 && !(f[i] > f[i - 1]))
      throw InvalidArgument(indexed("frequencies", i) + " = " + format_value(f[i]) +
                            " is invalid: frequencies must be strictly increasing");
  }
  require_in_range("seed", spec.seed, 0.0, 9007199254740992.0);
  if (spec.seed != std::floor(spec.seed))
    throw InvalidArgument("seed = " + format_value(spec.seed) +
                          " is invalid: must be an integer in [0, 2^53]");
  require_positive("duration", spec.duration);
}

}  // namespace

double psd_integral(const std::vector<double>& f, const std::vector<double>& s) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < f.size(); ++i) {
    const double ratio = f[i + 1] / f[i];
    const double b = std::log(s[i + 1] / s[i]) / std::log(ratio);
    sum += std::abs(b + 1.0) < 1e-12 ? s[i] * f[i] * std::log(ratio)
                                     : s[i] * f[i] / (b + 1.0) * (std::pow(ratio, b + 1.0) - 1.0);
  }
  return sum;
}

SampledSignal realise(const RandomVibrationSpec& spec) {
  check_spec(spec);
  const auto& f = spec.frequencies;
  const double T = spec.duration, df = 1.0 / T, low = f.front(), high = f.back();
  // (Checked before any count is computed: a duration of 1e300 s must not
  // overflow the doubling below.)
  if (kSamplesPerPeriod * high * T > static_cast<double>(kMaxSamples))
    throw InvalidArgument("duration = " + format_value(T) + " s is invalid with a highest "
                          "frequency of " + format_value(high) + " Hz: the realisation would "
                          "take more than 2^24 samples; must be at most " +
                          format_value(static_cast<double>(kMaxSamples) /
                                       (kSamplesPerPeriod * high)) + " s");
  const auto k_low = static_cast<std::size_t>(std::max(1.0, std::ceil(low * T - 1e-9)));
  const auto k_high = static_cast<std::size_t>(std::floor(high * T + 1e-9));
  if (k_high < k_low)
    throw InvalidArgument("duration = " + format_value(T) + " s is invalid: its frequency grid (" +
                          format_value(df) + " Hz) has no line in [" + format_value(low) + ", " +
                          format_value(high) + "] Hz: must be longer");
  std::size_t n = 16;
  while (static_cast<double>(n) < kSamplesPerPeriod * high * T || n < 2 * k_high + 2) n <<= 1;
  // Hermitian spectra of the signal and its derivative, packed as x + i x'.
  std::vector<std::complex<double>> a(n);
  std::mt19937_64 generator(static_cast<std::uint64_t>(spec.seed));
  for (std::size_t k = k_low; k <= k_high; ++k) {
    const double fk = static_cast<double>(k) * df;
    // The line stands for its bin [fk - df/2, fk + df/2] inside the band.
    const double width = std::min(fk + 0.5 * df, high) - std::max(fk - 0.5 * df, low);
    const double phase = 2.0 * kPi * static_cast<double>(generator() >> 11) * 0x1.0p-53;
    if (!(width > 0.0)) continue;
    const double amplitude = std::sqrt(2.0 * psd_at(f, spec.psd, fk) * width);
    const std::complex<double> z = 0.5 * std::polar(amplitude, phase);
    const std::complex<double> dz = std::complex<double>(0.0, 2.0 * kPi * fk) * z;
    const std::complex<double> i(0.0, 1.0);
    a[k] += z + i * dz;
    a[n - k] += std::conj(z) + i * std::conj(dz);
  }
  inverse_fft(a);
  SampledSignal s;
  s.times.resize(n + 1);
  s.values.resize(n + 1);
  s.slopes.resize(n + 1);
  s.step = T / static_cast<double>(n);
  for (std::size_t j = 0; j <= n; ++j) {
    s.times[j] = static_cast<double>(j) * s.step;
    s.values[j] = a[j % n].real();
    s.slopes[j] = a[j % n].imag();
  }
  s.period = T;
  s.time_scale = 1.0 / high;
  s.target_rms = std::sqrt(psd_integral(f, spec.psd));
  return s;
}

SampledSignal realise(const MeasuredSpec& spec) {
  const auto& t = spec.times;
  if (t.size() != spec.values.size())
    throw InvalidArgument("times and values must have the same length (got " +
                          std::to_string(t.size()) + " and " +
                          std::to_string(spec.values.size()) + ")");
  if (t.size() < 2)
    throw InvalidArgument("times must hold at least two samples (got " +
                          std::to_string(t.size()) + ")");
  require_finite("scale", spec.scale);
  SampledSignal s;
  s.times = t;
  s.values.resize(t.size());
  double shortest = INFINITY;
  for (std::size_t i = 0; i < t.size(); ++i) {
    require_finite(indexed("times", i), t[i]);
    s.values[i] = spec.scale * require_finite(indexed("values", i), spec.values[i]);
    if (i > 0 && !(t[i] > t[i - 1]))
      throw InvalidArgument(indexed("times", i) + " = " + format_value(t[i]) +
                            " is invalid: times must be strictly increasing");
    if (i > 0) shortest = std::min(shortest, t[i] - t[i - 1]);
  }
  const std::size_t last = t.size() - 1;
  const double spacing = (t[last] - t[0]) / static_cast<double>(last);
  if (spec.repeat) {  // the last sample runs into the first one over the mean spacing
    s.times.push_back(t[last] + spacing);
    s.values.push_back(s.values[0]);
    s.period = s.times.back() - t[0];
  }
  const std::size_t m = s.times.size() - 1;
  s.slopes.resize(m + 1);
  for (std::size_t i = 0; i <= m; ++i) {
    std::size_t before = i == 0 ? 0 : i - 1, after = i == m ? m : i + 1;
    double t_before = s.times[before], y_before = s.values[before];
    if (spec.repeat && i == 0) {  // wrap: the sample before the first is the last one
      t_before = s.times[0] - spacing;
      y_before = s.values[last];
    }
    double t_after = s.times[after], y_after = s.values[after];
    if (spec.repeat && i == m) {
      t_after = s.times[m] + (s.times[1] - s.times[0]);
      y_after = s.values[1];
    }
    s.slopes[i] = (y_after - y_before) / (t_after - t_before);
  }
  bool uniform = true;
  for (std::size_t i = 0; i <= m && uniform; ++i)
    uniform = std::abs(s.times[i] - (t[0] + static_cast<double>(i) * spacing)) <= 1e-9 * spacing;
  if (uniform) s.step = spacing;
  s.time_scale = 2.0 * std::min(shortest, spacing);
  return s;
}

void SampledSignal::locate(double t, std::size_t& i, double& s) const {
  const double t0 = times.front();
  if (period > 0.0) {
    t = t0 + std::fmod(t - t0, period);
    if (t < t0) t += period;
  }
  const std::size_t last = times.size() - 2;
  if (step > 0.0) {
    const double position = std::floor((t - t0) / step);
    i = position <= 0.0 ? 0 : std::min(static_cast<std::size_t>(position), last);
  } else {
    const auto upper = std::upper_bound(times.begin(), times.end(), t);
    i = upper == times.begin() ? 0 : std::min<std::size_t>(upper - times.begin() - 1, last);
  }
  s = (t - times[i]) / (times[i + 1] - times[i]);
}

double SampledSignal::value(double t) const {
  if (period == 0.0) {
    if (t <= times.front()) return values.front();
    if (t >= times.back()) return values.back();
  }
  std::size_t i = 0;
  double s = 0.0;
  locate(t, i, s);
  const double h = times[i + 1] - times[i], s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * values[i] + (s3 - 2 * s2 + s) * h * slopes[i] +
         (-2 * s3 + 3 * s2) * values[i + 1] + (s3 - s2) * h * slopes[i + 1];
}

double SampledSignal::derivative(double t) const {
  if (period == 0.0 && (t < times.front() || t >= times.back())) return 0.0;
  std::size_t i = 0;
  double s = 0.0;
  locate(t, i, s);
  const double h = times[i + 1] - times[i], s2 = s * s;
  return (6 * s2 - 6 * s) * (values[i] - values[i + 1]) / h +
         (3 * s2 - 4 * s + 1) * slopes[i] + (3 * s2 - 2 * s) * slopes[i + 1];
}

}  // namespace leadscrew
