// SPDX-License-Identifier: MIT
// Quantisation and the `sh` blob (technique sh): quantised values against the layout's formulas
// on hand-picked fractions of each column's range, the 8-bit error bound, the SHTR bytes decoded
// by hand, the self-check, and determinism over thread counts (`prt-bake bake sh` end to end is
// sh_cli_test.cpp).
#include <gtest/gtest.h>

#include <prt/prt.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "prt/baker/sh/sh_blob.hpp"
#include "sh/sh_test_scenes.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

constexpr std::uint32_t kShtr = PRT_TAG('S', 'H', 'T', 'R');

ShTransfer empty_transfer(std::uint32_t order, std::size_t vertices) {
  ShTransfer t;
  t.order = order;
  t.vertex_count = vertices;
  t.coefficients.assign(vertices * 3 * order * order, 0.0f);
  return t;
}

float& at(ShTransfer& t, std::size_t v, int c, std::size_t k) {
  return t.coefficients[(v * 3 + static_cast<std::size_t>(c)) * t.coefficient_count() + k];
}

// Four vertices; column (c, k) holds lo + f * range with f = 0, 1, 1/4, 3/5 (rotated by the
// column so min and max sit at different vertices), except column (1, 2), which is constant.
constexpr double kFractions[4] = {0.0, 1.0, 0.25, 0.6};
ShTransfer fraction_transfer(double* lo_out, double* range_out) {
  ShTransfer t = empty_transfer(2, 4);
  for (int c = 0; c < 3; ++c) {
    for (std::size_t k = 0; k < 4; ++k) {
      const std::size_t column = static_cast<std::size_t>(c) * 4 + k;
      const double lo = -0.5 + 0.125 * double(column), range = 0.25 * double(column + 1);
      lo_out[column] = lo;
      range_out[column] = range;
      for (std::size_t v = 0; v < 4; ++v) {
        at(t, v, c, k) = static_cast<float>(lo + kFractions[(v + column) % 4] * range);
      }
    }
  }
  for (std::size_t v = 0; v < 4; ++v) at(t, v, 1, 2) = 0.37f;
  return t;
}

void check_fraction_quantization(int bits, const std::vector<std::uint16_t>& expected_q) {
  double lo[12], range[12];
  const ShTransfer t = fraction_transfer(lo, range);
  const QuantizedShTransfer q = quantize_sh_transfer(t, bits);
  ASSERT_EQ(q.order, 2u);
  ASSERT_EQ(q.channels, 3u);
  ASSERT_EQ(q.bits, static_cast<std::uint32_t>(bits));
  ASSERT_EQ(q.q.size(), 4u * 12u);
  const double levels = std::pow(2.0, bits) - 1.0;
  for (int c = 0; c < 3; ++c) {
    for (std::size_t k = 0; k < 4; ++k) {
      const std::size_t column = static_cast<std::size_t>(c) * 4 + k;
      if (c == 1 && k == 2) {  // constant: scale 0, q 0, exact
        EXPECT_EQ(q.offsets[column], 0.37f);
        EXPECT_EQ(q.scales[column], 0.0f);
        for (std::size_t v = 0; v < 4; ++v) {
          EXPECT_EQ(q.q[(v * 3 + 1) * 4 + k], 0);
          EXPECT_EQ(q.dequantized(v, 1, k), 0.37f);
        }
        continue;
      }
      EXPECT_FLOAT_EQ(q.offsets[column], static_cast<float>(lo[column]));
      EXPECT_NEAR(q.scales[column], range[column] / levels, 1e-6 * range[column] / levels);
      for (std::size_t v = 0; v < 4; ++v) {
        const std::size_t fraction = (v + column) % 4;
        EXPECT_EQ(q.q[(v * 3 + static_cast<std::size_t>(c)) * 4 + k], expected_q[fraction])
            << "column " << column << " vertex " << v;
      }
    }
  }
}

// f * (2^b - 1) for f = 0, 1, 1/4, 3/5: 8 bits 0, 255, 63.75 -> 64, 153; 16 bits 0, 65535,
// 16383.75 -> 16384, 39321.
TEST(ShQuantize, EightBitValuesFollowTheLayoutFormulas) {
  check_fraction_quantization(8, {0, 255, 64, 153});
}

TEST(ShQuantize, SixteenBitValuesFollowTheLayoutFormulas) {
  check_fraction_quantization(16, {0, 65535, 16384, 39321});
}

TEST(ShQuantize, ConstantTransferIsExact) {
  ShTransfer t = empty_transfer(3, 5);
  for (std::size_t i = 0; i < t.coefficients.size(); ++i) t.coefficients[i] = 0.1f * float(i % 27);
  // Same vector at every vertex: every column constant.
  for (std::size_t v = 1; v < 5; ++v) {
    for (std::size_t i = 0; i < 27; ++i) t.coefficients[v * 27 + i] = t.coefficients[i];
  }
  for (int bits : {8, 16}) {
    const QuantizedShTransfer q = quantize_sh_transfer(t, bits);
    EXPECT_EQ(q.max_abs_error, 0.0);
    EXPECT_EQ(q.rms_abs_error, 0.0);
    for (float scale : q.scales) EXPECT_EQ(scale, 0.0f);
  }
}

// Rounding to the nearest of 256 levels: |error| <= half a step = range / 510.
TEST(ShQuantize, EightBitErrorIsAtMostHalfAStep) {
  ShTransfer t = empty_transfer(4, 200);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(-2.0f, 3.0f);
  for (float& x : t.coefficients) x = value(random);
  const QuantizedShTransfer q = quantize_sh_transfer(t, 8);
  double max_error = 0.0, sum_sq = 0.0;
  for (int c = 0; c < 3; ++c) {
    for (std::size_t k = 0; k < 16; ++k) {
      float lo = 1e30f, hi = -1e30f;
      for (std::size_t v = 0; v < 200; ++v) {
        lo = std::min(lo, at(t, v, c, k));
        hi = std::max(hi, at(t, v, c, k));
      }
      const double bound = (double(hi) - double(lo)) / 510.0;
      for (std::size_t v = 0; v < 200; ++v) {
        const double error = std::abs(double(q.dequantized(v, c, k)) - at(t, v, c, k));
        EXPECT_LE(error, bound * (1.0 + 1e-5) + 1e-7);
        max_error = std::max(max_error, error);
        sum_sq += error * error;
      }
    }
  }
  EXPECT_GT(max_error, 0.0);
  EXPECT_DOUBLE_EQ(q.max_abs_error, max_error);
  EXPECT_NEAR(q.rms_abs_error, std::sqrt(sum_sq / (200.0 * 48.0)), 1e-9);
}

TEST(ShQuantize, RejectsBadBits) {
  const ShTransfer t = empty_transfer(2, 3);
  EXPECT_THROW(quantize_sh_transfer(t, 12), Error);
  EXPECT_THROW(quantize_sh_transfer(t, 0), Error);
}

// Two meshes so that TRIS's per-mesh index offset shows.
Scene two_grid_scene() {
  return test::scene_of({test::make_grid("a", glm::vec3(0.0f), glm::vec3(1, 0, 0),
                                         glm::vec3(0, 0, 1), 2, 2, glm::vec3(0, 1, 0)),
                         test::make_grid("b", glm::vec3(0, 1, 0), glm::vec3(1, 0, 0),
                                         glm::vec3(0, 1, 0), 1, 2, glm::vec3(0, 0, 1))});
}

ShTransfer random_transfer(std::uint32_t order, std::size_t vertices, unsigned seed) {
  ShTransfer t = empty_transfer(order, vertices);
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  for (float& x : t.coefficients) x = value(random);
  return t;
}

// Little-endian loads, byte by byte.
std::uint32_t le16(const std::uint8_t* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8;
}
std::uint32_t u32(const std::uint8_t* p) {
  return le16(p) | le16(p + 2) << 16;
}
float f32(const std::uint8_t* p) {
  const std::uint32_t bits = u32(p);
  float value;
  std::memcpy(&value, &bits, 4);
  return value;
}

class ShBlobBits : public ::testing::TestWithParam<int> {};

TEST_P(ShBlobBits, ShtrBytesDecodedByHandEqualTheQuantizedValues) {
  const int bits = GetParam();
  const Scene scene = two_grid_scene();
  const std::size_t vertices = 9 + 6;
  ASSERT_EQ(scene.vertex_count(), vertices);
  const ShTransfer t = random_transfer(3, vertices, 11);
  const QuantizedShTransfer q = quantize_sh_transfer(t, bits, 0);
  const std::vector<std::uint8_t> blob = build_sh_blob(scene, q, "test blob");

  const prt::ContextPtr context = prt::create_context().handle;
  const auto [loaded, result] =
      prt::load_asset_memory(context.get(), blob.data(), blob.size(), PRT_VALIDATE_FULL);
  ASSERT_EQ(result, PRT_OK) << prt_context_last_message(context.get());
  const prt_asset* asset = loaded.get();
  const void* data = nullptr;
  size_t size = 0;
  ASSERT_EQ(prt_asset_section_data(asset, kShtr, &data, &size), PRT_OK);
  const auto* p = static_cast<const std::uint8_t*>(data);
  const std::size_t n2 = 9, columns = 3 * n2, bytes_per_value = std::size_t(bits) / 8;
  const std::size_t unpadded = 32 + 8 * columns + vertices * columns * bytes_per_value;
  EXPECT_EQ(size, (unpadded + 3) / 4 * 4);
  ASSERT_GE(size, unpadded);
  EXPECT_EQ(u32(p + 0), 3u);        // order
  EXPECT_EQ(u32(p + 4), vertices);  // vertex count
  EXPECT_EQ(u32(p + 8), 3u);        // channels
  EXPECT_EQ(u32(p + 12), unsigned(bits));
  EXPECT_EQ(u32(p + 16), 1u);  // kind: shadowed (ShTransfer's default)
  EXPECT_EQ(u32(p + 20), 0u);  // bounces
  EXPECT_EQ(u32(p + 24), 0u);
  EXPECT_EQ(u32(p + 28), 0u);
  for (std::size_t i = 0; i < columns; ++i) {
    EXPECT_EQ(f32(p + 32 + 8 * i), q.offsets[i]);
    EXPECT_EQ(f32(p + 36 + 8 * i), q.scales[i]);
  }
  for (std::size_t i = unpadded; i < size; ++i) EXPECT_EQ(p[i], 0) << "padding byte " << i;
  // Vertex 10 (in the second mesh): its row of C * n^2 values, each within half a step of t.
  const std::size_t v = 10;
  const std::uint8_t* row = p + 32 + 8 * columns + v * columns * bytes_per_value;
  for (std::size_t i = 0; i < columns; ++i) {
    const std::uint32_t stored = bits == 8 ? row[i] : le16(row + 2 * i);
    EXPECT_EQ(stored, q.q[v * columns + i]);
    const double decoded = double(f32(p + 32 + 8 * i)) + double(f32(p + 36 + 8 * i)) * stored;
    EXPECT_LE(std::abs(decoded - t.coefficients[v * columns + i]),
              0.5 * f32(p + 36 + 8 * i) * (1 + 1e-5) + 1e-7);
  }
  // The mesh sections: positions in Scene order, the second mesh's indices offset by 9.
  ASSERT_EQ(prt_asset_section_data(asset, PRT_SECTION_VPOS, &data, &size), PRT_OK);
  ASSERT_EQ(size, vertices * 12);
  const auto* positions = static_cast<const float*>(data);
  EXPECT_EQ(positions[3 * 10 + 1], scene.meshes[1].positions[1].y);
  ASSERT_EQ(prt_asset_section_data(asset, PRT_SECTION_TRIS, &data, &size), PRT_OK);
  ASSERT_EQ(size, (8 + 4) * 12u);
  const auto* indices = static_cast<const std::uint32_t*>(data);
  EXPECT_EQ(indices[8 * 3], 9 + scene.meshes[1].indices[0]);
}

INSTANTIATE_TEST_SUITE_P(Bits, ShBlobBits, ::testing::Values(8, 16));

TEST(ShBlobCheck, PassesForTheBakeAndFailsForAnotherTransfer) {
  const Scene scene = two_grid_scene();
  ShTransfer t = random_transfer(2, scene.vertex_count(), 5);
  const QuantizedShTransfer q = quantize_sh_transfer(t, 8);
  const std::vector<std::uint8_t> blob = build_sh_blob(scene, q, "");
  const ShBlobCheck good = check_sh_blob(blob, t, q);
  EXPECT_TRUE(good.passed) << good.message;
  EXPECT_LE(good.max_budget_ratio, 1.0);
  at(t, 3, 2, 1) += 4.0f * q.scales[2 * 4 + 1] + 0.01f;  // far beyond half a step
  const ShBlobCheck bad = check_sh_blob(blob, t, q);
  EXPECT_FALSE(bad.passed);
  EXPECT_GT(bad.max_budget_ratio, 1.0);
}

TEST(ShBlob, ByteIdenticalForOneAndTwoThreads) {
  const Scene scene = test::scene_of(
      {test::make_icosphere(2, 0.5f, glm::vec3(0, 0.5f, 0)), test::make_plane(2.0f, 6)});
  ShTransferSettings settings;
  settings.order = 3;
  settings.rays = 64;
  settings.kind = ShTransferKind::Interreflected;
  settings.bounces = 1;
  std::vector<std::uint8_t> blobs[2];
  for (unsigned threads : {1u, 2u}) {
    Context ctx;
    ctx.threads = threads;
    const ShTransfer t = compute_sh_transfer(scene, nullptr, settings, ctx);
    blobs[threads - 1] = build_sh_blob(scene, quantize_sh_transfer(t, 16, 1), "determinism");
  }
  ASSERT_FALSE(blobs[0].empty());
  EXPECT_EQ(blobs[0], blobs[1]);
}

}  // namespace
}  // namespace prt::bake
