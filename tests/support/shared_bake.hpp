// SPDX-License-Identifier: MIT
// A bake that every case of a test binary reads. ctest runs each case in a process of its own, so
// prt_add_gtest(... ENVIRONMENT <VARIABLE>=<folder> SETUP <Suite> FIXTURES_REQUIRED <name>) makes
// it once, before the cases: the setup suite's one case calls make_shared_bake, the cases read
// shared_bake_folder. Run by hand, without the variable, a binary makes its own bake the first
// time a case asks.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>

namespace prt_test {

// Makes the bake's files in `folder` (which exists); whether it succeeded.
using BakeInto = std::function<bool(const std::string& folder)>;

// The folder `variable` names, where the setup case made the bake; without the variable,
// `scratch` once `bake` has made it there, or "" when that failed.
inline std::string shared_bake_folder(const char* variable, const std::string& scratch,
                                      const BakeInto& bake) {
  if (const char* folder = std::getenv(variable)) return folder;
  return bake(scratch) ? scratch : std::string();
}

// The setup case: makes the bake in the folder `variable` names; skipped without the variable.
inline void make_shared_bake(const char* variable, const BakeInto& bake) {
  const char* folder = std::getenv(variable);
  if (!folder) GTEST_SKIP() << variable << " is not set: each test binary bakes its own";
  std::filesystem::create_directories(folder);
  EXPECT_TRUE(bake(folder)) << "the shared bake in " << folder << " failed";
}

}  // namespace prt_test
