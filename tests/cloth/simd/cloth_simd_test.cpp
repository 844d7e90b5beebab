// SPDX-License-Identifier: MIT
// The SIMD backend of cloth shading (runtime/src/cloth/cloth_shade_avx2.c) against the scalar
// reference on synthetic tables of the six presets' weaves: random samples and lights, every
// setting, the frame cache, the pool split and the dispatch.
//
// The conformance bound. The kernel runs the reference's steps in float: each rounding is 6e-8
// relative, and a node's value is a product of some 20 of them (1e-6); what float amplifies is
// (a) the lobe's ratio to its window's Gaussian, exp(e) with |e| up to about 10 at the window's
// ends (an absolute error of 1e-6 in e is 1e-6 relative), (b) the phi nodes' inverse normal CDF,
// accurate to 4e-6 in z, which moves each sharp node's Jacobian exp(z^2 / 2) by z 4e-6 (up to
// 3e-5 at |z| = 6, but only for nodes carrying e^-18 of the mass; 1e-5 at the central nodes),
// (c) the table reads, bilinear in float (1e-6 of T), and (d) the panel moments about the middle
// node, m2 + 2 d m1 + d^2 m0, which cancel by (d / w)^2 for a panel of width w at d from the
// mean (d / w up to about 4: 16 ulp). Summed over the lobes and tangents these make a few 1e-5
// of the radiance; values far below the peak carry absolute errors of the same size as the
// peak's, hence a floor. Measured (printed by the tests): 1e-5.
#include <gtest/gtest.h>

#include <prt/prt_cloth_asset.h>
#include <prt/prt_workers.h>
#include <prt/prt.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cloth/simd/cloth_simd_samples.hpp"
#include "cloth/simd/cloth_synthetic.hpp"
#include "support/blob_test_util.hpp"
#include "support/limited_context.hpp"
#include "support/mesh_blob.hpp"
#include "support/simd_dispatch.hpp"  // same_bits

namespace {

using prt_test::ClothSamples;
using prt_test::Deviation;

// |simd - scalar| <= kBound (|scalar| + kFloor max |scalar|) over a call's values.
const double kBound = 3e-5;
const double kFloor = 1e-3;

const std::vector<std::uint8_t>& six_presets() {
  static const std::vector<std::uint8_t> blob =
      prt_test::synthetic_cloth_blob(prt_test::SyntheticGrid{}, {}, 7);
  return blob;
}

struct Loaded {
  prt::ContextPtr context = prt_test::limited_context();
  prt_test::LoadedAsset asset;
  explicit Loaded(const std::vector<std::uint8_t>& blob) : asset(context.get(), blob) {
    EXPECT_EQ(asset.result, PRT_OK) << prt_context_last_message(context.get());
  }
};

bool simd_here() {
  const Loaded a(six_presets());
  return prt_test::simd_usable(a.context.get());
}

prt_cloth_settings settings_of(std::uint32_t flags, std::uint32_t segments = 0,
                               std::uint32_t phi = 0) {
  prt_cloth_settings s = prt::sized<prt_cloth_settings>();
  s.flags = flags;
  s.theta_segments = segments;
  s.phi_nodes = phi;
  return s;
}

std::vector<float> shade(const prt_asset* asset, prt_backend backend, std::uint32_t fabric,
                         const std::vector<prt_cloth_lobe>& lobes, const prt_cloth_settings* set,
                         const ClothSamples& samples, std::uint32_t first = 0,
                         std::uint32_t count = ~0u) {
  if (count == ~0u) count = std::uint32_t(samples.size()) - first;
  const prt_cloth_light light = prt_test::light_of(lobes);
  const prt_cloth_pixels pixels = samples.pixels();
  std::vector<float> out(3 * std::size_t(count), -1.0f);
  EXPECT_EQ(prt_cloth_shade(asset, backend, fabric, nullptr, &light, set, &pixels, first, count,
                            out.data()),
            PRT_OK);
  return out;
}

// SIMD against scalar for one fabric, light and setting; returns the deviation.
Deviation compare(const prt_asset* asset, std::uint32_t fabric,
                  const std::vector<prt_cloth_lobe>& lobes, const prt_cloth_settings* set,
                  const ClothSamples& samples) {
  const std::vector<float> ref = shade(asset, PRT_BACKEND_CPU, fabric, lobes, set, samples);
  const std::vector<float> got = shade(asset, PRT_BACKEND_SIMD, fabric, lobes, set, samples);
  const Deviation d = prt_test::deviation(got, ref, kFloor);
  EXPECT_LE(d.worst, kBound) << "fabric " << fabric << " sample " << d.at / 3 << ": simd "
                             << got[d.at] << " scalar " << ref[d.at] << " (peak " << d.peak << ")";
  EXPECT_GT(d.peak, 0.0);
  return d;
}

// The larger, NaN if either is.
double worse(double a, double b) {
  return std::isnan(a) || std::isnan(b) ? NAN : std::max(a, b);
}

class ClothSimd : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!simd_here()) GTEST_SKIP() << "SIMD not usable here (compiled out or no AVX2)";
  }
};

TEST_F(ClothSimd, AgreesWithTheScalarReferenceOnEveryPreset) {
  const Loaded a(six_presets());
  const ClothSamples samples = prt_test::random_samples(1203, 11);  // not a multiple of 8
  double worst = 0.0;
  for (std::uint32_t fabric = 0; fabric < 6; ++fabric)
    for (unsigned count : {1u, 5u, 32u}) {
      const auto lobes = prt_test::random_lobes(count, 0.25f, 1e4f, 100 * fabric + count);
      worst = worse(worst, compare(a.asset.asset, fabric, lobes, nullptr, samples).worst);
    }
  std::printf("measured: worst %.3g (bound %.3g)\n", worst, kBound);
}

TEST_F(ClothSimd, AgreesOnSkyLightsWithASun) {
  const Loaded a(six_presets());
  const ClothSamples samples = prt_test::random_samples(805, 12);
  double worst = 0.0;
  for (std::uint32_t fabric = 0; fabric < 6; ++fabric) {
    const auto lobes = prt_test::sky_lobes(10, 5.0f, 100.0f, true, fabric);
    worst = worse(worst, compare(a.asset.asset, fabric, lobes, nullptr, samples).worst);
  }
  std::printf("measured: worst %.3g (bound %.3g)\n", worst, kBound);
}

TEST_F(ClothSimd, AgreesUnderEverySettingAndCount) {
  const Loaded a(six_presets());
  const ClothSamples samples = prt_test::random_samples(203, 13);
  const auto lobes = prt_test::random_lobes(8, 0.25f, 1e4f, 14);
  double worst = 0.0;
  for (std::uint32_t flags :
       {PRT_CLOTH_KEEP_HIDDEN_LOBES, PRT_CLOTH_KEEP_WEAK_LOBES, PRT_CLOTH_NO_CONE_TABLE,
        PRT_CLOTH_NO_FRAME_CACHE, PRT_CLOTH_KEEP_HIDDEN_LOBES | PRT_CLOTH_KEEP_WEAK_LOBES,
        PRT_CLOTH_TANGENT_COPIES, PRT_CLOTH_NO_LOBE_SHARING}) {
    const prt_cloth_settings s = settings_of(flags);
    for (std::uint32_t fabric : {0u, 2u, 5u})
      worst = worse(worst, compare(a.asset.asset, fabric, lobes, &s, samples).worst);
  }
  for (std::uint32_t n = 1; n <= 8; ++n) {
    const prt_cloth_settings segments = settings_of(0, n), nodes = settings_of(0, 0, n);
    for (std::uint32_t fabric : {0u, 2u}) {
      worst = worse(worst, compare(a.asset.asset, fabric, lobes, &segments, samples).worst);
      worst = worse(worst, compare(a.asset.asset, fabric, lobes, &nodes, samples).worst);
    }
  }
  std::printf("measured: worst %.3g (bound %.3g)\n", worst, kBound);
}

TEST_F(ClothSimd, AgreesOnEveryRankAndBothWidths) {
  for (int bits : {8, 16})
    for (std::uint32_t rank = 1; rank <= 8; ++rank) {
      prt_test::SyntheticGrid g;
      g.rank = rank;
      g.cone_rank = 9 - rank;
      g.bits = bits;
      g.xi_size = 3 + rank % 3;
      g.levels = rank % 4 + 1;
      g.view_theta = 2 + rank % 2;
      g.view_phi = 3;
      const Loaded a(prt_test::synthetic_cloth_blob(g, {"linen_plain", "velvet"}, rank));
      const ClothSamples samples = prt_test::random_samples(77, 20 + rank);
      const auto lobes = prt_test::random_lobes(6, 0.25f, 1e4f, 30 + rank);
      compare(a.asset.asset, 0, lobes, nullptr, samples);
      compare(a.asset.asset, 1, lobes, nullptr, samples);
    }
}

// The cache of what a frame alone decides and the terms a lobe shares across tangents change no
// bit: runs of one frame, at every alignment, with and without each, over ranges that start
// anywhere, with more lobes than are shared.
TEST_F(ClothSimd, FrameCacheAndLobeSharingChangeNoBit) {
  const Loaded a(six_presets());
  ClothSamples samples = prt_test::random_samples(300, 15, 37);
  // a flat patch: one frame, every view different
  std::mt19937 rng(16);
  float n[3] = {0.0f, 0.0f, 1.0f}, w[3] = {1.0f, 0.2f, 0.0f}, v[3];
  for (int i = 0; i < 90; ++i) prt_test::random_view(rng, n, v), samples.add(n, w, v);
  const prt_cloth_settings with = settings_of(0);
  for (std::uint32_t flags : {PRT_CLOTH_NO_FRAME_CACHE, PRT_CLOTH_NO_LOBE_SHARING,
                              PRT_CLOTH_NO_FRAME_CACHE | PRT_CLOTH_NO_LOBE_SHARING}) {
    const prt_cloth_settings without = settings_of(flags);
    for (std::uint32_t fabric = 0; fabric < 6; ++fabric) {
      const auto lobes = prt_test::random_lobes(fabric == 2 ? 40 : 9, 0.25f, 1e4f, 17 + fabric);
      for (std::uint32_t first : {0u, 3u, 290u}) {
        const auto saved =
            shade(a.asset.asset, PRT_BACKEND_SIMD, fabric, lobes, &with, samples, first);
        const auto direct =
            shade(a.asset.asset, PRT_BACKEND_SIMD, fabric, lobes, &without, samples, first);
        EXPECT_TRUE(prt_test::same_bits(saved, direct))
            << "flags " << flags << " fabric " << fabric << " first " << first;
      }
    }
  }
}

// Two calls over [0, k) and [k, n) give the one call's bits, wherever k cuts a batch of eight or
// a run of one frame (the frame cache starts afresh in each call).
TEST_F(ClothSimd, SplitRangesAreBitwiseTheOneCall) {
  const Loaded a(six_presets());
  ClothSamples samples = prt_test::random_samples(120, 21, 37);
  std::mt19937 rng(22);
  float n[3] = {0.3f, -0.2f, 0.93273791f}, w[3] = {1.0f, 0.0f, 0.0f}, v[3];
  for (int i = 0; i < 70; ++i) prt_test::random_view(rng, n, v), samples.add(n, w, v);
  const std::uint32_t total = std::uint32_t(samples.size());
  for (std::uint32_t fabric : {1u, 2u, 5u}) {
    const auto lobes = prt_test::random_lobes(6, 0.25f, 1e4f, 23 + fabric);
    const auto one = shade(a.asset.asset, PRT_BACKEND_SIMD, fabric, lobes, nullptr, samples);
    for (std::uint32_t k : {1u, 7u, 8u, 13u, 125u, 150u, total - 1u}) {
      auto split = shade(a.asset.asset, PRT_BACKEND_SIMD, fabric, lobes, nullptr, samples, 0, k);
      const auto rest = shade(a.asset.asset, PRT_BACKEND_SIMD, fabric, lobes, nullptr, samples, k);
      split.insert(split.end(), rest.begin(), rest.end());
      EXPECT_TRUE(prt_test::same_bits(one, split)) << "fabric " << fabric << " cut at " << k;
    }
  }
}

TEST_F(ClothSimd, WorkersAreBitwiseTheOneRangeCall) {
  const Loaded a(six_presets());
  const ClothSamples samples = prt_test::random_samples(501, 18);
  const auto lobes = prt_test::random_lobes(7, 0.25f, 1e4f, 19);
  const prt_cloth_light light = prt_test::light_of(lobes);
  const prt_cloth_pixels pixels = samples.pixels();
  for (std::uint32_t threads : {2u, 3u}) {
    prt_workers_desc desc = prt::sized<prt_workers_desc>();
    desc.thread_count = threads;
    prt_workers* workers = nullptr;
    ASSERT_EQ(prt_workers_create(a.context.get(), &desc, &workers), PRT_OK);
    for (std::uint32_t fabric : {0u, 3u}) {
      const auto one = shade(a.asset.asset, PRT_BACKEND_SIMD, fabric, lobes, nullptr, samples, 1);
      std::vector<float> split(one.size(), -1.0f);
      ASSERT_EQ(prt_cloth_shade_workers(workers, a.asset.asset, PRT_BACKEND_SIMD, fabric, nullptr,
                                        &light, nullptr, &pixels, 1,
                                        std::uint32_t(samples.size() - 1), split.data()),
                PRT_OK);
      EXPECT_TRUE(prt_test::same_bits(one, split)) << threads << " threads, fabric " << fabric;
    }
    prt_workers_destroy(workers);
  }
}

TEST_F(ClothSimd, DegenerateSamplesShadeToZero) {
  const Loaded a(six_presets());
  const float n[3] = {0.0f, 0.0f, 1.0f}, w[3] = {1.0f, 0.0f, 0.0f}, v[3] = {0.3f, 0.1f, 0.9f};
  const float zero[3] = {0.0f, 0.0f, 0.0f}, along[3] = {0.0f, 0.0f, 2.0f};
  const float nan[3] = {NAN, 0.0f, 1.0f}, inf[3] = {INFINITY, 0.0f, 1.0f};
  const float below[3] = {0.3f, 0.1f, -0.9f}, flat[3] = {1.0f, 0.0f, 0.0f};
  ClothSamples s;
  s.add(n, w, v);  // a good one first: its neighbours must not take its light
  s.add(zero, w, v);
  s.add(n, zero, v);
  s.add(n, along, v);
  s.add(n, w, zero);
  s.add(nan, w, v);
  s.add(n, inf, v);
  s.add(n, w, nan);
  s.add(n, w, below);
  s.add(n, w, flat);  // in the tangent plane: not above the surface
  s.add(n, w, v);
  const auto lobes = prt_test::random_lobes(5, 0.25f, 1e4f, 21);
  for (std::uint32_t fabric = 0; fabric < 6; ++fabric) {
    const auto out = shade(a.asset.asset, PRT_BACKEND_SIMD, fabric, lobes, nullptr, s);
    for (std::size_t i = 3; i < 30; ++i) EXPECT_EQ(out[i], 0.0f) << "sample " << i / 3;
    EXPECT_GT(out[0] + out[1] + out[2], 0.0f);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(out[c], out[30 + c]);
  }
}

}  // namespace
