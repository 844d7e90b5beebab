// SPDX-License-Identifier: MIT
// The zero-light block skip of `wavelet` shading, checked the same way on every CPU-side
// backend (wavelet_asset_test.cpp: scalar; wavelet_simd_test.cpp: each ISA):
// - prt_wavelet_prepare_light's mask marks exactly the 256-coefficient blocks whose light is all
//   zero, and every 4th float of the prepared light is plain 0 (no hidden state);
// - shading with the mask matches the exact sum as shading without it does (the skipped pairs
//   add exactly 0), and on the scalar backend, which keeps its summation order, bit for bit;
// - a block marked by hand although its light is not zero really is not read: its pairs drop out
//   of the sum, which then matches a double sum over the other pairs.
#pragma once

#include <gtest/gtest.h>

#include <prt/prt_wavelet_asset.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "wavelet/wavelet_blob_test_util.hpp"

namespace prt_test {

// rgb within Higham's bound gamma_{n+2} sum |terms| of the double sum over t's pairs.
inline void expect_near_reference(const WvltTransfer& t, const std::vector<float>& light,
                                  const std::vector<float>& rgb, const char* what) {
  const double u = std::ldexp(1.0, -24);
  for (uint32_t v = 0; v < t.vertices; ++v) {
    double expected[3], magnitude[3];
    wvlt_reference_shade(t, light, v, expected, magnitude);
    const double n = double(t.rows[v].size()) + 2.0;
    for (uint32_t c = 0; c < 3; ++c)
      ASSERT_NEAR(rgb[3 * size_t(v) + c], expected[c], n * u / (1.0 - n * u) * magnitude[c] + 1e-30)
          << what << ": vertex " << v << " channel " << c;
  }
}

inline void expect_zero_light_blocks_skipped(prt_context* ctx, prt_backend backend) {
  constexpr uint32_t kBlock = 256;
  const WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 32, 40, 900, 31);
  LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx);
  const uint32_t blocks = t.coefficients() / kBlock;
  std::vector<float> light = wvlt_random_light(t.coefficients(), 32);
  for (uint32_t j = 0; j < t.coefficients(); ++j)
    if ((j / kBlock) % 3 == 1)  // every third block dark
      for (uint32_t c = 0; c < 3; ++c) light[4 * size_t(j) + c] = 0.0f;
  std::vector<float> prepared(light.size());
  std::vector<uint8_t> zero_blocks(blocks, 0xEE);
  ASSERT_EQ(prt_wavelet_prepare_light(a.asset, light.data(), prepared.data(), zero_blocks.data()),
            PRT_OK);
  for (uint32_t k = 0; k < blocks; ++k) EXPECT_EQ(zero_blocks[k], k % 3 == 1 ? 1 : 0) << k;
  for (uint32_t j = 0; j < t.coefficients(); ++j) ASSERT_EQ(prepared[4 * size_t(j) + 3], 0.0f);
  // The mask is optional and changes nothing else.
  std::vector<float> prepared_alone(light.size(), -1.0f);
  ASSERT_EQ(prt_wavelet_prepare_light(a.asset, light.data(), prepared_alone.data(), nullptr),
            PRT_OK);
  EXPECT_EQ(std::memcmp(prepared.data(), prepared_alone.data(), prepared.size() * sizeof(float)),
            0);

  auto shade = [&](const uint8_t* mask) {
    std::vector<float> rgb(3 * size_t(t.vertices), -1.0f);
    EXPECT_EQ(prt_wavelet_shade(a.asset, backend, prepared.data(), mask, 0, t.vertices, rgb.data()),
              PRT_OK);
    return rgb;
  };
  // Both within the rounding bound of the exact sum; the scalar loop keeps its order, so its bits
  // are the same (the SIMD kernels regroup the pairs that remain into their lanes).
  const std::vector<float> skipped = shade(zero_blocks.data()), walked = shade(nullptr);
  expect_near_reference(t, light, skipped, "skipped");
  expect_near_reference(t, light, walked, "walked");
  if (backend == PRT_BACKEND_CPU) {
    EXPECT_EQ(std::memcmp(skipped.data(), walked.data(), skipped.size() * sizeof(float)), 0);
  }

  // Block 0 (the scaling coefficients and coarse levels of face 0) marked although lit.
  std::vector<uint8_t> hand = zero_blocks;
  hand[0] = 1;
  const std::vector<float> without_block0 = shade(hand.data());
  WvltTransfer rest = t;
  for (std::vector<WvltPair>& row : rest.rows)
    row.erase(std::remove_if(row.begin(), row.end(), [](const WvltPair& p) { return p.j < 256; }),
              row.end());
  expect_near_reference(rest, light, without_block0, "block 0 marked by hand");
  uint32_t differs = 0;
  for (size_t i = 0; i < skipped.size(); ++i) differs += without_block0[i] != skipped[i];
  EXPECT_GT(differs, 0u);  // block 0 held pairs of some vertex
}

}  // namespace prt_test
