// SPDX-License-Identifier: MIT
// Technique options set from argument lists (prt/baker/options.hpp: apply_option_args), as the
// scene command sets its candidates' settings and a node's extras.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "prt/baker/context.hpp"
#include "prt/baker/options.hpp"

namespace prt::bake {
namespace {

struct Values {
  std::uint32_t order = 3;
  int bits = 16;
  double ratio = 0.5;
  std::string kind = "shadowed";
  bool fast = false, order_given = false;
  std::vector<int> list;

  OptionList options() {
    OptionList list_;
    list_.add("--order", &order, "").range(1, 8).record_given(&order_given);
    list_.add("--bits", &bits, "").choices({8, 16});
    list_.add("-r,--ratio", &ratio, "").range(0.0, 1.0);
    list_.add("--kind", &kind, "").choices({"shadowed", "interreflected"});
    list_.add("--fast", &fast, "");
    list_.add("--list", &list, "");
    return list_;
  }
};

TEST(ApplyOptionArgs, SetsEachKindOfValue) {
  Values v;
  apply_option_args(v.options(), {"--order", "5", "--bits=8", "-r", "0.25", "--kind",
                                  "interreflected", "--fast", "--list", "1,2,3"});
  EXPECT_EQ(v.order, 5u);
  EXPECT_TRUE(v.order_given);
  EXPECT_EQ(v.bits, 8);
  EXPECT_EQ(v.ratio, 0.25);
  EXPECT_EQ(v.kind, "interreflected");
  EXPECT_TRUE(v.fast);
  EXPECT_EQ(v.list, (std::vector<int>{1, 2, 3}));
}

TEST(ApplyOptionArgs, RefusesWhatTheCommandWouldRefuse) {
  const auto refused = [](const std::vector<std::string>& args, const std::string& says) {
    Values v;
    try {
      apply_option_args(v.options(), args);
      ADD_FAILURE() << args[0] << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  refused({"--rays", "4"}, "unknown option '--rays'");
  refused({"--order", "9"}, "--order: 9 is outside [1, 8]");
  refused({"--order", "2.5"}, "not a whole number");
  refused({"--order", "x"}, "'x' is not a number");
  refused({"--order"}, "--order: needs a value");
  refused({"--bits", "12"}, "'12' is not one of 8, 16");
  refused({"--kind", "glossy"}, "is not one of shadowed, interreflected");
  refused({"--fast=yes"}, "a flag takes true or false");
  refused({"--ratio", "nan"}, "is not a number");
}

}  // namespace
}  // namespace prt::bake
