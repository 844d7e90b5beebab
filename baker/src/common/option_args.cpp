// SPDX-License-Identifier: MIT
// Options set from argument lists without a command-line parser: what `prt-bake scene` does with
// a technique's candidate settings and a node's extras (prt/baker/options.hpp).
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "prt/baker/context.hpp"
#include "prt/baker/options.hpp"

namespace prt::bake {
namespace {

bool spelled_as(const OptionSpec& spec, const std::string& name) {
  std::stringstream names(spec.name);
  for (std::string one; std::getline(names, one, ',');) {
    if (one == name) return true;
  }
  return false;
}

double parse_number(const std::string& option, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(value))
    throw Error(option + ": '" + text + "' is not a number");
  return value;
}

template <typename T>
T parse_value(const OptionSpec& spec, const std::string& text) {
  if constexpr (std::is_same_v<T, std::string>) {
    return text;
  } else {
    const double value = parse_number(spec.name, text);
    if constexpr (std::is_integral_v<T>) {
      if (value != std::floor(value) || value < double(std::numeric_limits<T>::lowest()) ||
          value > double(std::numeric_limits<T>::max()))
        throw Error(spec.name + ": '" + text + "' is not a whole number in range");
    }
    if (spec.bounds && (value < spec.bounds->first || value > spec.bounds->second)) {
      std::ostringstream range;
      range << spec.name << ": " << text << " is outside [" << spec.bounds->first << ", "
            << spec.bounds->second << "]";
      throw Error(range.str());
    }
    return static_cast<T>(value);
  }
}

void check_accepted(const OptionSpec& spec, const std::string& text) {
  if (spec.accepted.empty()) return;
  for (const std::string& accepted : spec.accepted) {
    if (accepted == text) return;
  }
  std::string list;
  for (const std::string& accepted : spec.accepted) list += (list.empty() ? "" : ", ") + accepted;
  throw Error(spec.name + ": '" + text + "' is not one of " + list);
}

template <typename T>
void set_value(const OptionSpec& spec, T* target, const std::string& text) {
  check_accepted(spec, text);
  *target = parse_value<T>(spec, text);
}

template <typename T>
void set_value(const OptionSpec& spec, std::vector<T>* target, const std::string& text) {
  std::vector<T> values;
  std::stringstream items(text);
  for (std::string item; std::getline(items, item, ',');) {
    check_accepted(spec, item);
    values.push_back(parse_value<T>(spec, item));
  }
  *target = std::move(values);
}

}  // namespace

void apply_option_args(const OptionList& list, const std::vector<std::string>& args) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string name = args[i], value;
    bool inline_value = false;
    if (const std::size_t eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name.resize(eq);
      inline_value = true;
    }
    const OptionSpec* spec = nullptr;
    for (const OptionSpec& candidate : list.specs()) {
      if (spelled_as(candidate, name)) spec = &candidate;
    }
    if (!spec) throw Error("unknown option '" + name + "'");
    if (std::holds_alternative<bool*>(spec->value)) {
      if (inline_value && value != "true" && value != "false")
        throw Error(name + ": a flag takes true or false, not '" + value + "'");
      *std::get<bool*>(spec->value) = !inline_value || value == "true";
    } else {
      if (!inline_value) {
        if (i + 1 >= args.size()) throw Error(name + ": needs a value");
        value = args[++i];
      }
      std::visit([&](auto* target) { set_value(*spec, target, value); }, spec->value);
    }
    if (spec->given) *spec->given = true;
  }
}

}  // namespace prt::bake
