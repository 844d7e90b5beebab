// SPDX-License-Identifier: MIT
// What `prt-bake bake <technique> --help` must say, for every technique's CLI test: each of the
// technique's own flags (from its Technique entry, not a list kept in the test), the flags every
// bake shares, and none of the flags only other techniques have.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <set>
#include <string>

#include "prt/baker/technique.hpp"

namespace prt_test {

// Whether `help` lists the flag `name` ("-o,--output" is listed as "--output"): its long name
// followed by a space, '=' or a newline, so "--keep" is not found in "--keep-energy".
inline bool lists_flag(const std::string& help, const std::string& name) {
  const std::string flag = name.substr(name.rfind(',') + 1);
  for (std::size_t at = help.find(flag); at != std::string::npos; at = help.find(flag, at + 1)) {
    const char next = at + flag.size() < help.size() ? help[at + flag.size()] : ' ';
    if (next == ' ' || next == '=' || next == '\n') return true;
  }
  return false;
}

// Checks `help` (the output of `bake <technique> --help`) and returns the technique's own flags.
inline std::set<std::string> expect_help_lists_own_flags_only(const std::string& help,
                                                              const std::string& technique) {
  std::set<std::string> own;
  const prt::bake::Technique* entry = prt::bake::find_technique(technique);
  EXPECT_NE(entry, nullptr) << technique;
  if (!entry) return own;
  const std::unique_ptr<prt::bake::TechniqueBake> bake = entry->make_bake();
  const prt::bake::OptionList options = bake->options();  // holds pointers into `bake`
  for (const prt::bake::OptionSpec& spec : options.specs()) {
    own.insert(spec.name);
    EXPECT_TRUE(lists_flag(help, spec.name)) << spec.name << "\n" << help;
  }
  for (const char* shared : {"--albedo", "--seed", "--output", "--report", "SCENE"})
    EXPECT_NE(help.find(shared), std::string::npos) << shared;
  std::size_t foreign = 0;
  for (const prt::bake::Technique* other : prt::bake::techniques()) {
    if (std::string(other->name()) == technique) continue;
    const std::unique_ptr<prt::bake::TechniqueBake> other_bake = other->make_bake();
    const prt::bake::OptionList other_options = other_bake->options();
    for (const prt::bake::OptionSpec& spec : other_options.specs()) {
      if (own.count(spec.name)) continue;
      ++foreign;
      EXPECT_FALSE(lists_flag(help, spec.name)) << spec.name << "\n" << help;
    }
  }
  EXPECT_GT(foreign, 0u) << "no other technique has a flag of its own to look for";
  EXPECT_FALSE(lists_flag(help, "--technique"));
  return own;
}

}  // namespace prt_test
