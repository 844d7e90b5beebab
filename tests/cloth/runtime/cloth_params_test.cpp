// SPDX-License-Identifier: MIT
// The checks of prt_cloth.h: each range of the parameters, the weave and the light at and past
// its bounds, struct sizes, and the kernel's and weights' refusals of degenerate vectors.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "cloth/cloth_hand_model.hpp"

namespace {

using namespace cloth_test;

const float kNan = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();
const float kPiF = float(kPi);
const float kHalfPiF = float(kPi / 2);

prt_result params_with(const std::function<void(prt_cloth_params&)>& change) {
  prt_cloth_params p = linen_params();
  change(p);
  return prt_cloth_params_validate(&p);
}

TEST(ClothParams, RangesOfEveryField) {
  EXPECT_EQ(prt_cloth_params_validate(nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(params_with([](prt_cloth_params&) {}), PRT_OK);
  EXPECT_EQ(params_with([](prt_cloth_params& p) { p.struct_size = sizeof(p) - 1; }),
            PRT_ERROR_INVALID_ARGUMENT);
  struct Field {
    const char* name;
    float prt_cloth_thread::*member;
    std::vector<float> good, bad;
  };
  const Field fields[] = {
      {"eta", &prt_cloth_thread::eta, {1.0f, 4.0f}, {0.99f, 4.01f, kNan, kInf}},
      {"kd", &prt_cloth_thread::kd, {0.0f, 1.0f}, {-0.01f, 1.01f, kNan}},
      {"gamma_s", &prt_cloth_thread::gamma_s, {1e-6f, kPiF}, {0.0f, -0.1f, 3.15f, kNan}},
      {"gamma_v", &prt_cloth_thread::gamma_v, {1e-6f, kPiF}, {0.0f, 3.15f, kInf}},
      {"coverage", &prt_cloth_thread::coverage, {0.0f, 0.67f}, {-0.01f, 0.68f, kNan}},
  };
  for (const Field& f : fields)
    for (int j = 0; j < 2; ++j) {
      for (float v : f.good)
        EXPECT_EQ(params_with([&](prt_cloth_params& p) { p.threads[j].*f.member = v; }), PRT_OK)
            << f.name << " " << v;
      for (float v : f.bad)
        EXPECT_EQ(params_with([&](prt_cloth_params& p) { p.threads[j].*f.member = v; }),
                  PRT_ERROR_INVALID_ARGUMENT)
            << f.name << " " << v;
    }
  for (float v : {-0.01f, 1.01f, kNan})
    EXPECT_EQ(params_with([&](prt_cloth_params& p) { p.threads[1].albedo[2] = v; }),
              PRT_ERROR_INVALID_ARGUMENT);
  // Coverages summing to 1 as decimals rounded to float pass (satin: 0.9 + 0.1).
  EXPECT_EQ(params_with([](prt_cloth_params& p) {
              p.threads[0].coverage = 0.9f;
              p.threads[1].coverage = 0.1f;
            }),
            PRT_OK);
  EXPECT_EQ(params_with([](prt_cloth_params& p) {
              p.threads[0].coverage = 0.9f;
              p.threads[1].coverage = 0.11f;
            }),
            PRT_ERROR_INVALID_ARGUMENT);
}

prt_result weave_with(const std::function<void(prt_cloth_weave&)>& change) {
  prt_cloth_weave w = satin_weave();
  change(w);
  return prt_cloth_weave_validate(&w);
}

TEST(ClothWeave, CountsOffsetsAndMultiplicities) {
  EXPECT_EQ(prt_cloth_weave_validate(nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(weave_with([](prt_cloth_weave&) {}), PRT_OK);
  EXPECT_EQ(weave_with([](prt_cloth_weave& w) { w.struct_size = 8; }), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(weave_with([](prt_cloth_weave& w) { w.tangent_count[1] = 0; }),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(weave_with([](prt_cloth_weave& w) {
              w.tangent_count[0] = PRT_CLOTH_MAX_THREAD_TANGENTS;
              for (uint32_t k = 0; k < PRT_CLOTH_MAX_THREAD_TANGENTS; ++k) {
                w.offsets[0][k] = 0.1f * float(k) - 0.75f;
                w.multiplicity[0][k] = PRT_CLOTH_MAX_MULTIPLICITY;
              }
            }),
            PRT_OK);
  EXPECT_EQ(weave_with(
                [](prt_cloth_weave& w) { w.tangent_count[0] = PRT_CLOTH_MAX_THREAD_TANGENTS + 1; }),
            PRT_ERROR_INVALID_ARGUMENT);
  for (float tau : {kHalfPiF, -kHalfPiF})
    EXPECT_EQ(weave_with([&](prt_cloth_weave& w) { w.offsets[1][0] = tau; }), PRT_OK);
  for (float tau : {std::nextafter(kHalfPiF, 2.0f), -std::nextafter(kHalfPiF, 2.0f), kNan})
    EXPECT_EQ(weave_with([&](prt_cloth_weave& w) { w.offsets[1][0] = tau; }),
              PRT_ERROR_INVALID_ARGUMENT);
  for (uint32_t m : {0u, PRT_CLOTH_MAX_MULTIPLICITY + 1})
    EXPECT_EQ(weave_with([&](prt_cloth_weave& w) { w.multiplicity[0][2] = m; }),
              PRT_ERROR_INVALID_ARGUMENT);
  // A repeated offset must be one offset with its multiplicity.
  EXPECT_EQ(weave_with([](prt_cloth_weave& w) { w.offsets[0][1] = w.offsets[0][0]; }),
            PRT_ERROR_INVALID_ARGUMENT);
}

TEST(ClothLight, LobeRanges) {
  std::vector<prt_cloth_lobe> lobes(2, prt_cloth_lobe{{0.0f, 0.0f, 1.0f}, 10.0f, {1, 2, 3}});
  prt_cloth_light light = prt::sized<prt_cloth_light>();
  light.lobe_count = 2;
  light.lobes = lobes.data();
  auto with = [&](const std::function<void(prt_cloth_lobe&)>& change) {
    std::vector<prt_cloth_lobe> copy = lobes;
    change(copy[1]);
    prt_cloth_light l = light;
    l.lobes = copy.data();
    return prt_cloth_light_validate(&l);
  };
  EXPECT_EQ(prt_cloth_light_validate(&light), PRT_OK);
  EXPECT_EQ(prt_cloth_light_validate(nullptr), PRT_ERROR_INVALID_ARGUMENT);
  prt_cloth_light l = light;
  l.struct_size = 8;
  EXPECT_EQ(prt_cloth_light_validate(&l), PRT_ERROR_INVALID_ARGUMENT);
  l = light;
  l.lobes = nullptr;
  EXPECT_EQ(prt_cloth_light_validate(&l), PRT_ERROR_INVALID_ARGUMENT);
  l.lobe_count = 0;
  EXPECT_EQ(prt_cloth_light_validate(&l), PRT_OK);  // no lobes: a black light
  std::vector<prt_cloth_lobe> many(PRT_CLOTH_MAX_LOBES + 1, lobes[0]);
  l.lobes = many.data();
  l.lobe_count = PRT_CLOTH_MAX_LOBES;
  EXPECT_EQ(prt_cloth_light_validate(&l), PRT_OK);
  l.lobe_count = PRT_CLOTH_MAX_LOBES + 1;
  EXPECT_EQ(prt_cloth_light_validate(&l), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](prt_cloth_lobe& b) { b.sharpness = PRT_CLOTH_MIN_SHARPNESS; }), PRT_OK);
  EXPECT_EQ(with([](prt_cloth_lobe& b) { b.sharpness = PRT_CLOTH_MAX_SHARPNESS; }), PRT_OK);
  EXPECT_EQ(with([](prt_cloth_lobe& b) { b.axis[2] = 1.0009f; }), PRT_OK);
  for (const auto& bad : std::vector<std::function<void(prt_cloth_lobe&)>>{
           [](prt_cloth_lobe& b) { b.sharpness = 0.2f; },
           [](prt_cloth_lobe& b) { b.sharpness = 1.1e4f; },
           [](prt_cloth_lobe& b) { b.sharpness = kNan; },
           [](prt_cloth_lobe& b) { b.axis[2] = 1.002f; },
           [](prt_cloth_lobe& b) { b.axis[2] = 0.0f; }, [](prt_cloth_lobe& b) { b.axis[0] = kNan; },
           [](prt_cloth_lobe& b) { b.rgb[1] = -1e-6f; },
           [](prt_cloth_lobe& b) { b.rgb[2] = kInf; }})
    EXPECT_EQ(with(bad), PRT_ERROR_INVALID_ARGUMENT);
}

TEST(ClothKernel, RefusesBadArguments) {
  const prt_cloth_params p = linen_params();
  const prt_cloth_weave w = linen_weave();
  const float n[3] = {0, 0, 1}, u[3] = {1, 0, 0}, d[3] = {0, 0.6f, 0.8f};
  const float zero[3] = {0, 0, 0}, nan3[3] = {kNan, 0, 1}, along_n[3] = {0, 0, -3};
  float rgb[3], weights[PRT_CLOTH_MAX_THREAD_TANGENTS];
  EXPECT_EQ(prt_cloth_kernel(&p, &w, n, u, d, d, rgb), PRT_OK);
  EXPECT_EQ(prt_cloth_thread_weights(&w, 1, n, u, d, d, weights), PRT_OK);
  // Unnormalised vectors and a warp leaning on the normal are fine.
  const float n2[3] = {0, 0, 5}, u2[3] = {2, 0, 7};
  EXPECT_EQ(prt_cloth_kernel(&p, &w, n2, u2, d, d, rgb), PRT_OK);
  EXPECT_EQ(prt_cloth_kernel(nullptr, &w, n, u, d, d, rgb), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_kernel(&p, nullptr, n, u, d, d, rgb), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_kernel(&p, &w, n, u, d, d, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  const float* vectors[4] = {n, u, d, d};
  for (int which = 0; which < 4; ++which)
    for (const float* bad : {static_cast<const float*>(nullptr), zero, nan3}) {
      const float* v[4] = {vectors[0], vectors[1], vectors[2], vectors[3]};
      v[which] = bad;
      EXPECT_EQ(prt_cloth_kernel(&p, &w, v[0], v[1], v[2], v[3], rgb), PRT_ERROR_INVALID_ARGUMENT)
          << which;
      EXPECT_EQ(prt_cloth_thread_weights(&w, 0, v[0], v[1], v[2], v[3], weights),
                PRT_ERROR_INVALID_ARGUMENT)
          << which;
    }
  EXPECT_EQ(prt_cloth_kernel(&p, &w, n, along_n, d, d, rgb), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_thread_weights(&w, 2, n, u, d, d, weights), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_thread_weights(&w, 0, n, u, d, d, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  prt_cloth_params bad = p;
  bad.threads[0].coverage = 0.8f;  // 0.8 + 0.33 > 1
  EXPECT_EQ(prt_cloth_kernel(&bad, &w, n, u, d, d, rgb), PRT_ERROR_INVALID_ARGUMENT);
}

}  // namespace
