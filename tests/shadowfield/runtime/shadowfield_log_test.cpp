// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s log-space product (runtime/src/shadowfield/shadowfield_log.h): the
// exponential against the C library's, the direction-space exponential and the log fields
// against projections on a fine midpoint grid, and scenes of many blockers against the product of
// their visibilities taken in direction space.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "shadowfield/runtime/shadowfield_test_scene.hpp"

namespace prt::test {
namespace {

const float kEye[3] = {2.0f, 30.0f, 1.0f};
const double kSqrt4Pi = std::sqrt(4.0 * kSfPi);

// A visibility mean + swing (d . w) as order-n coefficients (bands 0 and 1), d in the SH frame.
std::vector<float> lobe(uint32_t order, float mean, float swing, const float d[3]) {
  std::vector<float> c(order * order, 0.0f);
  c[0] = float(mean * kSqrt4Pi);
  const float scale = float(swing * std::sqrt(4.0 * kSfPi / 3.0));
  c[1] = scale * d[1];
  c[2] = scale * d[2];
  c[3] = scale * d[0];
  return c;
}

void* test_alloc(void*, size_t size, size_t align) {
  return std::aligned_alloc(align, (size + align - 1) / align * align);
}
void test_free(void*, void* ptr, size_t) {
  std::free(ptr);
}

// A quadrature of shadowfield_log.h on the C library's allocator.
struct Rule {
  prt_allocator allocator{test_alloc, test_free, nullptr};
  prt_sf_sphere_rule rule{};
  Rule(uint32_t order, bool fine) {
    EXPECT_EQ(fine ? prt_sf_log_rule_build(&allocator, order, &rule)
                   : prt_sf_exp_rule_build(&allocator, order, &rule),
              PRT_OK);
  }
  ~Rule() { prt_sf_sphere_rule_free(&allocator, &rule); }
};

double max_relative(const std::vector<float>& got, const std::vector<double>& want, double scale) {
  double worst = 0.0;
  for (size_t i = 0; i < got.size(); ++i) worst = std::max(worst, std::fabs(got[i] - want[i]));
  return worst / scale;
}

TEST(ShadowfieldLog, TheExponentialAgreesWithTheLibrarys) {
  double worst = 0.0;
  for (double x = -87.0; x <= 88.0; x += 0.001) {
    const float xf = float(x);
    const double want = std::exp(double(xf));
    worst = std::max(worst, std::fabs(prt_sf_exp(xf) - want) / want);
  }
  std::printf("prt_sf_exp: largest relative error %.3g\n", worst);
  EXPECT_LT(worst, 2e-7);  // measured 9.4e-8, under one float ulp
  EXPECT_EQ(prt_sf_exp(-1000.0f), prt_sf_exp(-87.0f));
  EXPECT_GT(prt_sf_exp(-1000.0f), 0.0f);
  EXPECT_TRUE(std::isfinite(prt_sf_exp(1000.0f)));
  EXPECT_EQ(prt_sf_exp(std::numeric_limits<float>::quiet_NaN()), prt_sf_exp(-87.0f));
  EXPECT_EQ(prt_sf_exp(-std::numeric_limits<float>::infinity()), prt_sf_exp(-87.0f));
}

TEST(ShadowfieldLog, TheExponentialOfAConstantIsExact) {
  const uint32_t order = 4, n2 = 16;
  Rule rule(order, false);
  std::vector<float> lanes(n2 * PRT_SF_LANES, 0.0f);
  for (uint32_t lane = 0; lane < PRT_SF_LANES; ++lane)
    lanes[lane] = float(kSqrt4Pi * (-10.0 + 1.3 * lane));  // the function -10 + 1.3 lane
  prt_sf_kernels_scalar.exp_lanes(&rule.rule, lanes.data(), 0xFFu);
  for (uint32_t lane = 0; lane < PRT_SF_LANES; ++lane) {
    const double want = kSqrt4Pi * std::exp(-10.0 + 1.3 * lane);
    EXPECT_NEAR(lanes[lane], want, 2e-6 * want) << lane;
    for (uint32_t i = 1; i < n2; ++i) EXPECT_NEAR(lanes[i * PRT_SF_LANES + lane], 0.0, 2e-6 * want);
  }
}

TEST(ShadowfieldLog, TheExponentialMatchesAFineProjection) {
  // exp of a log lobe from -4.6 (1 %) to 0 at each order: the direction-space exponential against
  // exp(f) projected on a fine midpoint grid.
  const float d[3] = {0.36f, 0.48f, 0.8f};
  for (uint32_t order = 2; order <= 6; ++order) {
    const uint32_t n2 = order * order;
    Rule rule(order, false);
    const std::vector<float> f = lobe(order, -2.3f, 2.3f, d);
    std::vector<float> lanes(n2 * PRT_SF_LANES, 0.0f);
    for (uint32_t i = 0; i < n2; ++i) lanes[i * PRT_SF_LANES + 3] = f[i];
    prt_sf_kernels_scalar.exp_lanes(&rule.rule, lanes.data(), 1u << 3);
    std::vector<float> got(n2);
    for (uint32_t i = 0; i < n2; ++i) got[i] = lanes[i * PRT_SF_LANES + 3];
    const std::vector<double> want = project_dense(
        order, [&](const float* w) { return std::exp(sh_value(order, f.data(), w)); });
    const double error = max_relative(got, want, want[0]);
    std::printf("order %u: exponential's largest coefficient error %.3g of the DC\n", order, error);
    EXPECT_LT(error, order == 2 ? 3.2e-4 : 7.5e-5) << order;  // measured 1.3e-4, 2e-5 to 3e-5
  }
}

TEST(ShadowfieldLog, TheLogFieldIsTheProjectionOfTheClampedLog) {
  const uint32_t order = 4, n2 = 16;
  Rule fine(order, true);
  const float d[3] = {0.0f, 0.6f, 0.8f};
  std::vector<float> field;
  const std::vector<float> open = lobe(order, 1.0f, 0.0f, d), shut(n2, 0.0f);
  const std::vector<float> smooth = lobe(order, 0.5f, 0.4f, d), deep = lobe(order, 0.3f, 0.6f, d);
  for (const auto* point : {&open, &shut, &smooth, &deep})
    field.insert(field.end(), point->begin(), point->end());
  std::vector<float> logs(field.size());
  prt_sf_log_of_field(&fine.rule, field.data(), 4, PRT_SF_LOG_FLOOR, logs.data());
  for (uint32_t i = 0; i < n2; ++i) EXPECT_NEAR(logs[i], 0.0f, 1e-6f) << i;
  EXPECT_NEAR(logs[n2], kSqrt4Pi * std::log(PRT_SF_LOG_FLOOR), 1e-5);
  for (uint32_t i = 1; i < n2; ++i) EXPECT_NEAR(logs[n2 + i], 0.0f, 1e-5f) << i;
  // A smooth visibility in [0.1, 0.9], and one that the floor cuts (down to -0.3).
  const double bounds[2] = {4e-5, 2e-3};  // measured 1.6e-5 and 7.7e-4
  for (int p = 2; p < 4; ++p) {
    const float* v = field.data() + p * n2;
    const std::vector<double> want = project_dense(order, [&](const float* w) {
      return std::log(std::max(sh_value(order, v, w), double(PRT_SF_LOG_FLOOR)));
    });
    const std::vector<float> got(logs.begin() + p * n2, logs.begin() + (p + 1) * n2);
    const double error = max_relative(got, want, std::fabs(want[0]));
    std::printf("log field, point %d: largest coefficient error %.3g of the DC\n", p, error);
    EXPECT_LT(error, bounds[p - 2]) << p;
  }
}

// A receiver patch under `blockers` instances of `blocker` around it (each within its outer
// shell), shaded with the product given.
std::vector<float> shade_under(SyntheticObject& receiver, SyntheticObject& blocker,
                               uint32_t blockers, prt_shadowfield_product product,
                               const std::vector<float>& light) {
  TestScene s(std::max(blockers + 1, 2u));
  EXPECT_EQ(prt_shadowfield_scene_set_product(s.scene, product), PRT_OK);
  s.add_instance(s.add_object(receiver), make_transform(identity_rotation(), 0, 0, 0));
  const uint32_t object = s.add_object(blocker);
  for (uint32_t b = 0; b < blockers; ++b) {
    const float angle = 2.0f * float(kSfPi) * float(b) / float(blockers);
    s.add_instance(object, make_transform(identity_rotation(), 2.0f * std::cos(angle),
                                          1.0f + 0.1f * float(b), 2.0f * std::sin(angle)));
  }
  return s.shade(light, kEye, 0)[0];
}

TEST(ShadowfieldLog, ManyUniformBlockersMultiplyTheirTransmittances) {
  // Twenty blockers that each pass 0.9 of the light in every direction: 0.9^20 of it reaches
  // the receiver, with either product.
  SyntheticObject receiver = make_patch(4, 3), blocker = make_patch(4, 2);
  std::vector<float> uniform(16, 0.0f);
  uniform[0] = float(0.9 * kSqrt4Pi);
  blocker.set_constant_oof(uniform);
  const std::vector<float> light = test_light(4);
  const std::vector<float> open =
      shade_under(receiver, blocker, 0, PRT_SHADOWFIELD_PRODUCT_TRIPLE, light);
  const double pass = std::pow(0.9, 20.0);
  for (const auto product : {PRT_SHADOWFIELD_PRODUCT_TRIPLE, PRT_SHADOWFIELD_PRODUCT_LOG}) {
    const std::vector<float> out = shade_under(receiver, blocker, 20, product, light);
    for (size_t e = 0; e < out.size(); ++e)
      EXPECT_NEAR(out[e], pass * open[e], 4e-6 * max_abs(open)) << product << " " << e;
  }
}

TEST(ShadowfieldLog, ManyBlockersMatchTheirProductInDirectionSpace) {
  // Blockers of one lobe each, all read unturned (no rotation); the receiver's light is the
  // environment times all their visibilities, which a fine midpoint grid projects: the receiver
  // alone under that light is the reference for both products.
  const uint32_t order = 4, blockers = 12;
  SyntheticObject receiver = make_patch(order, 3), blocker = make_patch(order, 2);
  const float d[3] = {0.6f, 0.0f, 0.8f};
  blocker.set_constant_oof(lobe(order, 0.75f, 0.2f, d));
  const std::vector<float> light = test_light(order);
  std::vector<float> shadowed(light.size());
  for (uint32_t c = 0; c < 3; ++c) {
    std::vector<float> env(16);
    for (uint32_t i = 0; i < 16; ++i) env[i] = light[3 * i + c];
    const std::vector<float> v = lobe(order, 0.75f, 0.2f, d);
    const std::vector<double> product = project_dense(order, [&](const float* w) {
      return sh_value(order, env.data(), w) * std::pow(sh_value(order, v.data(), w), blockers);
    });
    for (uint32_t i = 0; i < 16; ++i) shadowed[3 * i + c] = float(product[i]);
  }
  SyntheticObject alone = make_patch(order, 3);
  const std::vector<float> want =
      shade_under(alone, blocker, 0, PRT_SHADOWFIELD_PRODUCT_TRIPLE, shadowed);
  double errors[2];
  for (const auto product : {PRT_SHADOWFIELD_PRODUCT_TRIPLE, PRT_SHADOWFIELD_PRODUCT_LOG}) {
    const std::vector<float> got = shade_under(receiver, blocker, blockers, product, light);
    errors[product] = max_difference(got, want) / max_abs(want);
    std::printf("%u blockers, %s product: largest error %.3g of the largest radiance\n", blockers,
                product == PRT_SHADOWFIELD_PRODUCT_LOG ? "log" : "triple", errors[product]);
  }
  EXPECT_LT(errors[PRT_SHADOWFIELD_PRODUCT_TRIPLE], 0.017);  // measured 0.0070
  EXPECT_LT(errors[PRT_SHADOWFIELD_PRODUCT_LOG], 0.014);     // measured 0.0057
}

TEST(ShadowfieldLog, TheProductIsAsSetAndTripleAgainGivesItsFramesBitwise) {
  SyntheticObject receiver = make_patch(4, 3), blocker = make_patch(4, 2);
  const float d[3] = {0.0f, 0.6f, 0.8f};
  blocker.set_constant_oof(lobe(4, 0.6f, 0.3f, d));
  const std::vector<float> light = test_light(4);
  TestScene s(2);
  EXPECT_EQ(prt_shadowfield_scene_product(s.scene), PRT_SHADOWFIELD_PRODUCT_TRIPLE);
  // Set before any object: each object's log field is made when it is added.
  ASSERT_EQ(prt_shadowfield_scene_set_product(s.scene, PRT_SHADOWFIELD_PRODUCT_LOG), PRT_OK);
  s.add_instance(s.add_object(receiver), make_transform(identity_rotation(), 0, 0, 0));
  s.add_instance(s.add_object(blocker), make_transform(identity_rotation(), 0, 1, 0));
  EXPECT_EQ(prt_shadowfield_scene_product(s.scene), PRT_SHADOWFIELD_PRODUCT_LOG);
  EXPECT_NE(s.scene->log_fields[1].values, nullptr);
  const std::vector<float> log_out = s.shade(light, kEye, 0)[0];
  ASSERT_EQ(prt_shadowfield_scene_set_product(s.scene, PRT_SHADOWFIELD_PRODUCT_TRIPLE), PRT_OK);
  EXPECT_EQ(s.scene->log_fields[1].values, nullptr);
  const std::vector<float> triple_out = s.shade(light, kEye, 0)[0];
  // The same frame in a scene that never had the log product.
  TestScene plain(2);
  plain.add_instance(plain.add_object(receiver), make_transform(identity_rotation(), 0, 0, 0));
  plain.add_instance(plain.add_object(blocker), make_transform(identity_rotation(), 0, 1, 0));
  EXPECT_EQ(max_difference(triple_out, plain.shade(light, kEye, 0)[0]), 0.0);
  // One smooth blocker: the two products differ by the log's floor and truncation only.
  const double difference = max_difference(log_out, triple_out) / max_abs(triple_out);
  std::printf("one blocker: log against triple %.3g of the largest radiance\n", difference);
  EXPECT_GT(difference, 0.0);
  EXPECT_LT(difference, 3e-4);  // measured 1.1e-4
}

TEST(ShadowfieldLog, AnUnknownProductIsRefusedAndKeepsTheScenes) {
  TestScene s(1);
  EXPECT_EQ(prt_shadowfield_scene_set_product(nullptr, PRT_SHADOWFIELD_PRODUCT_LOG),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_scene_set_product(s.scene, prt_shadowfield_product(7)),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(prt_context_last_message(s.context)).find("product 7"), std::string::npos);
  EXPECT_EQ(prt_shadowfield_scene_product(s.scene), PRT_SHADOWFIELD_PRODUCT_TRIPLE);
  EXPECT_EQ(prt_shadowfield_scene_product(nullptr), PRT_SHADOWFIELD_PRODUCT_TRIPLE);
}

// One blocker under a white sky, as the irradiance over pi of a receiver whose normal is turned
// from the vertical: the truth (the binary visibility, integrated finely), the triple product's
// (the order-4 projection of the visibility, which is exact for it: the cosine lobe has order 3)
// and the log product's, exp of the projected log. A small blocker (a cap of 30 degrees) comes
// out as with the triple product; a half-space one, whose log is a deep step the order cannot
// hold, comes out brighter.
TEST(ShadowfieldLog, ASmallBlockerIsKeptAndAHalfSpaceOneLeftBrighter) {
  const uint32_t order = 4, n2 = 16;
  Rule fine(order, true), rule(order, false);
  const double axis[3] = {0.5, 0.5, 0.70710678};
  struct Case {
    double cap;  // blocked where the cosine to axis exceeds it; -1: below the horizon
    double low, high;
  };
  // Measured log / truth: cap of 30 degrees 1.002 to 1.004, half-space 1.088 to 1.107.
  for (const Case c : {Case{0.866, 0.995, 1.01}, Case{-1.0, 1.06, 1.13}}) {
    auto visible = [&](const float* w) {
      if (c.cap < -0.5) return w[1] > 0.0f ? 1.0 : 0.0;
      return w[0] * axis[0] + w[1] * axis[1] + w[2] * axis[2] > c.cap ? 0.0 : 1.0;
    };
    const std::vector<double> projected = project_dense(order, visible);
    const std::vector<float> v(projected.begin(), projected.end());
    std::vector<float> logs(n2), lanes(n2 * PRT_SF_LANES, 0.0f);
    prt_sf_log_of_field(&fine.rule, v.data(), 1, PRT_SF_LOG_FLOOR, logs.data());
    for (uint32_t i = 0; i < n2; ++i) lanes[i * PRT_SF_LANES] = logs[i];
    prt_sf_kernels_scalar.exp_lanes(&rule.rule, lanes.data(), 1u);
    for (const double tilt : {0.0, 0.5, 1.0, 1.5}) {
      const float n[3] = {float(std::sin(tilt)), float(std::cos(tilt)), 0.0f};
      std::vector<float> y(n2);
      prt_sh_eval(order, n, y.data());
      double triple = 0.0, log_product = 0.0;
      for (uint32_t i = 0; i < n2; ++i) {
        const uint32_t l = uint32_t(std::sqrt(float(i)) + 1e-4f);
        const double lobe = prt_sh_cosine_band_factor(l) * y[i] / kSfPi;
        triple += lobe * v[i];
        log_product += lobe * lanes[i * PRT_SF_LANES];
      }
      const double truth = std::sqrt(4.0 * kSfPi) * project_dense(1, [&](const float* w) {
                             const double cosine = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
                             return cosine > 0.0 ? visible(w) * cosine / kSfPi : 0.0;
                           })[0];
      std::printf("cap %.3f, tilt %.1f: truth %.3f, triple %.3f, log %.3f (%.3f of the truth)\n",
                  c.cap, tilt, truth, triple, log_product, log_product / truth);
      EXPECT_NEAR(triple, truth, 0.01 * truth);
      EXPECT_GT(log_product / truth, c.low) << c.cap << " " << tilt;
      EXPECT_LT(log_product / truth, c.high) << c.cap << " " << tilt;
    }
  }
}

}  // namespace
}  // namespace prt::test
