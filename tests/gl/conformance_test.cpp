// SPDX-License-Identifier: MIT
// Backend conformance (conformance.hpp) for every technique: one row per technique below, its
// cases in tests/<t>/gl/<t>_conformance.cpp, registered as conformance.<Technique><Case>.
#include <gtest/gtest.h>

#include "gl/conformance.hpp"

// The cases of each technique, defined in its folder.
namespace prt_conformance {
std::vector<Case> sh_cases();
std::vector<Case> wavelet_cases();
std::vector<Case> pose_cases();
std::vector<Case> cloth_cases();
std::vector<Case> shadowfield_cases();
}  // namespace prt_conformance

namespace {

struct TechniqueCases {
  const char* name;  // the test name's prefix
  std::vector<prt_conformance::Case> (*cases)();
};

const TechniqueCases kTechniques[] = {
    {"Sh", prt_conformance::sh_cases},
    {"Wavelet", prt_conformance::wavelet_cases},
    {"Pose", prt_conformance::pose_cases},
    {"Cloth", prt_conformance::cloth_cases},
    {"Shadowfield", prt_conformance::shadowfield_cases},
};

class ConformanceCase : public ::testing::Test {
 public:
  explicit ConformanceCase(std::function<void()> run) : run_(std::move(run)) {}
  void TestBody() override { run_(); }

 private:
  std::function<void()> run_;
};

// Registered before main, so that gtest_discover_tests lists every case.
[[maybe_unused]] const bool kRegistered = [] {
  for (const TechniqueCases& technique : kTechniques)
    for (const prt_conformance::Case& c : technique.cases()) {
      const std::string name = technique.name + c.name;
      ::testing::RegisterTest(
          "conformance", name.c_str(), nullptr, nullptr, __FILE__, __LINE__,
          [run = c.run]() -> ::testing::Test* { return new ConformanceCase(run); });
    }
  return true;
}();

}  // namespace
