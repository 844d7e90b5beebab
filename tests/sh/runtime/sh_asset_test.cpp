// SPDX-License-Identifier: MIT
// `sh` assets (SHTR section, formats/SPEC.md): header query, dequantisation, scalar shading,
// vertex ranges, and full validation of every header field. Blobs are built here byte by byte
// from the layout table, and the expected values are recomputed here from the stored q, offset
// and scale, independently of the runtime.
#include <gtest/gtest.h>

#include <prt/format/blob_writer.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "sh/sh_blob_test_util.hpp"

namespace {

using namespace prt_test;

class ShAsset : public ::testing::Test {
 protected:
  Context ctx;

  // Decodes every vertex and checks t = offset + scale q, computed here in float.
  void expect_decodes_to_stored(const Transfer& t, bool zstd) {
    LoadedAsset a(ctx.ctx, make_blob(encode(t), t.vertices, zstd));
    ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx.ctx);
    prt_sh_info info = prt::sized<prt_sh_info>();
    ASSERT_EQ(prt_sh_get_info(a.asset, &info), PRT_OK);
    EXPECT_EQ(info.order, t.order);
    EXPECT_EQ(info.vertex_count, t.vertices);
    EXPECT_EQ(info.channels, t.channels);
    EXPECT_EQ(info.bits, t.bits);
    EXPECT_EQ(info.kind, t.kind);
    EXPECT_EQ(info.bounces, t.bounces);
    std::vector<float> out(size_t(t.vertices) * t.coefficients());
    ASSERT_EQ(prt_sh_decode_transfer(a.asset, 0, t.vertices, out.data()), PRT_OK);
    for (uint32_t v = 0; v < t.vertices; ++v)
      for (uint32_t j = 0; j < t.coefficients(); ++j) {
        const float expected =
            t.offset[j] + t.scale[j] * float(t.q[size_t(v) * t.coefficients() + j]);
        ASSERT_FLOAT_EQ(out[size_t(v) * t.coefficients() + j], expected) << "v " << v << " j " << j;
      }
  }

  // Shades every vertex under a random light and compares with the sum in double.
  void expect_shading_is_dot_product(const Transfer& t) {
    LoadedAsset a(ctx.ctx, make_blob(encode(t), t.vertices));
    ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx.ctx);
    const uint32_t n2 = t.order * t.order;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-2.0f, 2.0f);
    std::vector<float> light(size_t(n2) * 3);
    for (float& l : light) l = unit(rng);
    std::vector<float> rgb(size_t(t.vertices) * 3);
    ASSERT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_CPU, light.data(), 0, t.vertices, rgb.data()),
              PRT_OK);
    for (uint32_t v = 0; v < t.vertices; ++v)
      for (uint32_t ch = 0; ch < 3; ++ch) {
        const uint32_t c = t.channels == 3 ? ch : 0;
        double sum = 0, magnitude = 0;
        for (uint32_t k = 0; k < n2; ++k) {
          const double term = t.value(v, c * n2 + k) * double(light[3 * k + ch]);
          sum += term;
          magnitude += std::fabs(term);
        }
        // float dequantisation and rounding: a few ulps of the largest partial sum.
        EXPECT_NEAR(rgb[3 * size_t(v) + ch], sum, 1e-6 * magnitude + 1e-30)
            << "v " << v << " ch " << ch;
      }
  }
};

TEST_F(ShAsset, Decodes8BitTransferAsOffsetPlusScaleTimesQ) {
  expect_decodes_to_stored(random_transfer(3, 5, 3, 8, 1), false);
}

TEST_F(ShAsset, Decodes16BitZstdTransferAsOffsetPlusScaleTimesQ) {
  expect_decodes_to_stored(random_transfer(4, 9, 1, 16, 2), true);
}

TEST_F(ShAsset, DecodesOrderOneAndMaximumOrder) {
  expect_decodes_to_stored(random_transfer(1, 3, 3, 8, 3), false);
  expect_decodes_to_stored(random_transfer(16, 3, 1, 16, 4), false);
}

TEST_F(ShAsset, ConstantCoefficientWithZeroScaleDecodesExactly) {
  Transfer t = random_transfer(2, 6, 3, 16, 5);
  const float constant = 0.1f;  // not representable in binary: exactness is not luck
  for (uint32_t j = 0; j < t.coefficients(); j += 2) t.scale[j] = 0.0f, t.offset[j] = constant;
  for (uint32_t v = 0; v < t.vertices; ++v)
    for (uint32_t j = 0; j < t.coefficients(); j += 2) t.q[size_t(v) * t.coefficients() + j] = 0;
  LoadedAsset a(ctx.ctx, make_blob(encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> out(size_t(t.vertices) * t.coefficients());
  ASSERT_EQ(prt_sh_decode_transfer(a.asset, 0, t.vertices, out.data()), PRT_OK);
  for (uint32_t v = 0; v < t.vertices; ++v)
    for (uint32_t j = 0; j < t.coefficients(); j += 2)
      EXPECT_EQ(out[size_t(v) * t.coefficients() + j], constant);
}

TEST_F(ShAsset, RgbShadingIsTheDotProductPerChannel) {
  expect_shading_is_dot_product(random_transfer(4, 7, 3, 8, 6));
  expect_shading_is_dot_product(random_transfer(6, 5, 3, 16, 7));
}

TEST_F(ShAsset, GreyTransferShadesRedGreenAndBlueWithItsOneChannel) {
  expect_shading_is_dot_product(random_transfer(3, 6, 1, 8, 8));
  // Under a white light (same coefficients in R, G, B) grey transfer gives grey radiance.
  const Transfer t = random_transfer(3, 4, 1, 16, 9);
  LoadedAsset a(ctx.ctx, make_blob(encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> light(27);
  for (size_t k = 0; k < 9; ++k) light[3 * k] = light[3 * k + 1] = light[3 * k + 2] = 0.3f * k - 1;
  std::vector<float> rgb(size_t(t.vertices) * 3);
  ASSERT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_CPU, light.data(), 0, t.vertices, rgb.data()),
            PRT_OK);
  for (uint32_t v = 0; v < t.vertices; ++v) {
    EXPECT_EQ(rgb[3 * v], rgb[3 * v + 1]);
    EXPECT_EQ(rgb[3 * v], rgb[3 * v + 2]);
  }
}

TEST_F(ShAsset, SplitRangesOnTwoThreadsEqualOneCall) {
  const Transfer t = random_transfer(5, 101, 3, 16, 10);
  LoadedAsset a(ctx.ctx, make_blob(encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> light(75);
  for (size_t i = 0; i < light.size(); ++i) light[i] = std::sin(float(i));
  std::vector<float> whole(size_t(t.vertices) * 3), split(whole.size(), -1.0f);
  ASSERT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_CPU, light.data(), 0, t.vertices, whole.data()),
            PRT_OK);
  const uint32_t half = 37;
  prt_result first = PRT_ERROR_INVALID_OPERATION, second = PRT_ERROR_INVALID_OPERATION;
  std::thread worker(
      [&] { first = prt_sh_shade(a.asset, PRT_BACKEND_CPU, light.data(), 0, half, split.data()); });
  second = prt_sh_shade(a.asset, PRT_BACKEND_CPU, light.data(), half, t.vertices - half,
                        split.data() + 3 * half);
  worker.join();
  ASSERT_EQ(first, PRT_OK);
  ASSERT_EQ(second, PRT_OK);
  EXPECT_EQ(whole, split);
  std::vector<float> decoded_whole(size_t(t.vertices) * t.coefficients()),
      decoded_split(decoded_whole.size());
  ASSERT_EQ(prt_sh_decode_transfer(a.asset, 0, t.vertices, decoded_whole.data()), PRT_OK);
  ASSERT_EQ(prt_sh_decode_transfer(a.asset, 0, half, decoded_split.data()), PRT_OK);
  ASSERT_EQ(prt_sh_decode_transfer(a.asset, half, t.vertices - half,
                                   decoded_split.data() + size_t(half) * t.coefficients()),
            PRT_OK);
  EXPECT_EQ(decoded_whole, decoded_split);
}

TEST_F(ShAsset, RejectsInvalidRangesAndArguments) {
  const Transfer t = random_transfer(2, 8, 3, 8, 11);
  LoadedAsset a(ctx.ctx, make_blob(encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> light(12, 1.0f), out(1024, 0.0f);
  const uint32_t V = t.vertices;
  const uint32_t bad[][2] = {{V + 1, 0}, {0, V + 1},      {V, 1},
                             {1, V},     {1, UINT32_MAX}, {UINT32_MAX, 2}};
  for (const auto& r : bad) {
    EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_CPU, light.data(), r[0], r[1], out.data()),
              PRT_ERROR_INVALID_ARGUMENT)
        << r[0] << "+" << r[1];
    EXPECT_EQ(prt_sh_decode_transfer(a.asset, r[0], r[1], out.data()), PRT_ERROR_INVALID_ARGUMENT)
        << r[0] << "+" << r[1];
  }
  EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_CPU, nullptr, 0, V, out.data()),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_CPU, light.data(), 0, V, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_shade(nullptr, PRT_BACKEND_CPU, light.data(), 0, V, out.data()),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_decode_transfer(a.asset, 0, V, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_get_info(a.asset, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  // Empty ranges, including the one at the end, are valid and write nothing.
  EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_CPU, light.data(), V, 0, out.data()), PRT_OK);
  EXPECT_EQ(prt_sh_decode_transfer(a.asset, 0, 0, out.data()), PRT_OK);
  EXPECT_EQ(out[0], 0.0f);
}

TEST_F(ShAsset, AssetWithoutTransferReportsNotFound) {
  prt::format::BlobWriter w;
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  w.add_section(kVPOS, positions, sizeof positions, 3);
  LoadedAsset a(ctx.ctx, w.finish());
  ASSERT_EQ(a.result, PRT_OK);
  prt_sh_info info = prt::sized<prt_sh_info>();
  float light[3] = {1, 1, 1}, out[9];
  EXPECT_EQ(prt_sh_get_info(a.asset, &info), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_sh_decode_transfer(a.asset, 0, 1, out), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_CPU, light, 0, 1, out), PRT_ERROR_NOT_FOUND);
}

// The writer refuses these blobs, so they are made by editing the section table of a good one.
TEST_F(ShAsset, TransferWithoutPositionsIsCorrupt) {
  const Transfer t = random_transfer(2, 3, 1, 8, 12);
  prt::format::BlobWriter w;
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const Bytes shtr = encode(t);
  w.add_section(kVPOS, positions, sizeof positions, 3);
  w.add_section(kSHTR, shtr.data(), shtr.size(), t.vertices);
  Bytes blob = w.finish();
  ASSERT_EQ(validate(ctx.ctx, blob, PRT_VALIDATE_FULL), PRT_OK);
  put_u32(blob, entry(0) + PRT_BLOB_SEC_OFF_TAG, PRT_BLOB_TAG('X', 'P', 'O', 'S'));
  fix_header_checksum(blob);
  EXPECT_EQ(validate(ctx.ctx, blob, PRT_VALIDATE_QUICK), PRT_ERROR_CORRUPT);
}

struct Corruption {
  const char* name;
  std::function<void(Bytes&)> edit;  // on the SHTR bytes
  prt_result expected;               // at full validation
  // A header field that does not fit the section fails the load at either validation level
  // (CORRUPT, with a message containing this); nullptr: a content error, found by full
  // validation only.
  const char* quick_load_message;
};

// Base: order 2, 3 channels, 8 bits, 3 vertices: payload 32 + 96 + 36 = 164 bytes (no padding).
const Corruption kCorruptions[] = {
    {"order 0", [](Bytes& b) { put_u32(b, 0, 0); }, PRT_ERROR_CORRUPT, "order 0 is not in 1..16"},
    {"order 17", [](Bytes& b) { put_u32(b, 0, 17); }, PRT_ERROR_CORRUPT, "order 17"},
    {"order 3 (size no longer matches)", [](Bytes& b) { put_u32(b, 0, 3); }, PRT_ERROR_CORRUPT,
     "the header implies"},
    {"channels 2", [](Bytes& b) { put_u32(b, 8, 2); }, PRT_ERROR_CORRUPT, "2 channels"},
    {"channels 0", [](Bytes& b) { put_u32(b, 8, 0); }, PRT_ERROR_CORRUPT, "0 channels"},
    {"bits 12", [](Bytes& b) { put_u32(b, 12, 12); }, PRT_ERROR_CORRUPT, "12 bits"},
    {"reserved 24", [](Bytes& b) { put_u32(b, 24, 1); }, PRT_ERROR_CORRUPT, "reserved"},
    {"reserved 28", [](Bytes& b) { put_u32(b, 28, 0x80000000u); }, PRT_ERROR_CORRUPT, "reserved"},
    {"vertex_count 4 for 3 positions", [](Bytes& b) { put_u32(b, 4, 4); }, PRT_ERROR_CORRUPT,
     "header says 4 vertices"},
    {"vertex_count 2 for 3 positions",
     [](Bytes& b) {
       put_u32(b, 4, 2);
       b.resize(b.size() - 12);  // consistent size, so only the count disagrees
     },
     PRT_ERROR_CORRUPT, "header says 2 vertices"},
    {"raw size +4", [](Bytes& b) { b.resize(b.size() + 4, 0); }, PRT_ERROR_CORRUPT,
     "168 raw bytes"},
    {"raw size -4", [](Bytes& b) { b.resize(b.size() - 4); }, PRT_ERROR_CORRUPT, "160 raw bytes"},
    {"NaN scale", [](Bytes& b) { put_f32(b, 32 + 8 * 5 + 4, std::nanf("")); }, PRT_ERROR_NON_FINITE,
     nullptr},
    {"infinite offset",
     [](Bytes& b) { put_f32(b, 32 + 8 * 11, -std::numeric_limits<float>::infinity()); },
     PRT_ERROR_NON_FINITE, nullptr},
    {"negative scale", [](Bytes& b) { put_f32(b, 32 + 8 * 7 + 4, -1e-6f); }, PRT_ERROR_CORRUPT,
     nullptr},
};

TEST_F(ShAsset, EachCorruptHeaderFieldIsRejectedAtFullValidation) {
  const Transfer t = random_transfer(2, 3, 3, 8, 13);
  const Bytes good = encode(t);
  ASSERT_EQ(good.size(), 164u);
  ASSERT_EQ(validate(ctx.ctx, make_blob(good, 3), PRT_VALIDATE_FULL), PRT_OK);
  for (const Corruption& c : kCorruptions) {
    Bytes shtr = good;
    c.edit(shtr);
    for (bool zstd : {false, true}) {
      const Bytes blob = make_blob(shtr, 3, zstd);
      EXPECT_EQ(validate(ctx.ctx, blob, PRT_VALIDATE_FULL), c.expected) << c.name;
      EXPECT_EQ(load(ctx.ctx, blob, PRT_VALIDATE_FULL), c.expected) << c.name;
      // Content checks run at full validation only; the header is checked against the section
      // by every load, so a quick-loaded asset never reads by a header that lies about the size.
      LoadedAsset quick(ctx.ctx, blob, PRT_VALIDATE_QUICK);
      if (c.quick_load_message) {
        EXPECT_EQ(quick.result, PRT_ERROR_CORRUPT) << c.name;
        EXPECT_EQ(quick.asset, nullptr) << c.name;
        const std::string message = prt_context_last_message(ctx.ctx);
        EXPECT_NE(message.find("'SHTR'"), std::string::npos) << c.name << ": " << message;
        EXPECT_NE(message.find(c.quick_load_message), std::string::npos)
            << c.name << ": " << message;
        // Quick validation reads an uncompressed section's header in place, and agrees (the
        // writer keeps a section raw when zstd does not make it smaller).
        const bool compressed = blob[entry(2) + PRT_BLOB_SEC_OFF_CODEC] != PRT_BLOB_CODEC_NONE;
        EXPECT_EQ(validate(ctx.ctx, blob, PRT_VALIDATE_QUICK),
                  compressed ? PRT_OK : PRT_ERROR_CORRUPT)
            << c.name;
      } else {
        ASSERT_EQ(quick.result, PRT_OK) << c.name;
        EXPECT_EQ(prt_asset_techniques(quick.asset), 1u << PRT_TECHNIQUE_SH) << c.name;
      }
    }
  }
}

TEST_F(ShAsset, NonZeroPaddingAndElementCountMismatchAreCorrupt) {
  const Transfer t = random_transfer(1, 3, 1, 8, 14);  // payload 32 + 8 + 3 = 43: one pad byte
  Bytes shtr = encode(t);
  ASSERT_EQ(shtr.size(), 44u);
  ASSERT_EQ(validate(ctx.ctx, make_blob(shtr, 3), PRT_VALIDATE_FULL), PRT_OK);
  shtr[43] = 1;
  EXPECT_EQ(validate(ctx.ctx, make_blob(shtr, 3), PRT_VALIDATE_FULL), PRT_ERROR_CORRUPT);
  Bytes blob = make_blob(encode(t), 3);
  put_u64(blob, entry(2) + PRT_BLOB_SEC_OFF_ELEMENT_COUNT, 4);  // SHTR is section 2
  fix_header_checksum(blob);
  EXPECT_EQ(validate(ctx.ctx, blob, PRT_VALIDATE_QUICK), PRT_ERROR_CORRUPT);
}

}  // namespace
