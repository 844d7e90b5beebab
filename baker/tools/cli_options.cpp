// SPDX-License-Identifier: MIT
// A technique's option descriptions (prt/baker/options.hpp) as CLI11 options: the one place
// where the library's options meet the parser.
#include <type_traits>
#include <utility>
#include <vector>

#include "command.hpp"

namespace prt::bake::cli {
namespace {

template <typename T>
struct is_vector : std::false_type {};
template <typename T>
struct is_vector<std::vector<T>> : std::true_type {};

// The option for one spec; a range is checked in the value's own type, so the help reads
// "UINT in [1 - 16]" for an unsigned value.
template <typename T>
CLI::Option* add_option(CLI::App* cmd, const OptionSpec& spec, T* value) {
  if constexpr (std::is_same_v<T, bool>) {
    return cmd->add_flag(spec.name, *value, spec.help);
  } else {
    CLI::Option* option = cmd->add_option(spec.name, *value, spec.help);
    if constexpr (is_vector<T>::value) {
      option->delimiter(',');
    } else if constexpr (std::is_arithmetic_v<T>) {
      if (spec.bounds) {
        option->check(
            CLI::Range(static_cast<T>(spec.bounds->first), static_cast<T>(spec.bounds->second)));
      }
    }
    if (!spec.accepted.empty()) option->check(CLI::IsMember(spec.accepted));
    if (spec.show_default) option->capture_default_str();
    return option;
  }
}

}  // namespace

std::function<void()> add_options(CLI::App* cmd, const OptionList& options) {
  std::vector<std::pair<CLI::Option*, bool*>> recorded;
  for (const OptionSpec& spec : options.specs()) {
    CLI::Option* option =
        std::visit([&](auto* value) { return add_option(cmd, spec, value); }, spec.value);
    if (spec.given) recorded.emplace_back(option, spec.given);
  }
  for (const OptionSpec& spec : options.specs()) {
    if (!spec.excluded.empty()) cmd->get_option(spec.name)->excludes(spec.excluded);
  }
  return [recorded] {
    for (const auto& [option, given] : recorded) *given = option->count() > 0;
  };
}

std::vector<std::string> given_option_args(CLI::App* cmd, const OptionList& options) {
  std::vector<std::string> args;
  for (const OptionSpec& spec : options.specs()) {
    const CLI::Option* option = cmd->get_option(spec.name);
    if (option->count() == 0) continue;
    const std::string name = spec.name.substr(spec.name.rfind(',') + 1);
    if (std::holds_alternative<bool*>(spec.value)) {
      args.push_back(name + "=" + (*std::get<bool*>(spec.value) ? "true" : "false"));
      continue;
    }
    std::string value;
    for (const std::string& item : option->results()) value += (value.empty() ? "" : ",") + item;
    args.push_back(name + "=" + value);
  }
  return args;
}

}  // namespace prt::bake::cli
