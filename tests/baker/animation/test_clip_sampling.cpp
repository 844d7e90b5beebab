// SPDX-License-Identifier: MIT
// Keyframe interpolation (glTF 2.0 Appendix C) against closed forms: lines through linear keys,
// rotations about one axis by known angles, cubics that a Hermite spline with their own
// derivatives as tangents reproduces; and the instants a clip is sampled at.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "prt/baker/animation.hpp"

namespace prt::bake {
namespace {

using Channel = AnimationChannel;

Channel make_channel(Channel::Path path, Channel::Interpolation interpolation,
                     std::vector<float> times, std::vector<float> values, int components) {
  Channel c;
  c.node = 0;
  c.path = path;
  c.interpolation = interpolation;
  c.times = std::move(times);
  c.values = std::move(values);
  c.components = components;
  return c;
}

// A rotation by `angle` about +Z as glTF stores it (x, y, z, w).
std::vector<float> about_z(double angle) {
  return {0.0f, 0.0f, float(std::sin(angle / 2)), float(std::cos(angle / 2))};
}

void expect_near4(const glm::vec4& got, const glm::vec4& want, float tol) {
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(got[i], want[i], tol) << "component " << i;
}

TEST(SampleChannel, LinearKeysFollowTheLineBetweenThem) {
  const Channel c = make_channel(Channel::Path::Translation, Channel::Interpolation::Linear,
                                 {0.0f, 1.0f, 3.0f}, {0, 0, 0, 2, 4, 6, 2, 0, -6}, 3);
  expect_near4(sample_channel(c, 0.25f), {0.5f, 1.0f, 1.5f, 0.0f}, 1e-6f);
  expect_near4(sample_channel(c, 2.0f), {2.0f, 2.0f, 0.0f, 0.0f}, 1e-6f);
  // Keys are hit exactly; outside the keys the first and last values hold; NaN gives the first.
  expect_near4(sample_channel(c, 1.0f), {2.0f, 4.0f, 6.0f, 0.0f}, 0.0f);
  expect_near4(sample_channel(c, -5.0f), {0.0f, 0.0f, 0.0f, 0.0f}, 0.0f);
  expect_near4(sample_channel(c, 99.0f), {2.0f, 0.0f, -6.0f, 0.0f}, 0.0f);
  expect_near4(sample_channel(c, std::numeric_limits<float>::quiet_NaN()), glm::vec4(0.0f), 0.0f);
}

TEST(SampleChannel, StepHoldsEachKeyUntilTheNext) {
  const Channel c = make_channel(Channel::Path::Scale, Channel::Interpolation::Step, {0.0f, 1.0f},
                                 {1, 1, 1, 3, 3, 3}, 3);
  EXPECT_EQ(sample_channel(c, 0.999f).x, 1.0f);
  EXPECT_EQ(sample_channel(c, 1.0f).x, 3.0f);
}

TEST(SampleChannel, RotationsSlerpByAngleAlongTheShorterArc) {
  const double quarter = M_PI / 2;
  std::vector<float> values = about_z(0.0);
  const std::vector<float> end = about_z(quarter);
  values.insert(values.end(), end.begin(), end.end());
  Channel c = make_channel(Channel::Path::Rotation, Channel::Interpolation::Linear, {0.0f, 2.0f},
                           values, 4);
  for (double s : {0.1, 0.25, 0.5, 0.9}) {
    const std::vector<float> want = about_z(s * quarter);
    expect_near4(sample_channel(c, float(2.0 * s)), {want[0], want[1], want[2], want[3]}, 2e-7f);
  }
  // -q is the same rotation: the interpolation must not take the long way round through it.
  for (int i = 4; i < 8; ++i) c.values[i] = -c.values[i];
  const glm::vec4 mid = sample_channel(c, 1.0f);
  const std::vector<float> want = about_z(quarter / 2);
  expect_near4(mid, {want[0], want[1], want[2], want[3]}, 2e-7f);
}

TEST(SampleChannel, NearlyEqualRotationsStayUnitLength) {
  std::vector<float> values = about_z(0.0);
  const std::vector<float> end = about_z(1e-4);
  values.insert(values.end(), end.begin(), end.end());
  const Channel c = make_channel(Channel::Path::Rotation, Channel::Interpolation::Linear,
                                 {0.0f, 1.0f}, values, 4);
  const glm::vec4 q = sample_channel(c, 0.5f);
  EXPECT_NEAR(glm::length(q), 1.0f, 1e-7f);
  EXPECT_NEAR(q.z, std::sin(0.25e-4), 1e-7);
}

// p(t) = 1 - 2t + 0.5t^2 + 0.25t^3 (and 3 p in y): a Hermite spline whose tangents are p'
// reproduces any cubic, whatever the key spacing (glTF scales tangents by the interval).
double cubic_p(double t) {
  return 1.0 - 2.0 * t + 0.5 * t * t + 0.25 * t * t * t;
}
double cubic_dp(double t) {
  return -2.0 + t + 0.75 * t * t;
}

TEST(SampleChannel, CubicSplineWithTheDerivativesAsTangentsIsTheCubic) {
  const std::vector<float> times = {0.0f, 0.5f, 2.0f, 2.25f};
  std::vector<float> values;
  for (float t : times) {
    for (double v : {cubic_dp(t), cubic_p(t), cubic_dp(t)})  // in-tangent, value, out-tangent
      values.insert(values.end(), {float(v), float(3 * v), 0.0f});
  }
  const Channel c = make_channel(Channel::Path::Translation, Channel::Interpolation::CubicSpline,
                                 times, values, 3);
  for (double t = 0.0; t <= 2.25; t += 0.0625) {
    const glm::vec4 v = sample_channel(c, float(t));
    EXPECT_NEAR(v.x, cubic_p(t), 2e-6) << "t = " << t;
    EXPECT_NEAR(v.y, 3 * cubic_p(t), 6e-6) << "t = " << t;
  }
}

TEST(SampleChannel, CubicSplineRotationsComeBackNormalised) {
  std::vector<float> values;
  for (double angle : {0.0, 1.0}) {
    const std::vector<float> q = about_z(angle), zero(4, 0.0f);
    values.insert(values.end(), zero.begin(), zero.end());
    values.insert(values.end(), q.begin(), q.end());
    values.insert(values.end(), zero.begin(), zero.end());
  }
  const Channel c = make_channel(Channel::Path::Rotation, Channel::Interpolation::CubicSpline,
                                 {0.0f, 1.0f}, values, 4);
  EXPECT_NEAR(glm::length(sample_channel(c, 0.5f)), 1.0f, 1e-7f);
}

TEST(ClipTimes, EveryFrameOfTheRateAndTheLastKey) {
  Animation clip;
  clip.duration = 1.0f;
  const std::vector<float> thirty = clip_times(clip, 30.0);
  ASSERT_EQ(thirty.size(), 31u);
  EXPECT_EQ(thirty.front(), 0.0f);
  EXPECT_FLOAT_EQ(thirty.back(), 1.0f);
  clip.duration = 1.05f;
  const std::vector<float> ten = clip_times(clip, 10.0);
  ASSERT_EQ(ten.size(), 12u);
  EXPECT_FLOAT_EQ(ten[10], 1.0f);
  EXPECT_EQ(ten[11], 1.05f);
  clip.duration = 0.0f;
  EXPECT_EQ(clip_times(clip, 24.0), std::vector<float>{0.0f});
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::quiet_NaN()})
    EXPECT_THROW(clip_times(clip, bad), Error);
}

}  // namespace
}  // namespace prt::bake
