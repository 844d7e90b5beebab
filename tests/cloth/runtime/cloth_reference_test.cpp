// SPDX-License-Identifier: MIT
// prt_cloth_reference: a texel adds its power times the kernel (bitwise for powers of two), texels
// below the surface and black ones add nothing, a view below the surface or degenerate vectors
// give 0, the workers give the one-range result bit for bit, and bad arguments are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "cloth/cloth_hand_model.hpp"

namespace {

using namespace cloth_test;

std::vector<float> unit_vectors(size_t count, unsigned seed, double min_z = -1.0) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<float> out;
  while (out.size() < 3 * count) {
    double v[3] = {normal(rng), normal(rng), normal(rng)};
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (v[2] / len < min_z) continue;
    for (double x : v) out.push_back(float(x / len));
  }
  return out;
}

// Samples facing up (normals near +Z, views above them) with random warps.
struct Samples {
  std::vector<float> normals, warps, views;
  explicit Samples(size_t count, unsigned seed)
      : normals(unit_vectors(count, seed, 0.8)),
        warps(unit_vectors(count, seed + 1)),
        views(unit_vectors(count, seed + 2, 0.5)) {}
  prt_cloth_pixels pixels() const {
    prt_cloth_pixels p = prt::sized<prt_cloth_pixels>();
    p.normals = normals.data();
    p.warps = warps.data();
    p.views = views.data();
    return p;
  }
};

struct Texels {
  std::vector<float> directions, power;
  prt_cloth_env_texels env() const {
    prt_cloth_env_texels e = prt::sized<prt_cloth_env_texels>();
    e.count = uint32_t(directions.size() / 3);
    e.directions = directions.data();
    e.power = power.data();
    return e;
  }
  void add(const float* d, float r, float g, float b) {
    directions.insert(directions.end(), d, d + 3);
    power.insert(power.end(), {r, g, b});
  }
};

std::vector<float> reference(const prt_cloth_params& p, const prt_cloth_weave& w,
                             const Texels& texels, const Samples& s, uint32_t first,
                             uint32_t count) {
  const prt_cloth_env_texels env = texels.env();
  const prt_cloth_pixels pixels = s.pixels();
  std::vector<float> out(3 * size_t(count), -1.0f);
  EXPECT_EQ(prt_cloth_reference(&p, &w, &env, &pixels, first, count, out.data()), PRT_OK);
  return out;
}

std::array<float, 3> kernel_at(const prt_cloth_params& p, const prt_cloth_weave& w,
                               const Samples& s, size_t i, const float* light) {
  std::array<float, 3> k{};
  EXPECT_EQ(prt_cloth_kernel(&p, &w, &s.normals[3 * i], &s.warps[3 * i], light, &s.views[3 * i],
                             k.data()),
            PRT_OK);
  return k;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(ClothReference, OneTexelIsItsPowerTimesTheKernel) {
  const Samples s(40, 3);
  const std::vector<float> lights = unit_vectors(40, 9, 0.3);
  for (const auto& [params, weave] :
       {std::pair{linen_params(), linen_weave()}, std::pair{satin_params(), satin_weave()},
        std::pair{velvet_params(), velvet_weave()}})
    for (size_t i = 0; i < 40; ++i) {
      Texels t;
      t.add(&lights[3 * i], 1.0f, 2.0f, 0.25f);  // powers of two: the products are exact
      const std::vector<float> out = reference(params, weave, t, s, uint32_t(i), 1);
      const std::array<float, 3> k = kernel_at(params, weave, s, i, &lights[3 * i]);
      EXPECT_EQ(out, (std::vector<float>{k[0], 2.0f * k[1], 0.25f * k[2]})) << i;
    }
}

TEST(ClothReference, SumsTheTexelsAboveTheSurface) {
  const Samples s(10, 5);
  const prt_cloth_params p = satin_params();
  const prt_cloth_weave w = satin_weave();
  const std::vector<float> dirs = unit_vectors(60, 21);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> power(0.0f, 3.0f);
  Texels t;
  for (size_t i = 0; i < 60; ++i) t.add(&dirs[3 * i], power(rng), power(rng), power(rng));
  const std::vector<float> out = reference(p, w, t, s, 0, 10);
  for (size_t i = 0; i < 10; ++i) {
    double want[3] = {0, 0, 0};
    for (size_t x = 0; x < 60; ++x) {
      const std::array<float, 3> k = kernel_at(p, w, s, i, &dirs[3 * x]);
      for (int c = 0; c < 3; ++c) want[c] += double(t.power[3 * x + c]) * k[c];
    }
    // The kernel through the API is rounded to float before the sum.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[3 * i + c], want[c], 2e-7 * want[c]) << i;
  }
  // Texels below every sample's surface and black texels change nothing, not even a bit.
  Texels more = t;
  const float down[3] = {0.0f, 0.0f, -1.0f}, up[3] = {0.0f, 0.0f, 1.0f};
  more.add(down, 5.0f, 5.0f, 5.0f);
  more.add(up, 0.0f, 0.0f, 0.0f);
  EXPECT_TRUE(same_bits(reference(p, w, more, s, 0, 10), out));
}

TEST(ClothReference, ZeroForAViewBelowOrDegenerateVectors) {
  Samples s(4, 7);
  const float up[3] = {0.0f, 0.0f, 1.0f};
  Texels t;
  t.add(up, 1.0f, 1.0f, 1.0f);
  for (int i = 0; i < 3; ++i) {
    s.views[i] = -s.normals[i];         // sample 0: a view below the surface
    s.warps[3 + i] = s.normals[3 + i];  // sample 1: warp along the normal
    s.views[6 + i] = 0.0f;              // sample 2: no view
  }
  s.normals[9] = std::numeric_limits<float>::quiet_NaN();  // sample 3
  const std::vector<float> out = reference(linen_params(), linen_weave(), t, s, 0, 4);
  EXPECT_EQ(out, std::vector<float>(12, 0.0f));
  // An environment without texels is black.
  EXPECT_EQ(reference(linen_params(), linen_weave(), Texels{}, Samples(3, 1), 0, 3),
            std::vector<float>(9, 0.0f));
}

TEST(ClothReference, WorkersGiveTheOneRangeResult) {
  const Samples s(45, 13);
  const std::vector<float> dirs = unit_vectors(300, 17);
  Texels t;
  for (size_t i = 0; i < 300; ++i) t.add(&dirs[3 * i], 0.3f, 0.7f, float(i % 5));
  const prt_cloth_params p = satin_params();
  const prt_cloth_weave w = satin_weave();
  const std::vector<float> one = reference(p, w, t, s, 3, 41);
  auto [context, made] = prt::create_context();
  ASSERT_EQ(made, PRT_OK);
  const prt_cloth_env_texels env = t.env();
  const prt_cloth_pixels pixels = s.pixels();
  for (uint32_t threads : {1u, 2u, 3u, 8u}) {
    prt_workers_desc desc = prt::sized<prt_workers_desc>();
    desc.thread_count = threads;
    prt_workers* workers = nullptr;
    ASSERT_EQ(prt_workers_create(context.get(), &desc, &workers), PRT_OK);
    std::vector<float> split(one.size(), -1.0f);
    EXPECT_EQ(prt_cloth_reference_workers(workers, &p, &w, &env, &pixels, 3, 41, split.data()),
              PRT_OK);
    EXPECT_TRUE(same_bits(one, split)) << threads;
    EXPECT_EQ(prt_cloth_reference_workers(workers, &p, &w, &env, &pixels, 3, 41, nullptr),
              PRT_ERROR_INVALID_ARGUMENT);
    prt_workers_destroy(workers);
  }
}

TEST(ClothReference, RefusesBadArguments) {
  const Samples s(2, 1);
  const float up[3] = {0.0f, 0.0f, 1.0f};
  Texels t;
  t.add(up, 1.0f, 1.0f, 1.0f);
  const prt_cloth_params p = linen_params();
  const prt_cloth_weave w = linen_weave();
  const prt_cloth_env_texels env = t.env();
  const prt_cloth_pixels pixels = s.pixels();
  float out[6];
  auto call = [&](const prt_cloth_params* pp, const prt_cloth_weave* ww,
                  const prt_cloth_env_texels* ee, const prt_cloth_pixels* xx, uint32_t first,
                  uint32_t count,
                  float* o) { return prt_cloth_reference(pp, ww, ee, xx, first, count, o); };
  EXPECT_EQ(call(&p, &w, &env, &pixels, 0, 2, out), PRT_OK);
  EXPECT_EQ(call(nullptr, &w, &env, &pixels, 0, 2, out), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(call(&p, nullptr, &env, &pixels, 0, 2, out), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(call(&p, &w, nullptr, &pixels, 0, 2, out), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(call(&p, &w, &env, nullptr, 0, 2, out), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(call(&p, &w, &env, &pixels, 0, 2, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(call(&p, &w, &env, &pixels, 2, UINT32_MAX, out), PRT_ERROR_INVALID_ARGUMENT);
  prt_cloth_params bad_p = p;
  bad_p.threads[1].eta = 0.5f;
  EXPECT_EQ(call(&bad_p, &w, &env, &pixels, 0, 2, out), PRT_ERROR_INVALID_ARGUMENT);
  prt_cloth_weave bad_w = w;
  bad_w.tangent_count[0] = 0;
  EXPECT_EQ(call(&p, &bad_w, &env, &pixels, 0, 2, out), PRT_ERROR_INVALID_ARGUMENT);
  prt_cloth_env_texels bad_env = env;
  bad_env.struct_size = 8;
  EXPECT_EQ(call(&p, &w, &bad_env, &pixels, 0, 2, out), PRT_ERROR_INVALID_ARGUMENT);
  bad_env = env;
  bad_env.power = nullptr;
  EXPECT_EQ(call(&p, &w, &bad_env, &pixels, 0, 2, out), PRT_ERROR_INVALID_ARGUMENT);
  prt_cloth_pixels bad_pixels = pixels;
  bad_pixels.struct_size = 8;
  EXPECT_EQ(call(&p, &w, &env, &bad_pixels, 0, 2, out), PRT_ERROR_INVALID_ARGUMENT);
  for (int field = 0; field < 3; ++field) {
    bad_pixels = pixels;
    (field == 0 ? bad_pixels.normals : field == 1 ? bad_pixels.warps : bad_pixels.views) = nullptr;
    EXPECT_EQ(call(&p, &w, &env, &bad_pixels, 0, 2, out), PRT_ERROR_INVALID_ARGUMENT) << field;
  }
  // Texels outside the contract: non-finite or negative power, a direction not unit.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (const auto& [d, power] : {std::pair<std::array<float, 3>, float>{{0, 0, 1}, nan},
                                 {{0, 0, 1}, inf},
                                 {{0, 0, 1}, -1},
                                 {{0, 0, 2}, 1},
                                 {{0, 0, 0}, 1},
                                 {{nan, 0, 1}, 1}}) {
    Texels bad = t;
    bad.add(d.data(), 1.0f, power, 1.0f);
    const prt_cloth_env_texels e = bad.env();
    EXPECT_EQ(call(&p, &w, &e, &pixels, 0, 2, out), PRT_ERROR_INVALID_ARGUMENT) << power;
  }
  EXPECT_EQ(prt_cloth_reference_workers(nullptr, &p, &w, &env, &pixels, 0, 2, out),
            PRT_ERROR_INVALID_ARGUMENT);
}

}  // namespace
