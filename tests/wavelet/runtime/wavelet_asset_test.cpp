// SPDX-License-Identifier: MIT
// `wavelet` assets (WVLT section, formats/SPEC.md §7.2): the stored layout decoded by hand, header
// query, dense decoding, light preparation, scalar shading, vertex ranges and threads, and full
// and quick validation of corrupted sections. Blobs are built byte by byte from the layout table
// (wavelet_blob_test_util.hpp); expected values are recomputed here from the stored q and scales.
#include <gtest/gtest.h>

#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>
#include <prt/format/blob_writer.hpp>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "wavelet/wavelet_blob_test_util.hpp"
#include "wavelet/wavelet_skip_check.hpp"

namespace {

using namespace prt_test;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Higham's gamma_n = n u / (1 - n u) for float (u = 2^-24): the relative bound of n roundings.
double gamma_n(double n) {
  const double u = std::ldexp(1.0, -24);
  return n * u / (1.0 - n * u);
}

// Scalar shading of vertex v under the UNPREPARED light: the runtime rounds bs L (1), q bs L (1),
// sums n products in float (n - 1) and multiplies by vs (1): within gamma_{n+2} sum |terms|.
void expect_shading_matches_reference(const WvltTransfer& t, const std::vector<float>& light,
                                      const std::vector<float>& rgb, uint32_t first = 0) {
  for (uint32_t i = 0; i < rgb.size() / 3; ++i) {
    const uint32_t v = first + i;
    double expected[3], magnitude[3];
    wvlt_reference_shade(t, light, v, expected, magnitude);
    const double bound = gamma_n(double(t.rows[v].size()) + 2.0);
    for (uint32_t c = 0; c < 3; ++c)
      ASSERT_NEAR(rgb[3 * size_t(i) + c], expected[c], bound * magnitude[c] + 1e-30)
          << "vertex " << v << " channel " << c;
  }
}

class WaveletAsset : public ::testing::Test {
 protected:
  Context ctx;

  std::vector<float> prepare(const LoadedAsset& a, const std::vector<float>& light) {
    std::vector<float> prepared(light.size());
    EXPECT_EQ(prt_wavelet_prepare_light(a.asset, light.data(), prepared.data(), nullptr), PRT_OK);
    return prepared;
  }

  std::vector<float> shade_all(const LoadedAsset& a, const WvltTransfer& t,
                               const std::vector<float>& light) {
    const std::vector<float> prepared = prepare(a, light);
    std::vector<float> rgb(3 * size_t(t.vertices), -1.0f);
    EXPECT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_CPU, prepared.data(), nullptr, 0, t.vertices,
                                rgb.data()),
              PRT_OK);
    return rgb;
  }

  // Loads, checks the info, every decoded row (= q bs vs) and the shading of every vertex.
  void expect_round_trip(const WvltTransfer& t, bool zstd = false) {
    LoadedAsset a(ctx.ctx, wvlt_make_blob(wvlt_encode(t), t.vertices, zstd));
    ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx.ctx);
    prt_wavelet_info info = prt::sized<prt_wavelet_info>();
    ASSERT_EQ(prt_wavelet_get_info(a.asset, &info), PRT_OK);
    EXPECT_EQ(info.param, t.param);
    EXPECT_EQ(info.size, t.size);
    EXPECT_EQ(info.faces, t.param == 0 ? 6u : 2u);
    EXPECT_EQ(info.coefficient_count, info.faces * t.size * t.size);
    EXPECT_EQ(info.block_count, info.coefficient_count / 256);
    EXPECT_EQ(info.vertex_count, t.vertices);
    EXPECT_EQ(info.quantizer, t.quantizer);
    EXPECT_EQ(info.keep, t.keep);
    EXPECT_EQ(info.bounces, t.bounces);
    EXPECT_EQ(info.pair_count, t.pair_count());
    std::vector<float> row(3 * size_t(t.coefficients()));
    for (uint32_t v = 0; v < t.vertices; ++v) {
      ASSERT_EQ(prt_wavelet_decode_transfer(a.asset, v, 1, row.data()), PRT_OK);
      std::vector<float> expected(row.size(), 0.0f);
      for (const WvltPair& p : t.rows[v])
        for (uint32_t c = 0; c < 3; ++c)
          expected[3 * size_t(p.j) + c] =
              float(p.q) * t.band_scale[t.band(p.j)] * t.vertex_scale[3 * size_t(v) + c];
      for (size_t k = 0; k < row.size(); ++k)
        ASSERT_EQ(row[k], expected[k]) << "vertex " << v << " coefficient " << k / 3;
    }
    const std::vector<float> light = wvlt_random_light(t.coefficients(), 99);
    expect_shading_matches_reference(t, light, shade_all(a, t, light));
  }
};

// The layout itself: a known row found in the blob's bytes by §7.2's offsets and decoded here.
TEST_F(WaveletAsset, KnownRowDecodesByHandFromTheBlobBytes) {
  // Cube, S = 16: F = 6, 6 * 256 = 1536 coefficients, B = 6 blocks, log2 S + 1 = 5 bands/face.
  const uint32_t S = 16, V = 3, F = 6, B = 6, bands = 30;
  std::vector<std::vector<int8_t>> dense(V, std::vector<int8_t>(F * S * S, 0));
  // Vertex 1's known row: (j, q) across blocks 0, 1, 2 and 5; block 3 and 4 empty.
  const std::vector<std::pair<uint32_t, int>> known = {{0, 5},   {3, -7},   {255, 127}, {256, -127},
                                                       {300, 1}, {700, -1}, {1535, 42}};
  for (const auto& [j, q] : known) dense[1][j] = int8_t(q);
  dense[0][17] = 9;  // neighbours, so that vertex 1's pairs do not start at 0
  dense[0][600] = -3;
  dense[2][1000] = 77;
  std::vector<float> band_scale(bands), vertex_scale(3 * V);
  for (uint32_t b = 0; b < bands; ++b) band_scale[b] = 0.125f * float(b + 1);
  for (uint32_t i = 0; i < 3 * V; ++i) vertex_scale[i] = 0.5f + 0.25f * float(i);
  const WvltTransfer t =
      wvlt_from_dense(PRT_WAVELET_PARAM_CUBE, S, dense, band_scale, vertex_scale);
  const Bytes blob = wvlt_make_blob(wvlt_encode(t), V);

  // The section, uncompressed, from the table entry 2 (offset at +16, codec at +6).
  ASSERT_EQ(blob[entry(2) + 6], PRT_BLOB_CODEC_NONE);
  const size_t base = size_t(get_u64(blob, entry(2) + 16));
  ASSERT_EQ(get_u32(blob, base + 0), 0u);    // param
  ASSERT_EQ(get_u32(blob, base + 4), S);     // face size
  ASSERT_EQ(get_u32(blob, base + 8), V);     // vertices
  ASSERT_EQ(get_u32(blob, base + 24), 10u);  // pair count: 2 + 7 + 1
  // §7.2 offsets, written out: 32-byte header, f32[F (log2 S + 1)], f32[V][3], u32[V + 1],
  // u16[V][B], then the pairs.
  const size_t row_start = base + 32 + 4 * bands + 12 * V;
  const size_t counts = row_start + 4 * (V + 1);
  const size_t pairs = counts + 2 * V * B;
  EXPECT_EQ(get_u32(blob, row_start + 0), 0u);
  const uint32_t start = get_u32(blob, row_start + 4 * 1);
  const uint32_t end = get_u32(blob, row_start + 4 * 2);
  EXPECT_EQ(start, 2u);
  EXPECT_EQ(end, 9u);
  EXPECT_EQ(get_u32(blob, row_start + 4 * V), 10u);
  // Block counts of vertex 1, then its (index, value) pairs, 16 bits each.
  const uint16_t expected_counts[B] = {3, 2, 1, 0, 0, 1};
  std::vector<std::pair<uint32_t, int>> decoded;
  size_t at = pairs + 2 * size_t(start);
  for (uint32_t k = 0; k < B; ++k) {
    const uint16_t n =
        uint16_t(blob[counts + 2 * (B * 1 + k)] | blob[counts + 2 * (B * 1 + k) + 1] << 8);
    EXPECT_EQ(n, expected_counts[k]) << "block " << k;
    for (uint32_t i = 0; i < n; ++i, at += 2)
      decoded.push_back({256 * k + blob[at], int(int8_t(blob[at + 1]))});
  }
  EXPECT_EQ(at, pairs + 2 * size_t(end));
  EXPECT_EQ(decoded, known);

  LoadedAsset a(ctx.ctx, blob);
  ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx.ctx);
  std::vector<float> row(3 * size_t(F) * S * S);
  ASSERT_EQ(prt_wavelet_decode_transfer(a.asset, 1, 1, row.data()), PRT_OK);
  size_t nonzero = 0;
  for (float value : row) nonzero += value != 0.0f;
  EXPECT_EQ(nonzero, 3 * known.size());
  for (const auto& [j, q] : known) {
    // The band by hand: face j / 256, level = floor(log2 max(x, y)) (-1 at the origin).
    const uint32_t face = j / 256, x = j % 16, y = (j % 256) / 16, m = std::max(x, y);
    const int level = m == 0 ? -1 : int(std::floor(std::log2(double(m))));
    const uint32_t band = face * 5 + uint32_t(level + 1);
    for (uint32_t c = 0; c < 3; ++c)
      EXPECT_EQ(row[3 * size_t(j) + c], float(q) * band_scale[band] * vertex_scale[3 + c])
          << "j " << j << " channel " << c;
  }
}

TEST_F(WaveletAsset, RandomRowsRoundTripCube16) {
  expect_round_trip(wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 7, 100, 1));
}

TEST_F(WaveletAsset, RandomRowsRoundTripCube128) {
  expect_round_trip(wvlt_random(PRT_WAVELET_PARAM_CUBE, 128, 3, 2000, 2));
}

TEST_F(WaveletAsset, RandomRowsRoundTripParaboloid16) {
  expect_round_trip(wvlt_random(PRT_WAVELET_PARAM_DUAL_PARABOLOID, 16, 6, 60, 3));
}

TEST_F(WaveletAsset, RandomRowsRoundTripParaboloid128) {
  expect_round_trip(wvlt_random(PRT_WAVELET_PARAM_DUAL_PARABOLOID, 128, 3, 1500, 4));
}

TEST_F(WaveletAsset, ZstdCompressedSectionGivesTheSameResults) {
  WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 32, 20, 300, 5);
  t.quantizer = 0;
  t.bounces = 2;
  const Bytes zstd_blob = wvlt_make_blob(wvlt_encode(t), t.vertices, true);
  ASSERT_EQ(zstd_blob[entry(2) + 6], PRT_BLOB_CODEC_ZSTD);
  expect_round_trip(t, true);
}

TEST_F(WaveletAsset, BlockWith256NonZeros) {
  const uint32_t S = 16;
  std::vector<std::vector<int8_t>> dense(2, std::vector<int8_t>(6 * S * S, 0));
  for (uint32_t i = 0; i < 256; ++i)
    dense[1][256 * 4 + i] = int8_t(int(i % 254) - 127 + (i % 254 >= 127));
  dense[0][3] = 1;
  std::vector<float> bs(30, 0.25f), vs(6, 1.5f);
  const WvltTransfer t = wvlt_from_dense(PRT_WAVELET_PARAM_CUBE, S, dense, bs, vs);
  ASSERT_EQ(t.rows[1].size(), 256u);
  const Bytes section = wvlt_encode(t);
  EXPECT_EQ(get_u32(section, 0), 0u);
  EXPECT_EQ(prt_le_load_u16(section.data() + wvlt_offsets(t).counts + 2 * (6 + 4)), 256u);
  expect_round_trip(t);
}

TEST_F(WaveletAsset, RowWithAllKeptValuesEqual) {
  const uint32_t S = 16;
  std::vector<std::vector<int8_t>> dense(1, std::vector<int8_t>(2 * S * S, 0));
  for (uint32_t j = 0; j < 2 * S * S; j += 7) dense[0][j] = 127;
  std::vector<float> bs(10, 1.0f), vs = {0.2f, 0.3f, 0.4f};
  const WvltTransfer t = wvlt_from_dense(PRT_WAVELET_PARAM_DUAL_PARABOLOID, S, dense, bs, vs);
  expect_round_trip(t);
  // Under a constant light every term is equal: 127 L vs times the count, exactly in double.
  LoadedAsset a(ctx.ctx, wvlt_make_blob(wvlt_encode(t), 1));
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> light(4 * size_t(t.coefficients()), 0.5f);
  const std::vector<float> rgb = shade_all(a, t, light);
  const double n = double(t.rows[0].size());
  for (uint32_t c = 0; c < 3; ++c)
    EXPECT_NEAR(rgb[c], 127.0 * 0.5 * n * double(vs[c]), gamma_n(n + 2) * 127.0 * 0.5 * n);
}

TEST_F(WaveletAsset, AllZeroRowShadesToExactlyZero) {
  WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 4, 50, 6);
  t.rows[2].clear();  // no pairs: every block count 0, rs[3] = rs[2]
  t.rows[0].clear();
  LoadedAsset a(ctx.ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx.ctx);
  std::vector<float> light(4 * size_t(t.coefficients()), 1e30f);
  const std::vector<float> rgb = shade_all(a, t, light);
  for (uint32_t c = 0; c < 3; ++c) {
    EXPECT_EQ(rgb[0 + c], 0.0f);
    EXPECT_EQ(rgb[6 + c], 0.0f);
  }
  std::vector<float> row(3 * size_t(t.coefficients()), 1.0f);
  ASSERT_EQ(prt_wavelet_decode_transfer(a.asset, 2, 1, row.data()), PRT_OK);
  for (float value : row) ASSERT_EQ(value, 0.0f);
  expect_round_trip(t);
}

TEST_F(WaveletAsset, PrepareLightFoldsBandScalesInPlace) {
  const WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 32, 2, 10, 7);
  LoadedAsset a(ctx.ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> light = wvlt_random_light(t.coefficients(), 8);
  for (size_t j = 0; j < t.coefficients(); ++j) light[4 * j + 3] = 7.0f;  // padding is ignored
  const std::vector<float> original = light;
  ASSERT_EQ(prt_wavelet_prepare_light(a.asset, light.data(), light.data(), nullptr), PRT_OK);
  for (uint32_t j = 0; j < t.coefficients(); ++j) {
    for (uint32_t c = 0; c < 3; ++c)
      ASSERT_EQ(light[4 * size_t(j) + c], original[4 * size_t(j) + c] * t.band_scale[t.band(j)]);
    ASSERT_EQ(light[4 * size_t(j) + 3], 0.0f);
  }
}

TEST_F(WaveletAsset, ZeroLightBlocksAreSkippedExactly) {
  expect_zero_light_blocks_skipped(ctx.ctx, PRT_BACKEND_CPU);
}

TEST_F(WaveletAsset, VertexRangesAndThreadsGiveTheSameBits) {
  const WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 64, 120, 9);
  LoadedAsset a(ctx.ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  const std::vector<float> light = wvlt_random_light(t.coefficients(), 10);
  const std::vector<float> prepared = prepare(a, light);
  const std::vector<float> whole = shade_all(a, t, light);
  std::vector<float> part(3 * 13);
  ASSERT_EQ(
      prt_wavelet_shade(a.asset, PRT_BACKEND_CPU, prepared.data(), nullptr, 20, 13, part.data()),
      PRT_OK);
  EXPECT_EQ(std::memcmp(part.data(), whole.data() + 60, part.size() * 4), 0);
  expect_shading_matches_reference(t, light, part, 20);
  std::vector<float> threaded(whole.size());
  std::vector<std::thread> pool;
  std::vector<prt_result> results(4);
  for (uint32_t i = 0; i < 4; ++i)
    pool.emplace_back([&, i] {
      results[i] = prt_wavelet_shade(a.asset, PRT_BACKEND_CPU, prepared.data(), nullptr, 16 * i, 16,
                                     threaded.data() + 48 * size_t(i));
    });
  for (auto& thread : pool) thread.join();
  for (prt_result r : results) EXPECT_EQ(r, PRT_OK);
  EXPECT_EQ(std::memcmp(threaded.data(), whole.data(), whole.size() * 4), 0);
  // Empty and out-of-range ranges.
  EXPECT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_CPU, prepared.data(), nullptr, 64, 0, nullptr),
            PRT_OK);
  EXPECT_EQ(
      prt_wavelet_shade(a.asset, PRT_BACKEND_CPU, prepared.data(), nullptr, 60, 5, part.data()),
      PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(
      prt_wavelet_shade(a.asset, PRT_BACKEND_CPU, prepared.data(), nullptr, 65, 0, part.data()),
      PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_CPU, nullptr, nullptr, 0, 1, part.data()),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_decode_transfer(a.asset, 64, 1, part.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_get_info(nullptr, nullptr), PRT_ERROR_INVALID_ARGUMENT);
}

TEST_F(WaveletAsset, AssetWithoutWvltIsNotFound) {
  prt::format::BlobWriter w;
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint32_t tri[3] = {0, 1, 2};
  w.add_section(kWvltVPOS, positions, sizeof positions, 3);
  w.add_section(kWvltTRIS, tri, sizeof tri, 1);
  LoadedAsset a(ctx.ctx, w.finish());
  ASSERT_EQ(a.result, PRT_OK);
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  EXPECT_EQ(prt_wavelet_get_info(a.asset, &info), PRT_ERROR_NOT_FOUND);
  float light[4] = {0, 0, 0, 0}, out[3];
  EXPECT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_CPU, light, nullptr, 0, 1, out),
            PRT_ERROR_NOT_FOUND);
}

// --- Corruption: full validation rejects, quick validation never reads out of bounds ---------

struct Corruption {
  const char* name;
  std::function<void(const WvltTransfer&, Bytes&)> edit;  // edits the section bytes
  prt_result full;                                        // what full validation reports
  const char* message;                                    // a part of its message
  bool quick_shade_corrupt;  // at quick validation shading must return CORRUPT (else OK too)
  // The header, the size or rs[V] are wrong: the load fails at either validation level (CORRUPT,
  // with `message` in the message too), so nothing ever reads by them.
  bool quick_load_fails;
};

// Rows: vertex 0 one pair (pair 0), vertex 1 pairs 1-3 in block 0 (indices 2, 9, 40) and pair 4
// in block 1, vertex 2 pairs 5, 6; P = 7, rs = 0, 1, 5, 7; 2 padding bytes.
WvltTransfer corruption_subject() {
  const uint32_t S = 16;
  std::vector<std::vector<int8_t>> dense(3, std::vector<int8_t>(6 * S * S, 0));
  dense[0][5] = 1;
  dense[1][2] = 10, dense[1][9] = -20, dense[1][40] = 30, dense[1][300] = 40;
  dense[2][1400] = 6, dense[2][1500] = -5;
  return wvlt_from_dense(PRT_WAVELET_PARAM_CUBE, S, dense, std::vector<float>(30, 0.5f),
                         std::vector<float>(9, 1.0f));
}

size_t count_at(const WvltTransfer& t, uint32_t v, uint32_t k) {
  return wvlt_offsets(t).counts + 2 * (size_t(v) * t.blocks() + k);
}
size_t pair_at(const WvltTransfer& t, uint32_t index) {
  return wvlt_offsets(t).pairs + 2 * size_t(index);
}
size_t row_start_at(const WvltTransfer& t, uint32_t v) {
  return wvlt_offsets(t).row_start + 4 * size_t(v);
}

const Corruption kCorruptions[] = {
    {"count one too big", [](const WvltTransfer& t, Bytes& b) { put_u16(b, count_at(t, 1, 0), 4); },
     PRT_ERROR_CORRUPT, "vertex 1 block 1", true, false},
    {"count above 256", [](const WvltTransfer& t, Bytes& b) { put_u16(b, count_at(t, 1, 1), 300); },
     PRT_ERROR_CORRUPT, "vertex 1 block 1", true, false},
    {"count huge", [](const WvltTransfer& t, Bytes& b) { put_u16(b, count_at(t, 2, 5), 65535); },
     PRT_ERROR_CORRUPT, "vertex 2 block 5", true, false},
    {"counts sum below the row",
     [](const WvltTransfer& t, Bytes& b) { put_u16(b, count_at(t, 1, 1), 0); }, PRT_ERROR_CORRUPT,
     "vertex 1: block counts sum", true, false},
    {"index not increasing",
     [](const WvltTransfer& t, Bytes& b) { b[pair_at(t, 2)] = 41; },  // 41 after 9 then 40
     PRT_ERROR_CORRUPT, "vertex 1 block 0", false, false},
    {"duplicate index", [](const WvltTransfer& t, Bytes& b) { b[pair_at(t, 2)] = 2; },
     PRT_ERROR_CORRUPT, "vertex 1 block 0", false, false},
    {"value 0", [](const WvltTransfer& t, Bytes& b) { b[pair_at(t, 3) + 1] = 0; },
     PRT_ERROR_CORRUPT, "value 0", false, false},
    {"value -128", [](const WvltTransfer& t, Bytes& b) { b[pair_at(t, 4) + 1] = 0x80; },
     PRT_ERROR_CORRUPT, "value -128", false, false},
    {"row starts not monotone",
     [](const WvltTransfer& t, Bytes& b) { put_u32(b, row_start_at(t, 2), 0); }, PRT_ERROR_CORRUPT,
     "vertex 1", true, false},
    {"row start past the pairs",
     [](const WvltTransfer& t, Bytes& b) { put_u32(b, row_start_at(t, 1), 0xFFFFFFF0u); },
     PRT_ERROR_CORRUPT, "vertex 0", true, false},
    {"first row start not 0",
     [](const WvltTransfer& t, Bytes& b) { put_u32(b, row_start_at(t, 0), 1); }, PRT_ERROR_CORRUPT,
     "vertex 0", true, false},
    {"last row start not P",
     [](const WvltTransfer& t, Bytes& b) { put_u32(b, row_start_at(t, 3), 5); }, PRT_ERROR_CORRUPT,
     "last row start", true, true},
    {"NaN band scale",
     [](const WvltTransfer& t, Bytes& b) { wvlt_put_f32(b, wvlt_offsets(t).band_scale + 8, kNaN); },
     PRT_ERROR_NON_FINITE, "band scale 2", false, false},
    {"negative band scale",
     [](const WvltTransfer& t, Bytes& b) { wvlt_put_f32(b, wvlt_offsets(t).band_scale, -1.0f); },
     PRT_ERROR_CORRUPT, "band scale 0 is negative", false, false},
    {"infinite vertex scale",
     [](const WvltTransfer& t, Bytes& b) {
       wvlt_put_f32(b, wvlt_offsets(t).vertex_scale + 12 + 4, INFINITY);
     },
     PRT_ERROR_NON_FINITE, "vertex 1 scale 1", false, false},
    {"negative vertex scale",
     [](const WvltTransfer& t, Bytes& b) {
       wvlt_put_f32(b, wvlt_offsets(t).vertex_scale + 24 + 8, -0.5f);
     },
     PRT_ERROR_CORRUPT, "vertex 2 scale 2 is negative", false, false},
    {"pair count disagrees with the size", [](const WvltTransfer&, Bytes& b) { put_u32(b, 24, 9); },
     PRT_ERROR_CORRUPT, "raw bytes", true, true},
    {"pair count within the padding",  // 8 pairs fit the same 4-byte-rounded size as 7
     [](const WvltTransfer&, Bytes& b) { put_u32(b, 24, 8); }, PRT_ERROR_CORRUPT, "last row start",
     true, true},
    {"param 2", [](const WvltTransfer&, Bytes& b) { put_u32(b, 0, 2); }, PRT_ERROR_CORRUPT,
     "param 2", true, true},
    {"size 24", [](const WvltTransfer&, Bytes& b) { put_u32(b, 4, 24); }, PRT_ERROR_CORRUPT,
     "face size 24", true, true},
    {"size 8", [](const WvltTransfer&, Bytes& b) { put_u32(b, 4, 8); }, PRT_ERROR_CORRUPT,
     "face size 8", true, true},
    {"quantizer 2", [](const WvltTransfer&, Bytes& b) { put_u32(b, 12, 2); }, PRT_ERROR_CORRUPT,
     "quantizer", true, true},
    {"reserved field", [](const WvltTransfer&, Bytes& b) { put_u32(b, 28, 1); }, PRT_ERROR_CORRUPT,
     "reserved", true, true},
    {"vertex count", [](const WvltTransfer&, Bytes& b) { put_u32(b, 8, 2); }, PRT_ERROR_CORRUPT,
     "vertices", true, true},
    {"padding", [](const WvltTransfer&, Bytes& b) { b.back() = 1; }, PRT_ERROR_CORRUPT, "padding",
     false, false},
};

class WaveletCorruption : public ::testing::TestWithParam<Corruption> {
 protected:
  Context ctx;
};

TEST_P(WaveletCorruption, FullRejectsQuickStaysInBounds) {
  const Corruption& c = GetParam();
  const WvltTransfer t = corruption_subject();
  Bytes section = wvlt_encode(t);
  ASSERT_EQ(wvlt_offsets(t).payload_end % 4, 2u) << "the subject needs padding for the test";
  ASSERT_EQ(validate(ctx.ctx, wvlt_make_blob(section, t.vertices), PRT_VALIDATE_FULL), PRT_OK);
  c.edit(t, section);
  for (bool zstd : {false, true}) {
    const Bytes blob = wvlt_make_blob(section, t.vertices, zstd);
    auto copy = exact_copy(blob);
    char msg[256] = "";
    EXPECT_EQ(
        prt_asset_validate(ctx.ctx, copy.get(), blob.size(), PRT_VALIDATE_FULL, msg, sizeof msg),
        c.full)
        << msg;
    EXPECT_NE(std::string(msg).find(c.message), std::string::npos) << msg;

    LoadedAsset a(ctx.ctx, blob, PRT_VALIDATE_QUICK);
    if (c.quick_load_fails) {
      EXPECT_EQ(a.result, PRT_ERROR_CORRUPT);
      EXPECT_EQ(a.asset, nullptr);
      const std::string quick_message = prt_context_last_message(ctx.ctx);
      EXPECT_NE(quick_message.find("'WVLT'"), std::string::npos) << quick_message;
      EXPECT_NE(quick_message.find(c.message), std::string::npos) << quick_message;
      // Quick validation reads an uncompressed section's header in place, and agrees (the
      // writer keeps a section raw when zstd does not make it smaller).
      const bool compressed = blob[entry(2) + PRT_BLOB_SEC_OFF_CODEC] != PRT_BLOB_CODEC_NONE;
      EXPECT_EQ(validate(ctx.ctx, blob, PRT_VALIDATE_QUICK),
                compressed ? PRT_OK : PRT_ERROR_CORRUPT);
      continue;
    }
    ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx.ctx);
    EXPECT_EQ(prt_asset_techniques(a.asset), 1u << PRT_TECHNIQUE_WAVELET);
    prt_wavelet_info info = prt::sized<prt_wavelet_info>();
    ASSERT_EQ(prt_wavelet_get_info(a.asset, &info), PRT_OK);
    std::vector<float> light = wvlt_random_light(t.coefficients(), 3);
    std::vector<float> rgb(3 * size_t(t.vertices));
    std::vector<uint8_t> zero_blocks(t.blocks());
    ASSERT_EQ(prt_wavelet_prepare_light(a.asset, light.data(), light.data(), zero_blocks.data()),
              PRT_OK);
    for (prt_backend backend : {PRT_BACKEND_CPU, PRT_BACKEND_SIMD}) {
      for (const uint8_t* mask : {static_cast<const uint8_t*>(nullptr),
                                  static_cast<const uint8_t*>(zero_blocks.data())}) {
        const prt_result r =
            prt_wavelet_shade(a.asset, backend, light.data(), mask, 0, t.vertices, rgb.data());
        if (r == PRT_ERROR_UNSUPPORTED_BACKEND) continue;
        if (c.quick_shade_corrupt)
          EXPECT_EQ(r, PRT_ERROR_CORRUPT) << prt_backend_name(backend);
        else
          EXPECT_TRUE(r == PRT_OK || r == PRT_ERROR_CORRUPT) << prt_backend_name(backend);
        for (uint32_t v = 0; v < t.vertices; ++v)  // one by one too: every row's own checks
          prt_wavelet_shade(a.asset, backend, light.data(), mask, v, 1, rgb.data());
      }
    }
    std::vector<float> row(3 * size_t(t.coefficients()));
    for (uint32_t v = 0; v < t.vertices; ++v) {
      const prt_result r = prt_wavelet_decode_transfer(a.asset, v, 1, row.data());
      EXPECT_TRUE(r == PRT_OK || r == PRT_ERROR_CORRUPT);
    }
  }
}

std::string corruption_name(const ::testing::TestParamInfo<Corruption>& info) {
  std::string name;
  for (const char* p = info.param.name; *p; ++p)
    name += std::isalnum(static_cast<unsigned char>(*p)) ? *p : '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Section, WaveletCorruption, ::testing::ValuesIn(kCorruptions),
                         corruption_name);

}  // namespace
