// SPDX-License-Identifier: MIT
// A technique's command-line options described without a parser: name, help text, where the
// value goes (its current value is the default), accepted values or range, and whether it was
// given. prt-bake turns each into a CLI11 option, so the library does not depend on a parser and
// a technique's options can be listed or tested without one.
#pragma once

#include <cstdint>
#include <deque>
#include <initializer_list>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace prt::bake {

struct OptionSpec {
  using Value = std::variant<bool*, int*, std::uint32_t*, double*, std::string*, std::vector<int>*,
                             std::vector<std::uint32_t>*, std::vector<std::string>*>;

  std::string name;  // as the command spells it: "--order", "-o,--output"
  std::string help;
  Value value;                        // a flag when bool*; a comma-separated list when a vector
  std::vector<std::string> accepted;  // the only values allowed, when not empty
  std::optional<std::pair<double, double>> bounds;  // inclusive, checked in the value's type
  bool show_default = true;
  bool* given = nullptr;  // set to whether the option appeared on the command line
  std::string excluded;   // the name of an option of the same list it cannot be given with

  OptionSpec& range(double min, double max) {
    bounds = std::make_pair(min, max);
    return *this;
  }
  OptionSpec& choices(std::vector<std::string> values) {
    accepted = std::move(values);
    return *this;
  }
  OptionSpec& choices(std::initializer_list<long long> values);
  OptionSpec& no_default() {
    show_default = false;
    return *this;
  }
  OptionSpec& record_given(bool* flag) {
    given = flag;
    return *this;
  }
  OptionSpec& excludes(std::string other) {
    excluded = std::move(other);
    return *this;
  }
};

// The options of one command, in the order its help lists them. A deque, so the reference add()
// returns stays valid while more options are added.
class OptionList {
 public:
  template <typename T>
  OptionSpec& add(std::string name, T* value, std::string help) {
    specs_.push_back(
        OptionSpec{std::move(name), std::move(help), value, {}, {}, true, nullptr, {}});
    return specs_.back();
  }
  const std::deque<OptionSpec>& specs() const { return specs_; }

 private:
  std::deque<OptionSpec> specs_;
};

// Sets options of `list` from arguments as a command line spells them: {"--order", "4"} or
// {"--order=4"}; a flag (bool) takes no value. Checks choices and ranges as the command does;
// throws Error naming the option on an unknown name, a missing or bad value.
void apply_option_args(const OptionList& list, const std::vector<std::string>& args);

}  // namespace prt::bake
