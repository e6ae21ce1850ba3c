#include "leadscrew/excitation/excitation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew {

Excitation::Excitation(ConstantExcitation c) : definition_(c) {
  require_finite("value", c.value);
}

Excitation::Excitation(SineExcitation s) : definition_(s) {
  require_finite("amplitude", s.amplitude);
  require_finite("omega", s.omega);
  require_finite("phase", s.phase);
  require_finite("offset", s.offset);
}

Excitation Excitation::from_kind(const std::string& kind, const std::vector<double>& parameters,
                                 const std::vector<double>& times,
                                 const std::vector<double>& values) {
  auto count = [&](std::size_t low, std::size_t high, const std::string& names) {
    if (parameters.size() >= low && parameters.size() <= high) return;
    std::string listed = "[";
    for (std::size_t i = 0; i < parameters.size(); ++i)
      listed += (i ? ", " : "") + format_value(parameters[i]);
    throw InvalidArgument("parameters = " + listed + "] is invalid for kind = \"" + kind +
                          "\": must hold " + names);
  };
  auto no_table = [&]() {
    if (!times.empty() || !values.empty())
      throw InvalidArgument("times and values are invalid for kind = \"" + kind +
                            "\": only a \"table\", \"random\" or \"measured\" takes them");
  };
  static const std::vector<std::string> kinds = {"constant", "sine", "table", "random",
                                                 "measured"};
  switch (require_choice("kind", kind, kinds)) {
    case 0:
      count(1, 1, "[value]");
      no_table();
      return Excitation(ConstantExcitation{parameters[0]});
    case 1: {
      count(2, 4, "[amplitude, omega], [amplitude, omega, phase] or "
                  "[amplitude, omega, phase, offset]");
      no_table();
      SineExcitation sine{parameters[0], parameters[1]};
      if (parameters.size() > 2) sine.phase = parameters[2];
      if (parameters.size() > 3) sine.offset = parameters[3];
      return Excitation(sine);
    }
    case 2:
      count(0, 0, "empty (a table takes times and values)");
      return Excitation(TableExcitation{times, values});
    case 3:
      count(2, 2, "[seed, duration] (the frequencies as times, the psd as values)");
      return Excitation(RandomVibrationSpec{times, values, parameters[0], parameters[1]});
    default:
      count(2, 2, "[scale, repeat] (repeat 0 or 1)");
      if (parameters[1] != 0.0 && parameters[1] != 1.0)
        throw InvalidArgument("repeat = " + format_value(parameters[1]) +
                              " is invalid: must be 0 or 1");
      return Excitation(MeasuredSpec{times, values, parameters[0], parameters[1] == 1.0});
  }
}

Excitation::Excitation(TableExcitation table) {
  if (table.times.size() != table.values.size())
    throw InvalidArgument("times and values must have the same length (got " +
                          std::to_string(table.times.size()) + " and " +
                          std::to_string(table.values.size()) + ")");
  if (table.times.empty())
    throw InvalidArgument("times = [] is invalid: must hold at least one point");
  for (std::size_t i = 0; i < table.times.size(); ++i) {
    require_finite("times[" + std::to_string(i) + "]", table.times[i]);
    require_finite("values[" + std::to_string(i) + "]", table.values[i]);
    if (i > 0 && !(table.times[i] > table.times[i - 1]))
      throw InvalidArgument("times[" + std::to_string(i) + "] = " +
                            format_value(table.times[i]) +
                            " is invalid: times must be strictly increasing");
  }
  breakpoints_ = table.times;
  definition_ = std::move(table);
}

Excitation::Excitation(const RandomVibrationSpec& random)
    : definition_(SampledExcitation{std::make_shared<const SampledExcitation::Data>(
          SampledExcitation::Data{realise(random), "random", {random.seed, random.duration},
                                  random.frequencies, random.psd})}) {}

Excitation::Excitation(const MeasuredSpec& measured)
    : definition_(SampledExcitation{std::make_shared<const SampledExcitation::Data>(
          SampledExcitation::Data{realise(measured), "measured",
                                  {measured.scale, measured.repeat ? 1.0 : 0.0}, measured.times,
                                  measured.values})}) {
  // Held outside the record: its slope jumps at both ends.
  if (!measured.repeat) breakpoints_ = {measured.times.front(), measured.times.back()};
}

double Excitation::target_rms() const {
  return definition_.index() == 3 ? std::get<3>(definition_).data->signal.target_rms : 0.0;
}

Excitation::Excitation(CallableExcitation f) : definition_(std::move(f)) {
  if (!std::get<kCallable>(definition_).function)
    throw InvalidArgument("function is invalid: must be callable");
}

double Excitation::general_value(double t) const {
  if (definition_.index() == 2) {
    const auto& table = std::get<2>(definition_);
    const auto& times = table.times;
    if (t <= times.front()) return table.values.front();
    if (t >= times.back()) return table.values.back();
    const auto upper = std::upper_bound(times.begin(), times.end(), t);
    const std::size_t i = static_cast<std::size_t>(upper - times.begin());
    const double fraction = (t - times[i - 1]) / (times[i] - times[i - 1]);
    return table.values[i - 1] + fraction * (table.values[i] - table.values[i - 1]);
  }
  if (definition_.index() == 3) return std::get<3>(definition_).data->signal.value(t);
  const auto& callable = std::get<kCallable>(definition_);
  const double value = callable.function(t);
  if (!std::isfinite(value))
    throw SimulationError(t, "the excitation " + callable.description + " returned " +
                                 format_value(value),
                          "a load function must return finite numbers");
  return value;
}

double Excitation::time_scale() const {
  switch (definition_.index()) {
    case 0:
      return std::numeric_limits<double>::infinity();
    case 1: {
      const auto& s = std::get<1>(definition_);
      if (s.omega == 0.0 || s.amplitude == 0.0) return std::numeric_limits<double>::infinity();
      return 2.0 * 3.14159265358979323846 / std::abs(s.omega);
    }
    case 2:
      // Linear between its knots, which are breakpoints: a root function
      // linear in the loads changes sign at most once between two of them,
      // whatever their spacing. (The shortest interval used to be its time
      // scale: a 1e-7 s ramp capped every step of the run at 6e-9 s, even
      // with the ramp after t_end.)
      return std::numeric_limits<double>::infinity();
    case 3:
      return std::get<3>(definition_).data->signal.time_scale;
    default:
      return 0.0;
  }
}

double Excitation::difference_step(double t) { return 1e-6 * std::max(1.0, std::abs(t)); }

std::optional<Excitation::Jump> Excitation::jump_near(double t, double window) const {
  if (definition_.index() != kCallable || !(window > 0.0) || !std::isfinite(t)) return std::nullopt;
  double low = t - window, high = t + window;
  double f_low = general_value(low), f_high = general_value(high);
  const double change = std::abs(f_high - f_low);
  // Keep the half that changes more: it holds the step if there is one.
  // 100 halvings: 2 window / 2^100, below a double's resolution of t > 1e-16 s.
  for (int i = 0; i < 100; ++i) {
    const double middle = low + 0.5 * (high - low);
    if (!(middle > low && middle < high)) break;  // adjacent doubles
    const double f_middle = general_value(middle);
    if (std::abs(f_middle - f_low) >= std::abs(f_high - f_middle)) {
      high = middle;
      f_high = f_middle;
    } else {
      low = middle;
      f_low = f_middle;
    }
  }
  const double size = std::abs(f_high - f_low);
  const double round_off = 1e3 * std::numeric_limits<double>::epsilon() *
                           std::max(std::abs(f_low), std::abs(f_high));
  if (!(size > round_off) || !(size >= 0.5 * change)) return std::nullopt;
  return Jump{high, f_low, f_high};
}

double Excitation::derivative(double t) const {
  switch (definition_.index()) {
    case 0:
      return 0.0;
    case 1: {
      const auto& s = std::get<1>(definition_);
      return s.amplitude * s.omega * std::cos(s.omega * t + s.phase);
    }
    case 2: {
      const auto& table = std::get<2>(definition_);
      const auto& times = table.times;
      if (t < times.front() || t >= times.back() || times.size() < 2) return 0.0;
      const auto upper = std::upper_bound(times.begin(), times.end(), t);
      const std::size_t i = static_cast<std::size_t>(upper - times.begin());
      return (table.values[i] - table.values[i - 1]) / (times[i] - times[i - 1]);
    }
    case 3:
      return std::get<3>(definition_).data->signal.derivative(t);
    default: {
      const double h = difference_step(t);
      return (general_value(t + h) - general_value(t - h)) / (2.0 * h);
    }
  }
}

double Excitation::continuous_derivative(double t, const std::string& name) const {
  if (definition_.index() != kCallable) return derivative(t);
  const double h = difference_step(t);
  const double before = general_value(t - h), now = general_value(t), after = general_value(t + h);
  const double left = now - before, right = after - now;
  // A smooth function changes alike over both halves (they differ by its
  // curvature times h^2); a step shows in one half alone.
  if (std::abs(left - right) > 0.5 * (std::abs(left) + std::abs(right))) {
    if (const std::optional<Jump> jump = jump_near(t, h)) {
      const std::string& description = std::get<kCallable>(definition_).description;
      throw SimulationError(
          jump->time,
          name + " steps from " + format_value(jump->before) + " to " +
              format_value(jump->after) + " at t = " + format_value(jump->time) + " s (" +
              description + "): a step of a prescribed speed is an infinite acceleration",
          "ramp the change over a time the drive can follow (a table load ramps linearly "
          "between its knots), or, where the friction law allows it, integrator=\"moreau\", "
          "which takes the step as an impulse");
    }
  }
  return (after - before) / (2.0 * h);
}

Excitation::Definition Excitation::definition() const {
  switch (definition_.index()) {
    case 0:
      return {"constant", {std::get<0>(definition_).value}, {}, {}};
    case 1: {
      const auto& s = std::get<1>(definition_);
      return {"sine", {s.amplitude, s.omega, s.phase, s.offset}, {}, {}};
    }
    case 2:
      return {"table", {}, std::get<2>(definition_).times, std::get<2>(definition_).values};
    case 3: {
      const auto& d = *std::get<3>(definition_).data;
      return {d.kind, d.parameters, d.times, d.values};
    }
    default:
      return {"callable", {}, {}, {}};
  }
}

std::string Excitation::describe() const {
  std::ostringstream out;
  out.precision(12);
  switch (definition_.index()) {
    case 0:
      out << "Constant(" << std::get<0>(definition_).value << ")";
      break;
    case 1: {
      const auto& s = std::get<1>(definition_);
      out << "Sine(amplitude=" << s.amplitude << ", omega=" << s.omega << ", phase=" << s.phase
          << ", offset=" << s.offset << ")";
      break;
    }
    case 2:
      out << "Table(" << std::get<2>(definition_).times.size() << " points)";
      break;
    case 3: {
      const auto& d = *std::get<3>(definition_).data;
      if (d.kind == "random")
        out << "RandomVibration(" << d.times.size() << " breakpoints, " << d.times.front()
            << "-" << d.times.back() << " Hz, seed=" << d.parameters[0]
            << ", duration=" << d.parameters[1] << ")";
      else
        out << "Measured(" << d.times.size() << " samples, scale=" << d.parameters[0]
            << (d.parameters[1] == 1.0 ? ", repeated)" : ")");
      break;
    }
    default:
      out << std::get<kCallable>(definition_).description;
  }
  return out.str();
}

}  // namespace leadscrew
