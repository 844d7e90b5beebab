// SPDX-License-Identifier: MIT
// The scripted rigid paths (prt/io/rigid_path.hpp) that technique `shadowfield`'s scenes and app
// move instances along: keyframes returned exactly, midpoints against the analytic average and
// half-angle rotation, the loop's period and its wrap-around segment, slerp's unit length and
// shorter arc, a constant path, and the errors of bad paths.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>

#include "prt/io/error.hpp"
#include "prt/io/rigid_path.hpp"

namespace prt::io {
namespace {

constexpr float kPi = glm::pi<float>();

glm::quat turn(float radians, glm::vec3 axis) {
  return glm::angleAxis(radians, glm::normalize(axis));
}

// Rotations compared by what they do (q and -q are the same rotation).
void expect_same_rotation(const glm::quat& a, const glm::quat& b, float tolerance) {
  for (const glm::vec3& v : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}) {
    const glm::vec3 d = a * v - b * v;
    EXPECT_LE(glm::length(d), tolerance);
  }
}

// Three keyframes at uneven times; the loop returns to the first at time 4.
RigidPath three_keyframes() {
  RigidPath path;
  path.duration = 4.0f;
  path.keyframes = {
      {0.0f, {{0.0f, 0.0f, 0.0f}, turn(0.0f, {0, 1, 0}), 1.0f}},
      {1.0f, {{2.0f, 1.0f, -1.0f}, turn(0.5f * kPi, {0, 1, 0}), 2.0f}},
      {3.0f, {{-1.0f, 0.5f, 3.0f}, turn(0.4f * kPi, {1, 1, 0}), 0.5f}},
  };
  return path;
}

TEST(RigidPath, KeyframesAreReturnedExactly) {
  const RigidPath path = three_keyframes();
  for (const RigidKeyframe& k : path.keyframes) {
    const RigidPlacement p = path.at(k.time);
    EXPECT_EQ(p.translation, k.placement.translation);
    EXPECT_EQ(p.scale, k.placement.scale);
    expect_same_rotation(p.rotation, k.placement.rotation, 1e-6f);
  }
}

TEST(RigidPath, MidpointsAreTheAverageAndTheHalfTurn) {
  const RigidPath path = three_keyframes();
  const RigidPlacement p = path.at(0.5f);
  EXPECT_EQ(p.translation, glm::vec3(1.0f, 0.5f, -0.5f));
  EXPECT_FLOAT_EQ(p.scale, 1.5f);
  // Between yaw 0 and a quarter turn: an eighth of a turn about +Y.
  expect_same_rotation(p.rotation, turn(0.25f * kPi, {0, 1, 0}), 1e-6f);
  // A quarter of the way from keyframe 1 to 2 (times 1 and 3).
  const RigidPlacement q = path.at(1.5f);
  EXPECT_FLOAT_EQ(q.translation.x, 2.0f + 0.25f * (-1.0f - 2.0f));
  EXPECT_FLOAT_EQ(q.scale, 2.0f + 0.25f * (0.5f - 2.0f));
}

TEST(RigidPath, SlerpFollowsTheGreatCircleAtConstantSpeed) {
  // Two turns about one axis: the interpolant is the turn by the interpolated angle.
  RigidPath path;
  path.duration = 2.0f;
  const glm::vec3 axis(0.3f, -0.5f, 0.8f);
  path.keyframes = {{0.0f, {{}, turn(0.2f, axis), 1.0f}}, {1.0f, {{}, turn(1.7f, axis), 1.0f}}};
  for (float t : {0.1f, 0.37f, 0.5f, 0.9f}) {
    expect_same_rotation(path.at(t).rotation, turn(0.2f + t * 1.5f, axis), 1e-6f);
  }
}

TEST(RigidPath, LoopsWithItsDurationThroughTheWrapSegment) {
  const RigidPath path = three_keyframes();
  // Halfway from the last keyframe (time 3) back to the first (time 4 = 0 + duration).
  const RigidPlacement wrap = path.at(3.5f);
  EXPECT_EQ(wrap.translation, glm::vec3(-0.5f, 0.25f, 1.5f));
  EXPECT_FLOAT_EQ(wrap.scale, 0.75f);
  expect_same_rotation(wrap.rotation, turn(0.2f * kPi, {1, 1, 0}), 1e-6f);
  for (float t : {0.25f, 1.5f, 3.5f}) {
    for (float period : {-2.0f, -1.0f, 1.0f, 3.0f}) {
      const RigidPlacement a = path.at(t), b = path.at(t + period * path.duration);
      EXPECT_EQ(a.translation, b.translation) << t << " + " << period << " periods";
      EXPECT_EQ(a.scale, b.scale);
      expect_same_rotation(a.rotation, b.rotation, 1e-6f);
    }
  }
}

TEST(RigidPath, StaysOnThePathAtExtremeTimes) {
  const RigidPath path = three_keyframes();
  for (float t : {-1e7f, 1e7f, 3e38f, -3e38f, 1e-30f}) {
    const RigidPlacement p = path.at(t);
    EXPECT_TRUE(std::isfinite(p.translation.x + p.translation.y + p.translation.z)) << t;
    EXPECT_NEAR(glm::length(p.rotation), 1.0f, 2.5e-7f) << t;
    EXPECT_GE(p.scale, 0.5f) << t;  // the keyframes' smallest scale
    EXPECT_LE(p.scale, 2.0f) << t;  // and largest
  }
}

TEST(RigidPath, WrapsBeforeAFirstKeyframeThatIsNotAtZero) {
  RigidPath path;
  path.duration = 4.0f;
  path.keyframes = {{1.0f, {{0.0f, 0.0f, 0.0f}, glm::quat(1, 0, 0, 0), 1.0f}},
                    {3.0f, {{4.0f, 0.0f, 0.0f}, glm::quat(1, 0, 0, 0), 3.0f}}};
  // The wrap segment runs from time 3 to 5 (= 1 + 4): time 0 is its middle.
  EXPECT_EQ(path.at(0.0f).translation, glm::vec3(2.0f, 0.0f, 0.0f));
  EXPECT_EQ(path.at(0.0f).scale, 2.0f);
  EXPECT_EQ(path.at(4.5f).translation, glm::vec3(1.0f, 0.0f, 0.0f));
}

TEST(RigidPath, SlerpStaysUnitAndTakesTheShorterArc) {
  RigidPath path;
  path.duration = 3.0f;
  path.keyframes = {{0.0f, {{}, turn(2.9f, {1, 2, 3}), 1.0f}},
                    {1.0f, {{}, turn(-2.5f, {-3, 1, 0.5f}), 1.0f}},
                    {2.0f, {{}, -turn(2.9f, {1, 2, 3}), 1.0f}}};
  float worst = 0.0f;
  for (int i = 0; i <= 300; ++i) {
    worst = std::max(worst, std::abs(glm::length(path.at(0.01f * float(i)).rotation) - 1.0f));
  }
  EXPECT_LE(worst, 2.5e-7f);  // two float steps of 1
  // Keyframes 2 and 0 are q and -q, one rotation: the wrap segment must not turn at all.
  for (float t : {2.25f, 2.5f, 2.75f}) {
    expect_same_rotation(path.at(t).rotation, turn(2.9f, {1, 2, 3}), 1e-6f);
  }
}

TEST(RigidPath, OneKeyframeIsAConstantPlacement) {
  RigidPath path;
  const RigidPlacement place{{1.0f, 2.0f, 3.0f}, turn(1.0f, {0, 0, 1}), 0.25f};
  path.keyframes = {{0.0f, place}};
  for (float t : {-100.0f, 0.0f, 0.7f, 1e6f}) {
    const RigidPlacement p = path.at(t);
    EXPECT_EQ(p.translation, place.translation);
    EXPECT_EQ(p.scale, place.scale);
    expect_same_rotation(p.rotation, place.rotation, 1e-6f);
  }
}

TEST(RigidPath, PlacementAppliesScaleRotationThenTranslation) {
  const RigidPlacement p{{1.0f, 0.0f, 0.0f}, turn(0.5f * kPi, {0, 1, 0}), 2.0f};
  // A quarter turn about +Y takes +Z to +X.
  const glm::vec3 world = p.apply({0.0f, 0.0f, 1.0f});
  EXPECT_NEAR(world.x, 3.0f, 3e-7f);
  EXPECT_NEAR(world.y, 0.0f, 3e-7f);
  EXPECT_NEAR(world.z, 0.0f, 3e-7f);
}

TEST(RigidPath, BadPathsAreRejected) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(RigidPath{}.at(0.0f), Error);
  auto broken = [](auto change) {
    RigidPath path = three_keyframes();
    change(path);
    return path;
  };
  EXPECT_THROW(broken([](RigidPath& p) { p.duration = 3.0f; }).check(), Error);
  EXPECT_THROW(broken([](RigidPath& p) { p.duration = 0.0f; }).check(), Error);
  EXPECT_THROW(broken([](RigidPath& p) { p.keyframes[1].time = 0.0f; }).check(), Error);
  EXPECT_THROW(broken([](RigidPath& p) { p.keyframes[0].time = -1.0f; }).check(), Error);
  EXPECT_THROW(broken([](RigidPath& p) { p.keyframes[2].placement.scale = 0.0f; }).check(), Error);
  EXPECT_THROW(broken([&](RigidPath& p) { p.keyframes[1].placement.translation.y = nan; }).check(),
               Error);
  EXPECT_THROW(broken([&](RigidPath& p) { p.keyframes[1].placement.rotation.w = nan; }).check(),
               Error);
  EXPECT_THROW(broken([](RigidPath& p) {
                 p.keyframes[1].placement.rotation = {0, 0, 0, 0};
               }).check(),
               Error);
  EXPECT_NO_THROW(three_keyframes().check());
  EXPECT_THROW(three_keyframes().at(nan), Error);
  EXPECT_THROW(three_keyframes().at(std::numeric_limits<float>::infinity()), Error);
}

}  // namespace
}  // namespace prt::io
