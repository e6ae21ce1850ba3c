#include "leadscrew/friction/law.hpp"

#include <cmath>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"

namespace leadscrew::friction {

const LawType& law_type(const std::string& name, const std::string& key) {
  std::vector<std::string> names;
  for (const LawType& type : law_types()) {
    if (name == type.name) return type;
    names.emplace_back(type.name);
  }
  require_choice(key, name, names);  // throws, listing the laws
  throw InvalidArgument(key + " is invalid");  // not reached
}

std::vector<double> complete_values(const LawType& type, const LawValues& values,
                                    const std::string& prefix) {
  std::vector<double> out(type.parameters.size(), std::numeric_limits<double>::quiet_NaN());
  std::vector<bool> given(type.parameters.size(), false);
  for (const auto& [key, value] : values) {
    std::size_t k = 0;
    while (k < type.parameters.size() && key != type.parameters[k].key) ++k;
    if (k == type.parameters.size()) {
      std::string keys;
      for (const ParameterInfo& p : type.parameters)
        keys += (keys.empty() ? "" : ", ") + std::string(p.key);
      throw InvalidArgument(prefix + key + " is invalid for the friction law \"" + type.name +
                            "\": it takes " + keys);
    }
    out[k] = value;
    given[k] = true;
  }
  // Defaults: numbers first, then the ones taken from another key.
  for (std::size_t k = 0; k < out.size(); ++k) {
    const ParameterInfo& p = type.parameters[k];
    if (given[k] || p.default_from) continue;
    if (std::isnan(p.default_value))
      throw InvalidArgument(prefix + p.key + " is required by the friction law \"" + type.name +
                            "\" (" + p.doc + ")");
    out[k] = p.default_value;
  }
  auto index = [&](const char* key) {
    for (std::size_t k = 0; k < type.parameters.size(); ++k)
      if (std::string(type.parameters[k].key) == key) return k;
    throw InvalidArgument(std::string("friction law ") + type.name + ": no parameter " + key);
  };
  for (std::size_t k = 0; k < out.size(); ++k) {
    const ParameterInfo& p = type.parameters[k];
    if (!given[k] && p.default_from) out[k] = out[index(p.default_from)];
  }
  for (std::size_t k = 0; k < out.size(); ++k) {
    const ParameterInfo& p = type.parameters[k];
    require_in_range(prefix + p.key, out[k], p.low, p.high, p.low_open, p.high_open);
    if (p.at_least) {
      const double floor = out[index(p.at_least)];
      if (!(out[k] >= floor))
        throw InvalidArgument(prefix + p.key + " = " + format_value(out[k]) +
                              " is invalid: must be >= " + prefix + p.at_least + " = " +
                              format_value(floor));
    }
  }
  return out;
}

std::unique_ptr<Law> make_law(const std::string& name, const LawValues& values,
                              const std::string& prefix) {
  const LawType& type = law_type(name, prefix + "law");
  return type.make(complete_values(type, values, prefix));
}

}  // namespace leadscrew::friction
