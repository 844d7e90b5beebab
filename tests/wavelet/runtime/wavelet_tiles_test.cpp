// SPDX-License-Identifier: MIT
// `wavelet` tiled AVX2 shading (the rows repacked at load into 8-vertex tiles, dense coarse
// corners and the fine pairs by coefficient within 32-coefficient units) against the scalar
// reference that reads the blob rows. The tiled kernel is taken for lights whose non-zero fine
// light lies in at most a third of the groups, so every light here keeps its fine light to a few
// groups (the corners may be lit anywhere). Agreement is checked relative to sum |q P| vs, the size
// of the terms: the two sum the same products in different orders.
#include <gtest/gtest.h>

#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>
#include <prt/prt_workers.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "support/limited_context.hpp"
#include "wavelet/wavelet_bench_asset.hpp"
#include "wavelet/wavelet_blob_test_util.hpp"

namespace {

using namespace prt_test;

// The largest difference seen, relative to the terms' size: printed, so the tolerance below
// stays a small multiple of what the kernels really differ by.
double g_max_relative = 0.0;

// Tolerance relative to vs sum |q P|: about three times the largest difference measured on these
// assets (printed by WaveletTilesReport), in float roundings of 2^-24.
const double kRelativeTolerance = 16.0 * std::ldexp(1.0, -24);

bool is_corner(const WvltTransfer& t, uint32_t j) {
  const uint32_t within = j % (t.size * t.size);
  return within / t.size < 8 && within % t.size < 8;
}

// A light the tiled kernel takes: random RGB on the corners of the faces in `corner_faces`,
// and `fine` non-zero fine coefficients drawn from `lit_groups` random 64-coefficient groups
// (fine = ~0u: every fine coefficient of those groups).
std::vector<float> sparse_light(const WvltTransfer& t, uint32_t corner_faces, uint32_t lit_groups,
                                uint32_t fine, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<float> light(4 * size_t(t.coefficients()), 0.0f);
  for (uint32_t j = 0; j < t.coefficients(); ++j)
    if (is_corner(t, j) && (corner_faces >> (j / (t.size * t.size)) & 1u))
      for (uint32_t c = 0; c < 3; ++c) light[4 * size_t(j) + c] = unit(rng);
  const uint32_t groups = t.coefficients() / 64;
  std::vector<uint32_t> order(groups);
  for (uint32_t g = 0; g < groups; ++g) order[g] = g;
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<uint32_t> candidates;
  for (uint32_t i = 0; i < std::min(lit_groups, groups); ++i)
    for (uint32_t j = 64 * order[i]; j < 64 * order[i] + 64; ++j)
      if (!is_corner(t, j)) candidates.push_back(j);
  std::shuffle(candidates.begin(), candidates.end(), rng);
  if (fine < candidates.size()) candidates.resize(fine);
  for (uint32_t j : candidates)
    for (uint32_t c = 0; c < 3; ++c) light[4 * size_t(j) + c] = unit(rng);
  return light;
}

class WaveletTiles : public ::testing::Test {
 protected:
  void SetUp() override {
    prt_backend_info info = prt::sized<prt_backend_info>();
    ASSERT_EQ(prt_backend_get_info(ctx, PRT_BACKEND_SIMD, &info), PRT_OK);
    if (!info.usable || info.isa != PRT_SIMD_ISA_AVX2)
      GTEST_SKIP() << "these tests run the tiles on an AVX2-limited context";
  }

  // Shades [first, first + count) on SIMD and all vertices on the scalar path under the same
  // prepared light (and mask), and compares.
  void expect_matches(const LoadedAsset& a, const WvltTransfer& t, const std::vector<float>& light,
                      const uint8_t* zero_blocks, uint32_t first, uint32_t count) {
    std::vector<float> prepared(light.size());
    ASSERT_EQ(prt_wavelet_prepare_light(a.asset, light.data(), prepared.data(), nullptr), PRT_OK);
    std::vector<float> simd(3 * size_t(count) + 1, -7.0f), scalar(3 * size_t(t.vertices));
    ASSERT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, prepared.data(), zero_blocks, first,
                                count, simd.data()),
              PRT_OK);
    ASSERT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_CPU, prepared.data(), zero_blocks, 0,
                                t.vertices, scalar.data()),
              PRT_OK);
    EXPECT_EQ(simd[3 * size_t(count)], -7.0f);  // nothing written past the range
    for (uint32_t i = 0; i < count; ++i) {
      const uint32_t v = first + i;
      for (uint32_t c = 0; c < 3; ++c) {
        double magnitude = 0.0;
        for (const WvltPair& p : t.rows[v]) {
          if (zero_blocks && zero_blocks[p.j / 256]) continue;
          magnitude += std::fabs(double(p.q) * double(prepared[4 * size_t(p.j) + c]));
        }
        magnitude *= double(t.vertex_scale[3 * size_t(v) + c]);
        const double got = simd[3 * size_t(i) + c], want = scalar[3 * size_t(v) + c];
        const double difference = std::fabs(got - want);
        if (magnitude > 0.0) g_max_relative = std::max(g_max_relative, difference / magnitude);
        ASSERT_LE(difference, kRelativeTolerance * magnitude)
            << "vertex " << v << " channel " << c << " (" << t.rows[v].size() << " pairs)";
      }
    }
  }

  prt::ContextPtr context = limited_context(PRT_BACKEND_AUTO, PRT_SIMD_ISA_AVX2);
  prt_context* ctx = context.get();
};

TEST_F(WaveletTiles, BenchAssetMatchesScalar) {
  const WvltTransfer t = prt_bench::bake_shaped_transfer(4003, 64, 3);
  LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx);
  for (uint32_t fine : {0u, 1u, 30u, 300u, ~0u})
    expect_matches(a, t, sparse_light(t, 0x3f, 12, fine, 40 + fine), nullptr, 0, t.vertices);
}

TEST_F(WaveletTiles, SmallAssetsEveryShape) {
  for (const prt_wavelet_param param : {PRT_WAVELET_PARAM_CUBE, PRT_WAVELET_PARAM_DUAL_PARABOLOID})
    for (const uint32_t size : {16u, 32u})
      for (const uint32_t vertices : {1u, 13u, 77u}) {
        WvltTransfer t = wvlt_random(param, size, vertices, 150, 50 + size + vertices);
        t.rows[0].clear();  // a row with no pairs
        if (vertices > 5) t.rows[5].resize(1);
        LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
        ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx);
        const uint32_t faces = t.faces(), groups = t.coefficients() / 64;
        for (const uint32_t fine : {1u, 7u, 40u, ~0u}) {
          SCOPED_TRACE(testing::Message() << "param " << param << " S " << size << " V " << vertices
                                          << " fine " << fine);
          // Every face's corner lit, then only face 1's (the others zero), then none.
          for (const uint32_t corner_faces : {(1u << faces) - 1u, 2u, 0u}) {
            const std::vector<float> light =
                sparse_light(t, corner_faces, std::max(1u, groups / 4), fine, fine + corner_faces);
            expect_matches(a, t, light, nullptr, 0, vertices);
            if (vertices > 10) expect_matches(a, t, light, nullptr, 3, vertices - 5);  // mid-tile
            expect_matches(a, t, light, nullptr, vertices - 1, 1);                     // one
          }
        }
      }
}

TEST_F(WaveletTiles, MaskedBlocksAreLeftOut) {
  const WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 32, 21, 400, 60);
  LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  // The mask drops blocks whose light is not zero (the caller's word is taken, as the rows do):
  // the first block of every face, which holds its corner, and every third block.
  std::vector<uint8_t> mask(t.blocks(), 0);
  for (uint32_t k = 0; k < t.blocks(); ++k) mask[k] = uint8_t(k % 3 == 0 || k % 4 == 0);
  expect_matches(a, t, sparse_light(t, 0x3f, 8, ~0u, 61), mask.data(), 0, t.vertices);
  expect_matches(a, t, sparse_light(t, 0x3f, 8, ~0u, 62), mask.data(), 9, 4);
}

TEST_F(WaveletTiles, RangesGiveTheSameBits) {
  const WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 32, 45, 300, 70);
  LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> light = sparse_light(t, 0x3f, 10, ~0u, 71);
  ASSERT_EQ(prt_wavelet_prepare_light(a.asset, light.data(), light.data(), nullptr), PRT_OK);
  std::vector<float> whole(3 * size_t(t.vertices));
  ASSERT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, light.data(), nullptr, 0, t.vertices,
                              whole.data()),
            PRT_OK);
  for (uint32_t first = 0; first < t.vertices; first += 3)
    for (uint32_t count = 1; first + count <= t.vertices; count += 5) {
      std::vector<float> part(3 * size_t(count));
      ASSERT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, light.data(), nullptr, first, count,
                                  part.data()),
                PRT_OK);
      ASSERT_EQ(std::memcmp(part.data(), whole.data() + 3 * size_t(first), 4 * part.size()), 0)
          << "range " << first << " + " << count;
    }
}

TEST_F(WaveletTiles, WorkersGiveTheOneRangeBits) {
  const WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 32, 203, 300, 75);
  LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> light = sparse_light(t, 0x3f, 10, ~0u, 76);
  ASSERT_EQ(prt_wavelet_prepare_light(a.asset, light.data(), light.data(), nullptr), PRT_OK);
  std::vector<float> whole(3 * size_t(t.vertices));
  ASSERT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, light.data(), nullptr, 0, t.vertices,
                              whole.data()),
            PRT_OK);
  for (uint32_t threads = 1; threads <= 5; ++threads) {
    prt_workers_desc desc{};
    desc.struct_size = sizeof desc;
    desc.thread_count = threads;
    prt_workers* workers = nullptr;
    ASSERT_EQ(prt_workers_create(ctx, &desc, &workers), PRT_OK);
    std::vector<float> split(whole.size(), -1.0f);
    EXPECT_EQ(prt_wavelet_shade_workers(workers, a.asset, PRT_BACKEND_SIMD, light.data(), nullptr,
                                        0, t.vertices, split.data()),
              PRT_OK);
    prt_workers_destroy(workers);
    EXPECT_EQ(std::memcmp(split.data(), whole.data(), 4 * whole.size()), 0)
        << threads << " threads";
  }
}

// With a non-finite term in `light`, that only vertex 0 stores: vertex 0 shades to a non-finite
// value on the SIMD backend, vertex 1 stays finite, as on the scalar one.
void expect_only_vertex0_not_finite(const LoadedAsset& a, uint32_t vertices,
                                    std::vector<float> light) {
  ASSERT_EQ(prt_wavelet_prepare_light(a.asset, light.data(), light.data(), nullptr), PRT_OK);
  std::vector<float> simd(3 * size_t(vertices)), scalar(simd.size());
  ASSERT_EQ(
      prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, light.data(), nullptr, 0, vertices, simd.data()),
      PRT_OK);
  ASSERT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_CPU, light.data(), nullptr, 0, vertices,
                              scalar.data()),
            PRT_OK);
  EXPECT_TRUE(std::isinf(simd[0]) || std::isnan(simd[0]));
  EXPECT_TRUE(std::isfinite(simd[3]));
  EXPECT_EQ(std::isfinite(simd[3]), std::isfinite(scalar[3]));
}

TEST_F(WaveletTiles, NonFiniteCornerLightReachesOnlyItsPairs) {
  WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 9, 60, 80);
  // Vertex 0 stores coefficient 0 (face 0's scaling coefficient), vertex 1 does not.
  t.rows[0].insert(t.rows[0].begin(), {0u, int8_t(5)});
  t.rows[0].erase(std::unique(t.rows[0].begin(), t.rows[0].end(),
                              [](const WvltPair& x, const WvltPair& y) { return x.j == y.j; }),
                  t.rows[0].end());
  t.rows[1].erase(std::remove_if(t.rows[1].begin(), t.rows[1].end(),
                                 [](const WvltPair& p) { return p.j == 0; }),
                  t.rows[1].end());
  LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> light = sparse_light(t, 0x3f, 2, ~0u, 81);
  light[0] = INFINITY;
  expect_only_vertex0_not_finite(a, t.vertices, light);
}

TEST_F(WaveletTiles, RepeatedCornerAtQuickValidationShadesFromTheRows) {
  // Quick validation does not check index order: a row storing coefficient 0 twice must sum
  // both, as the rows do (the dense corner holds one value, so the asset keeps no tiles).
  WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 3, 20, 90);
  t.rows[1].clear();
  t.rows[1].push_back({0u, int8_t(100)});
  t.rows[1].push_back({0u, int8_t(100)});
  LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices), PRT_VALIDATE_QUICK);
  ASSERT_EQ(a.result, PRT_OK);
  const std::vector<float> light = sparse_light(t, 0x3f, 1, 0, 91);
  expect_matches(a, t, light, nullptr, 0, t.vertices);
}

TEST_F(WaveletTiles, RepeatedFineAtQuickValidationShadesFromTheRows) {
  // The same for a fine coefficient: the repack holds one value per coefficient and lane.
  WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 3, 20, 92);
  const uint32_t fine = 16 * 8 + 9;  // face 0, x = 9, y = 8: outside the corner
  t.rows[1].clear();
  t.rows[1].push_back({fine, int8_t(100)});
  t.rows[1].push_back({fine, int8_t(-30)});
  LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices), PRT_VALIDATE_QUICK);
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> light = sparse_light(t, 0x3f, 0, 0, 93);
  for (uint32_t c = 0; c < 3; ++c) light[4 * size_t(fine) + c] = 0.5f;
  expect_matches(a, t, light, nullptr, 0, t.vertices);
}

TEST_F(WaveletTiles, NonFiniteFineLightReachesOnlyItsPairs) {
  // A lane that does not store a lit fine coefficient multiplies its light by 0 in the tiles:
  // a non-finite fine light must reach only the vertices that store the coefficient.
  WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 9, 60, 82);
  const uint32_t fine = 16 * 8 + 9;
  for (uint32_t v = 0; v < 2; ++v)
    t.rows[v].erase(std::remove_if(t.rows[v].begin(), t.rows[v].end(),
                                   [&](const WvltPair& p) { return p.j == fine; }),
                    t.rows[v].end());
  t.rows[0].push_back({fine, int8_t(5)});
  std::sort(t.rows[0].begin(), t.rows[0].end(),
            [](const WvltPair& x, const WvltPair& y) { return x.j < y.j; });
  LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> light = sparse_light(t, 0x3f, 2, ~0u, 83);
  light[4 * size_t(fine)] = INFINITY;
  expect_only_vertex0_not_finite(a, t.vertices, light);
}

TEST(WaveletTilesReport, MaxRelativeDifference) {
  std::printf("tiled vs scalar: max |difference| / (vs sum |q P|) = %.3g (tolerance %.3g)\n",
              g_max_relative, kRelativeTolerance);
}

}  // namespace
