// SPDX-License-Identifier: MIT
// The two 8-bit quantisers against the SPEC's writers' rules on hand-made rows (zero dropped,
// |q| <= 127, half away from zero, band scale = band max / 127, vertex scale = rho max / 127),
// the WVLT bytes decoded by hand from the loaded blob, a block holding 256 non-zeros, the round
// trip through the runtime (decode_row, shade), and the self-check (passes, and fails on a
// blob that does not match).
#include <gtest/gtest.h>

#include <prt/prt.h>
#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "prt/baker/wavelet/wavelet_blob.hpp"
#include "wavelet/wavelet_test_util.hpp"

namespace prt::bake {
namespace {

const float kUnit = std::ldexp(1.0f, -10);  // 2^-10: m/127 exact for m = 127 * 2^-10

// Three vertices of a 16-cube transfer (1536 coefficients): vertex 0 has five values, vertex 1
// none, vertex 2 two.
WaveletTransfer hand_transfer() {
  WaveletTransfer t;
  t.param = PRT_WAVELET_PARAM_CUBE;
  t.size = 16;
  t.vertex_count = 3;
  t.coefficient_count = 1536;
  t.index = {0, 1, 2, 300, 1535, 256, 257};
  t.value = {127 * kUnit, 2.5f * kUnit, -2.5f * kUnit, 0.4f * kUnit, -127 * kUnit, 1.0f, 0.5f};
  t.row_start = {0, 5, 5, 7};
  t.albedo = {{1.0f, 0.5f, 0.25f}, {1, 1, 1}, {0.8f, 0.8f, 0.8f}};
  t.baked = {1, 1, 1};
  return t;
}

// One triangle per three vertices, for a blob.
Scene triangle_scene(std::size_t vertices) {
  Scene scene;
  Mesh mesh;
  mesh.name = "tri";
  for (std::size_t v = 0; v < vertices; ++v) {
    mesh.positions.emplace_back(float(v % 3), float(v / 3), 0.0f);
    mesh.normals.emplace_back(0.0f, 0.0f, 1.0f);
  }
  for (std::uint32_t v = 0; v + 2 < vertices; v += 3)
    mesh.indices.insert(mesh.indices.end(), {v, v + 1, v + 2});
  scene.meshes.push_back(mesh);
  return scene;
}

// The band numbering itself is the runtime's prt_wavelet_band (tested by hand in
// tests/wavelet/runtime/wavelet_domain_test.cpp); here only the band count the quantiser sizes its
// table by.
TEST(WaveletQuantizer, BandCountFollowsTheSpec) {
  EXPECT_EQ(wavelet_band_count(PRT_WAVELET_PARAM_CUBE, 16), 30u);  // 6 faces x (log2 16 + 1)
  EXPECT_EQ(wavelet_band_count(PRT_WAVELET_PARAM_DUAL_PARABOLOID, 128), 16u);  // 2 x 8
}

TEST(WaveletQuantizer, VertexScaleIsTheRowMaxOver127) {
  const QuantizedWavelet q =
      quantize_wavelet_transfer(hand_transfer(), WaveletQuantizer::Vertex, 9);
  for (float b : q.band_scale) EXPECT_EQ(b, 1.0f);
  EXPECT_EQ(q.vertex_scale[0], kUnit);  // rho 1 * (127 * 2^-10) / 127
  EXPECT_EQ(q.vertex_scale[1], 0.5f * kUnit);
  EXPECT_EQ(q.vertex_scale[2], 0.25f * kUnit);
  EXPECT_EQ(q.vertex_scale[3], 0.0f);  // an empty row
  EXPECT_EQ(q.vertex_scale[6], 0.8f * (1.0f / 127.0f));
  // 127, 2.5 -> 3 and -2.5 -> -3 (half away from zero), 0.4 -> 0 (dropped), -127; then vertex 2:
  // 1 -> 127, 0.5 -> 63.5 -> 64.
  EXPECT_EQ(q.q, (std::vector<std::int8_t>{127, 3, -3, -127, 127, 64}));
  EXPECT_EQ(q.index, (std::vector<std::uint32_t>{0, 1, 2, 1535, 256, 257}));
  EXPECT_EQ(q.row_start, (std::vector<std::uint32_t>{0, 4, 4, 6}));
  EXPECT_EQ(q.dropped_to_zero, 1u);
  EXPECT_EQ(q.keep, 9u);
}

TEST(WaveletQuantizer, BandScaleIsTheBandMaxOver127) {
  const QuantizedWavelet q = quantize_wavelet_transfer(hand_transfer(), WaveletQuantizer::Band, 9);
  ASSERT_EQ(q.band_scale.size(), 30u);
  std::vector<float> expected(30, 0.0f);
  expected[0] = 127 * kUnit / 127.0f;
  expected[1] = 2.5f * kUnit / 127.0f;
  expected[2] = 2.5f * kUnit / 127.0f;
  expected[9] = 0.4f * kUnit / 127.0f;
  expected[29] = 127 * kUnit / 127.0f;
  expected[5] = 1.0f / 127.0f;
  expected[6] = 0.5f / 127.0f;
  EXPECT_EQ(q.band_scale, expected);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(q.vertex_scale[c], hand_transfer().albedo[0][c]);
  // Each value is its band's max here: all +-127, nothing dropped.
  EXPECT_EQ(q.q, (std::vector<std::int8_t>{127, 127, -127, 127, -127, 127, 127}));
  EXPECT_EQ(q.dropped_to_zero, 0u);
}

TEST(WaveletQuantizer, ZeroStaysZeroAndValuesStayInRange) {
  WaveletTransfer t = hand_transfer();
  // A dense-ish random row for vertex 1: many values, some tiny.
  std::vector<std::uint32_t> index;
  std::vector<float> value;
  for (std::uint32_t j = 0; j < 1536; j += 3) {
    index.push_back(j);
    value.push_back(std::sin(float(j) * 0.37f) * std::pow(10.0f, -float(j % 7)));
  }
  t.index.insert(t.index.begin() + 5, index.begin(), index.end());
  t.value.insert(t.value.begin() + 5, value.begin(), value.end());
  t.row_start = {0, 5, 5 + std::uint64_t(index.size()), 7 + std::uint64_t(index.size())};
  for (WaveletQuantizer mode : {WaveletQuantizer::Vertex, WaveletQuantizer::Band}) {
    const QuantizedWavelet q = quantize_wavelet_transfer(t, mode, 0);
    for (std::int8_t v : q.q) {
      EXPECT_NE(v, 0);
      EXPECT_GE(v, -127);
    }
    // Every dequantised value within half a step of the float one; dropped ones were below it.
    EXPECT_LE(q.max_abs_error, 0.5 * q.max_abs_value / 127.0 * 1.0001);
    EXPECT_EQ(q.pair_count() + q.dropped_to_zero, t.value.size());
  }
}

// Reads a little-endian value at `at` of the section bytes.
template <typename T>
T read(const std::uint8_t* bytes, std::size_t at) {
  T v;
  std::memcpy(&v, bytes + at, sizeof v);
  return v;
}

TEST(WaveletBlob, SectionDecodedByHandFromTheLoadedBlob) {
  const WaveletTransfer t = hand_transfer();
  const QuantizedWavelet q = quantize_wavelet_transfer(t, WaveletQuantizer::Vertex, 9);
  const std::vector<std::uint8_t> blob = build_wavelet_blob(triangle_scene(3), q, "hand");
  test::RuntimeAsset a;
  ASSERT_EQ(a.load(blob), PRT_OK) << a.message();
  const void* data = nullptr;
  std::size_t size = 0;
  ASSERT_EQ(prt_asset_section_data(a.asset, PRT_SECTION_WVLT, &data, &size), PRT_OK);
  const auto* b = static_cast<const std::uint8_t*>(data);
  // Header.
  EXPECT_EQ(read<std::uint32_t>(b, 0), 0u);   // cube
  EXPECT_EQ(read<std::uint32_t>(b, 4), 16u);  // S
  EXPECT_EQ(read<std::uint32_t>(b, 8), 3u);   // V
  EXPECT_EQ(read<std::uint32_t>(b, 12), 0u);  // vertex quantiser
  EXPECT_EQ(read<std::uint32_t>(b, 16), 9u);  // keep
  EXPECT_EQ(read<std::uint32_t>(b, 20), 0u);  // bounces
  EXPECT_EQ(read<std::uint32_t>(b, 24), 6u);  // pairs
  EXPECT_EQ(read<std::uint32_t>(b, 28), 0u);
  // Sizes: 30 band scales, 3 x 3 vertex scales, 4 row starts, 3 x 6 block counts, 6 pairs.
  const std::size_t bs = 32, vs = bs + 4 * 30, rs = vs + 36, n = rs + 16, pairs = n + 2 * 18;
  EXPECT_EQ(size, (pairs + 12 + 3) / 4 * 4);
  EXPECT_EQ(read<float>(b, bs), 1.0f);
  EXPECT_EQ(read<float>(b, vs + 4), 0.5f * kUnit);  // vs[0][G]
  EXPECT_EQ(read<std::uint32_t>(b, rs + 4), 4u);
  EXPECT_EQ(read<std::uint32_t>(b, rs + 12), 6u);
  // Vertex 0: block 0 holds j = 0, 1, 2, block 5 holds j = 1535; vertex 2: block 1 holds 2.
  const std::uint16_t counts[18] = {3, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0};
  for (int k = 0; k < 18; ++k) EXPECT_EQ(read<std::uint16_t>(b, n + 2 * k), counts[k]) << k;
  const std::uint8_t expected_pairs[12] = {0, 127, 1, 3, 2, 0xFD, 255, 0x81, 0, 127, 1, 64};
  for (int i = 0; i < 12; ++i) EXPECT_EQ(b[pairs + i], expected_pairs[i]) << i;
  for (std::size_t i = pairs + 12; i < size; ++i) EXPECT_EQ(b[i], 0u);  // padding

  // The runtime's dense row of vertex 0 and its shading agree with the hand values.
  std::vector<float> row(1536 * 3);
  ASSERT_EQ(prt_wavelet_decode_transfer(a.asset, 0, 1, row.data()), PRT_OK);
  EXPECT_EQ(row[0 * 3 + 0], 127 * kUnit);
  EXPECT_EQ(row[1 * 3 + 1], 3 * 0.5f * kUnit);
  EXPECT_EQ(row[2 * 3 + 2], -3 * 0.25f * kUnit);
  EXPECT_EQ(row[300 * 3], 0.0f);
  EXPECT_EQ(row[1535 * 3], -127 * kUnit);
  std::vector<float> light(1536 * 4, 0.0f);
  light[0] = 2.0f;         // j = 0, R
  light[1535 * 4] = 1.0f;  // j = 1535, R
  const std::vector<glm::vec3> shaded = test::runtime_shade(a, light);
  EXPECT_FLOAT_EQ(shaded[0].r, (127 * 2 - 127) * kUnit);
  EXPECT_EQ(shaded[1], glm::vec3(0.0f));
}

TEST(WaveletBlob, ABlockWith256NonZerosRoundTrips) {
  WaveletTransfer t = hand_transfer();
  t.index.clear();
  t.value.clear();
  for (std::uint32_t j = 256; j < 512; ++j) {  // all of block 1
    t.index.push_back(j);
    t.value.push_back(float(int(j % 200) - 100 + (j % 200 >= 100 ? 1 : 0)) * kUnit);
  }
  t.row_start = {0, 0, 256, 256};
  for (WaveletQuantizer mode : {WaveletQuantizer::Vertex, WaveletQuantizer::Band}) {
    const QuantizedWavelet q = quantize_wavelet_transfer(t, mode, 256);
    ASSERT_EQ(q.pair_count(), 256u);
    const std::vector<std::uint8_t> blob = build_wavelet_blob(triangle_scene(3), q, "");
    test::RuntimeAsset a;
    ASSERT_EQ(a.load(blob), PRT_OK) << a.message();
    std::vector<float> row(1536 * 3);
    ASSERT_EQ(prt_wavelet_decode_transfer(a.asset, 1, 1, row.data()), PRT_OK);
    for (std::uint32_t p = 0; p < 256; ++p) EXPECT_EQ(row[q.index[p] * 3], q.dequantized(1, 0, p));
    const WaveletBlobCheck check = check_wavelet_blob(blob, t, q);
    EXPECT_TRUE(check.passed) << check.message;
  }
}

TEST(WaveletBlob, SelfCheckFailsOnABlobThatDoesNotMatch) {
  const WaveletTransfer t = hand_transfer();
  const QuantizedWavelet q = quantize_wavelet_transfer(t, WaveletQuantizer::Band, 9);
  const std::vector<std::uint8_t> blob = build_wavelet_blob(triangle_scene(3), q, "");
  EXPECT_TRUE(check_wavelet_blob(blob, t, q).passed);
  QuantizedWavelet other = q;
  other.q[3] = static_cast<std::int8_t>(-other.q[3]);
  const std::vector<std::uint8_t> wrong = build_wavelet_blob(triangle_scene(3), other, "");
  const WaveletBlobCheck check = check_wavelet_blob(wrong, t, q);
  EXPECT_FALSE(check.passed);
  EXPECT_NE(check.message.find("differ"), std::string::npos) << check.message;
  std::vector<std::uint8_t> truncated(blob.begin(), blob.end() - 4);
  EXPECT_FALSE(check_wavelet_blob(truncated, t, q).passed);
  EXPECT_THROW(build_wavelet_blob(triangle_scene(6), q, ""), Error);
}

// 130 vertices with one pair each, but `fullest` with two.
WaveletTransfer one_pair_rows(std::uint32_t fullest) {
  WaveletTransfer t = hand_transfer();
  t.vertex_count = 130;
  t.index.clear();
  t.value.clear();
  t.row_start.assign(1, 0);
  for (std::uint32_t v = 0; v < 130; ++v) {
    t.index.push_back(v);
    t.value.push_back(1.0f);
    if (v == fullest) {
      t.index.push_back(v + 1);
      t.value.push_back(0.5f);
    }
    t.row_start.push_back(t.index.size());
  }
  t.albedo.assign(130, glm::vec3(0.8f));
  t.baked.assign(130, 1);
  return t;
}

std::size_t rows_checked(const WaveletTransfer& t) {
  const QuantizedWavelet q = quantize_wavelet_transfer(t, WaveletQuantizer::Band, 9);
  const WaveletBlobCheck check =
      check_wavelet_blob(build_wavelet_blob(triangle_scene(t.vertex_count), q, ""), t, q);
  EXPECT_TRUE(check.passed) << check.message;
  EXPECT_EQ(check.message.rfind(std::to_string(check.rows_checked) + " decoded rows", 0), 0u)
      << check.message;
  return check.rows_checked;
}

// The self-check decodes every (V / 64)-th row and the fullest, each once: all three rows of the
// hand transfer (the fullest, vertex 0, among them); of 130 vertices the 65 even ones, plus the
// fullest when it is odd.
TEST(WaveletBlob, SelfCheckDecodesEachSampledRowOnce) {
  EXPECT_EQ(rows_checked(hand_transfer()), 3u);
  EXPECT_EQ(rows_checked(one_pair_rows(128)), 65u);
  EXPECT_EQ(rows_checked(one_pair_rows(129)), 66u);
}

TEST(WaveletBlob, SameBytesTwice) {
  const QuantizedWavelet q = quantize_wavelet_transfer(hand_transfer(), WaveletQuantizer::Band, 9);
  EXPECT_EQ(build_wavelet_blob(triangle_scene(3), q, "x"),
            build_wavelet_blob(triangle_scene(3), q, "x"));
}

}  // namespace
}  // namespace prt::bake
