// SPDX-License-Identifier: MIT
// The SIMD backend of `sh` shading (prt_sh_shade with PRT_BACKEND_SIMD): each instruction set
// the CPU has (forced through the context's simd_isa_limit) against a sum in double computed here
// from the stored q, offset and scale, over every layout (order 1..16, grey and RGB transfer, 8
// and 16 bits), vertex ranges, threads, extreme lights; and the dispatch (AUTO, limits, compiled
// out, GL). Blobs are built byte by byte (sh_blob_test_util.hpp) and loaded from exact-size heap
// copies, so ASan sees any read past the SHTR section.
#include <gtest/gtest.h>

#include <prt/format/blob_writer.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "sh/sh_blob_test_util.hpp"
#include "support/limited_context.hpp"
#include "support/simd_dispatch.hpp"

namespace {

using namespace prt_test;

// Light coefficients in [-amplitude, amplitude], order^2 RGB triples.
std::vector<float> random_light(uint32_t order, uint32_t seed, float amplitude = 2.0f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-amplitude, amplitude);
  std::vector<float> light(size_t(order) * order * 3);
  for (float& l : light) l = unit(rng);
  return light;
}

// Channel ch of vertex v in double from the stored values, and how far a float result may be
// from it. The kernel rounds each weight scale_j L_j to float (1 rounding); per lane it sums
// ceil(n^2/4) products with a multiply and an add (SSE4.1: 2 roundings each) or ceil(n^2/8)
// with an fma plus one block of 4 (AVX2); it adds the lanes (2 or 3 roundings) and the bias
// (1; the bias is summed in double and rounded once). With unit roundoff u = 2^-24 that is at
// most (n^2/2 + 8) u relative to M = sum_j (|offset_j L_j| + |scale_j q_j L_j|), the size of the
// terms actually summed (offset and scaled q are folded separately, so M rather than
// sum_j |t_j L_j|). We allow (n^2 + 8) 2^-23 M = (2 n^2 + 16) u M, at least twice that bound.
struct Expected {
  double value = 0.0, tolerance = 0.0;
};

Expected expected_radiance(const Transfer& t, const std::vector<float>& light, uint32_t v,
                           uint32_t ch) {
  const uint32_t n2 = t.order * t.order, c = t.channels == 3 ? ch : 0;
  double sum = 0.0, magnitude = 0.0;
  for (uint32_t k = 0; k < n2; ++k) {
    const uint32_t j = c * n2 + k;
    const double l = light[3 * k + ch];
    const double scaled_q = double(t.scale[j]) * double(t.q[size_t(v) * t.coefficients() + j]);
    sum += (double(t.offset[j]) + scaled_q) * l;
    magnitude += std::fabs(double(t.offset[j]) * l) + std::fabs(scaled_q * l);
  }
  return {sum, (n2 + 8) * std::ldexp(1.0, -23) * magnitude};
}

// Checks out (vertices first, first+1, ...) against the double sums.
void expect_matches_double_sum(const Transfer& t, const std::vector<float>& light, uint32_t first,
                               const std::vector<float>& out) {
  for (uint32_t i = 0; i < out.size() / 3; ++i)
    for (uint32_t ch = 0; ch < 3; ++ch) {
      const Expected e = expected_radiance(t, light, first + i, ch);
      ASSERT_NEAR(out[3 * size_t(i) + ch], e.value, e.tolerance)
          << "vertex " << first + i << " channel " << ch;
    }
}

// One instruction set, forced by the context's ISA limit; skipped where the CPU lacks it.
class ShSimd : public SimdIsaTest {
 protected:
  // SIMD shading of [first, first+count) into a vector of exactly 3*count floats.
  std::vector<float> shade(const LoadedAsset& a, const std::vector<float>& light, uint32_t first,
                           uint32_t count) {
    std::vector<float> out(size_t(count) * 3);
    EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_SIMD, light.data(), first, count, out.data()),
              PRT_OK);
    return out;
  }
};

TEST_P(ShSimd, MatchesTheDoubleSumForEveryLayout) {
  uint32_t seed = 100;
  for (uint32_t order : {1u, 2u, 3u, 6u, 8u, 16u})
    for (uint32_t channels : {1u, 3u})
      for (uint32_t bits : {8u, 16u})
        for (uint32_t vertices : {1u, 7u, 33u, 1000u}) {
          SCOPED_TRACE(testing::Message() << "order " << order << ", channels " << channels
                                          << ", bits " << bits << ", vertices " << vertices);
          const Transfer t = random_transfer(order, vertices, channels, bits, ++seed);
          // zstd sections are decoded into a buffer of exactly the section's size.
          LoadedAsset a(ctx, make_blob(encode(t), vertices, /*zstd=*/seed % 2 == 0));
          ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx);
          const std::vector<float> light = random_light(order, seed);
          expect_matches_double_sum(t, light, 0, shade(a, light, 0, vertices));
          if (HasFatalFailure()) return;
        }
}

TEST_P(ShSimd, AnyVertexRangeGivesTheSameBitsAsTheWholeAsset) {
  // Order 1 grey 8-bit has a 1-byte stride: its last vertices are the ones whose 4-value block
  // would pass the section's end. Order 3 RGB and order 6 grey 16-bit have unaligned strides.
  // The kernels shade vertices in groups: ranges starting off a group boundary shade a vertex in
  // a group in one call and alone in another, which must give the same bits.
  const Transfer layouts[] = {random_transfer(1, 7, 1, 8, 1),   random_transfer(2, 7, 1, 8, 2),
                              random_transfer(3, 33, 3, 8, 3),  random_transfer(6, 33, 1, 16, 4),
                              random_transfer(5, 33, 3, 16, 5), random_transfer(6, 33, 3, 8, 6)};
  for (const Transfer& t : layouts) {
    SCOPED_TRACE(testing::Message()
                 << "order " << t.order << ", channels " << t.channels << ", bits " << t.bits);
    LoadedAsset a(ctx, make_blob(encode(t), t.vertices, /*zstd=*/true));
    ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx);
    const std::vector<float> light = random_light(t.order, t.order);
    const std::vector<float> whole = shade(a, light, 0, t.vertices);
    expect_matches_double_sum(t, light, 0, whole);
    const uint32_t n = t.vertices;
    const uint32_t ranges[][2] = {{1, 1}, {2, n - 3}, {n - 1, 1}, {n - 3, 3}, {0, n - 1}, {3, 2}};
    for (const auto& range : ranges) {
      const std::vector<float> part = shade(a, light, range[0], range[1]);
      ASSERT_EQ(std::memcmp(part.data(), whole.data() + 3 * size_t(range[0]), part.size() * 4), 0)
          << "range " << range[0] << "+" << range[1];
    }
    // An empty range anywhere up to the end writes nothing; out may then be NULL.
    float sentinel[3] = {-7.0f, -7.0f, -7.0f};
    for (uint32_t first : {0u, n / 2, n}) {
      EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_SIMD, light.data(), first, 0, sentinel), PRT_OK);
      EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_SIMD, light.data(), first, 0, nullptr), PRT_OK);
    }
    EXPECT_EQ(sentinel[0], -7.0f);
    EXPECT_EQ(sentinel[2], -7.0f);
  }
}

TEST_P(ShSimd, TwoThreadsOnDisjointRangesGiveTheSingleCallResult) {
  const Transfer t = random_transfer(6, 1000, 3, 8, 21);
  LoadedAsset a(ctx, make_blob(encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  const std::vector<float> light = random_light(6, 22);
  const std::vector<float> single = shade(a, light, 0, t.vertices);
  expect_matches_double_sum(t, light, 0, single);
  // Both threads write into one array, right up to each other's first float.
  std::vector<float> split(single.size(), -1.0f);
  prt_result results[2] = {PRT_ERROR_INVALID_ARGUMENT, PRT_ERROR_INVALID_ARGUMENT};
  const uint32_t cut = 487;
  std::thread low([&] {
    results[0] = prt_sh_shade(a.asset, PRT_BACKEND_SIMD, light.data(), 0, cut, split.data());
  });
  std::thread high([&] {
    results[1] = prt_sh_shade(a.asset, PRT_BACKEND_SIMD, light.data(), cut, t.vertices - cut,
                              split.data() + 3 * size_t(cut));
  });
  low.join();
  high.join();
  EXPECT_EQ(results[0], PRT_OK);
  EXPECT_EQ(results[1], PRT_OK);
  EXPECT_EQ(std::memcmp(split.data(), single.data(), single.size() * 4), 0);
}

TEST_P(ShSimd, ZeroLightGivesExactlyZero) {
  for (uint32_t channels : {1u, 3u}) {
    const Transfer t = random_transfer(4, 33, channels, 16, 30 + channels);
    LoadedAsset a(ctx, make_blob(encode(t), t.vertices));
    ASSERT_EQ(a.result, PRT_OK);
    const std::vector<float> light(16 * 3, 0.0f);
    for (float value : shade(a, light, 0, t.vertices)) ASSERT_EQ(value, 0.0f);
  }
}

// Behaviour under huge lights: the sums are in float, so the result is finite (and as accurate
// as ever, relatively) while every partial sum stays below FLT_MAX: 1e30 light on transfer values
// of at most 3 gives at most 36 * 3e30. Past FLT_MAX a channel becomes an infinity of the sum's
// sign when all terms share it (tested below); it is NaN where infinities of both signs meet, or
// where a folded weight scale_j L_j itself overflows and meets q_j = 0 (not tested: a light past
// FLT_MAX / scale_j, far beyond any physical radiance).
TEST_P(ShSimd, HugeLightIsFiniteBelowFloatOverflowAndInfiniteAbove) {
  const Transfer t = random_transfer(6, 33, 3, 8, 40);
  LoadedAsset a(ctx, make_blob(encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> light = random_light(6, 41, 1e30f);
  const std::vector<float> out = shade(a, light, 0, t.vertices);
  for (float value : out) ASSERT_TRUE(std::isfinite(value));
  expect_matches_double_sum(t, light, 0, out);

  // Non-negative transfer (offsets >= 0; scales are >= 0 by the layout) under a light of
  // FLT_MAX in every coefficient: every term is >= 0 and their sum passes FLT_MAX.
  Transfer positive = t;
  for (float& offset : positive.offset) offset = std::fabs(offset) + 0.5f;
  LoadedAsset b(ctx, make_blob(encode(positive), positive.vertices));
  ASSERT_EQ(b.result, PRT_OK);
  light.assign(light.size(), std::numeric_limits<float>::max());
  for (float value : shade(b, light, 0, positive.vertices))
    ASSERT_EQ(value, std::numeric_limits<float>::infinity());
  // The scalar reference, summing in double, says the same.
  std::vector<float> reference(size_t(positive.vertices) * 3);
  ASSERT_EQ(
      prt_sh_shade(b.asset, PRT_BACKEND_CPU, light.data(), 0, positive.vertices, reference.data()),
      PRT_OK);
  for (float value : reference) ASSERT_EQ(value, std::numeric_limits<float>::infinity());
}

TEST_P(ShSimd, RejectsWhatTheScalarPathRejects) {
  const Transfer t = random_transfer(2, 3, 3, 8, 50);
  LoadedAsset a(ctx, make_blob(encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  const std::vector<float> light = random_light(2, 51);
  float out[9];
  EXPECT_EQ(prt_sh_shade(nullptr, PRT_BACKEND_SIMD, light.data(), 0, 3, out),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_SIMD, nullptr, 0, 3, out),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_SIMD, light.data(), 0, 3, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_SIMD, light.data(), 1, 3, out),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_SIMD, light.data(), 4, 0, out),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_SIMD, light.data(), 1, UINT32_MAX, out),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_shade(a.asset, static_cast<prt_backend>(9), light.data(), 0, 3, out),
            PRT_ERROR_INVALID_ARGUMENT);
  // A header whose size disagrees with the section (order 3 in an order 2 section) does not
  // load even at quick validation, so no backend ever reads by it.
  Bytes shtr = encode(t);
  put_u32(shtr, 0, 3);
  LoadedAsset quick(ctx, make_blob(shtr, t.vertices), PRT_VALIDATE_QUICK);
  EXPECT_EQ(quick.result, PRT_ERROR_CORRUPT);
  EXPECT_EQ(quick.asset, nullptr);
}

INSTANTIATE_TEST_SUITE_P(Isa, ShSimd, kSimdIsas, isa_test_name);

// --- The AVX-512 fixed-point kernel ------------------------------------------------------------

// With AVX-512 VNNI, 8-bit RGB values go through the fixed-point kernel: the weights are rounded to
// 24-bit fixed point against each channel's largest (three 8-bit digits), each limb's dot product
// is exact, and only that rounding, the combination of the limbs, the bias and the float weights
// round. These tests compare it with
// the AVX2 float kernel on the same asset: skipped on a CPU without AVX-512.
class ShFixedPoint : public ::testing::Test {
 protected:
  void SetUp() override {
    prt_backend_info info = prt::sized<prt_backend_info>();
    ASSERT_EQ(prt_backend_get_info(avx512.get(), PRT_BACKEND_SIMD, &info), PRT_OK);
    if (!info.usable || info.isa != PRT_SIMD_ISA_AVX512)
      GTEST_SKIP() << "this CPU lacks AVX-512 VNNI (" << info.note << ")";
  }
  // All vertices of `t` shaded in `ctx` under `light`.
  static std::vector<float> shade(prt_context* ctx, const Transfer& t,
                                  const std::vector<float>& light) {
    LoadedAsset a(ctx, make_blob(encode(t), t.vertices));
    EXPECT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx);
    std::vector<float> out(size_t(t.vertices) * 3);
    EXPECT_EQ(prt_sh_shade(a.asset, PRT_BACKEND_SIMD, light.data(), 0, t.vertices, out.data()),
              PRT_OK);
    return out;
  }
  prt::ContextPtr avx512 = limited_context(PRT_BACKEND_AUTO, PRT_SIMD_ISA_AVX512);
  prt::ContextPtr avx2 = limited_context(PRT_BACKEND_AUTO, PRT_SIMD_ISA_AVX2);
};

// Its error is a few float roundings of the whole sum (the limbs combine in two multiply-adds,
// then the bias, and each float weight is rounded) plus the fixed-point rounding, at most
// 2^-24 max|w| sum q, about u M (u = 2^-24) for these lights, whose weights are within a small
// factor of each other: it stays within 8 u M at every order, where the float kernels'
// summation error grows with the order. A wrong digit split or a lost tail would be off by far
// more. Its bits differ from the AVX2 kernel's, which shows that it ran.
TEST_F(ShFixedPoint, EightBitIsShadedWithinAFewRoundingsOfTheExactSum) {
  double worst = 0.0;
  uint32_t seed = 700;
  for (uint32_t order : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 10u, 12u, 16u}) {
    SCOPED_TRACE(testing::Message() << "order " << order);
    const Transfer t = random_transfer(order, 203, 3, 8, ++seed);
    const std::vector<float> light = random_light(order, seed);
    const std::vector<float> fixed = shade(avx512.get(), t, light);
    EXPECT_NE(std::memcmp(fixed.data(), shade(avx2.get(), t, light).data(), fixed.size() * 4), 0)
        << "the AVX2 kernel's bits: the fixed-point kernel did not run";
    for (uint32_t v = 0; v < t.vertices; ++v)
      for (uint32_t ch = 0; ch < 3; ++ch) {
        const Expected e = expected_radiance(t, light, v, ch);
        const double magnitude = e.tolerance / ((order * order + 8) * std::ldexp(1.0, -23));
        const double error = std::fabs(fixed[3 * size_t(v) + ch] - e.value);
        worst = std::max(worst, error / magnitude);
        ASSERT_LE(error, 8.0 * std::ldexp(1.0, -24) * magnitude)
            << "vertex " << v << " channel " << ch;
      }
  }
  RecordProperty("worst_error_in_u_of_M", testing::PrintToString(worst / std::ldexp(1.0, -24)));
}

// A light whose weights span too wide a range for 24-bit fixed point to round the small ones
// within the bound (one coefficient 1e9 times the others, no offsets to widen the bound) is
// shaded by the AVX2 kernel instead: its bits exactly, and within the bound.
TEST_F(ShFixedPoint, WideRangeLightFallsBackToTheFloatKernel) {
  Transfer t = random_transfer(6, 65, 3, 8, 800);
  for (float& offset : t.offset) offset = 0.0f;
  std::vector<float> light = random_light(6, 801, 1e-3f);
  for (uint32_t ch = 0; ch < 3; ++ch) light[ch] = 1e6f;
  const std::vector<float> fixed = shade(avx512.get(), t, light);
  EXPECT_EQ(std::memcmp(fixed.data(), shade(avx2.get(), t, light).data(), fixed.size() * 4), 0);
  expect_matches_double_sum(t, light, 0, fixed);
}

// 16-bit values and grey transfer (one value for three channels) stay on the AVX2 kernel.
TEST_F(ShFixedPoint, SixteenBitAndGreyAreTheAvx2Kernels) {
  for (uint32_t bits : {8u, 16u})
    for (uint32_t channels : {1u, 3u}) {
      if (bits == 8 && channels == 3) continue;
      const Transfer t = random_transfer(6, 65, channels, bits, 810 + channels + bits);
      const std::vector<float> light = random_light(6, 812);
      const std::vector<float> fixed = shade(avx512.get(), t, light);
      EXPECT_EQ(std::memcmp(fixed.data(), shade(avx2.get(), t, light).data(), fixed.size() * 4), 0)
          << bits << "-bit, " << channels << " channel(s)";
    }
}

// --- Dispatch -------------------------------------------------------------------------------

struct Scene {
  Transfer t = random_transfer(6, 1000, 3, 8, 60);
  std::vector<float> light = random_light(6, 61);
  Bytes blob = make_blob(encode(t), t.vertices);
};

// Shades all of the scene's asset on a backend.
ShadeAll shade_all(const Scene& s) {
  return [&s](const prt_asset* asset, prt_backend backend, std::vector<float>* out) {
    out->assign(size_t(s.t.vertices) * 3, 0.0f);
    return prt_sh_shade(asset, backend, s.light.data(), 0, s.t.vertices, out->data());
  };
}

TEST(ShSimdDispatch, AutoPicksSimdWhenUsable) {
  if (!simd_usable(limited_context().get()))
    GTEST_SKIP() << "SIMD not usable here (compiled out or no SSE4.1)";
  const Scene s;
  // The reference sums in double and the kernels in float: over 3000 sums of 36 terms some last
  // bits differ, which shows that AUTO did not run the reference.
  EXPECT_FALSE(expect_auto_shades_as_simd(s.blob, shade_all(s)));
}

TEST(ShSimdDispatch, ContextLimitedToCpuRefusesSimd) {
  const Scene s;
  expect_cpu_limit_refuses_simd(s.blob, shade_all(s));
}

TEST(ShSimdDispatch, IsaLimitNoneRefusesSimd) {
  const Scene s;
  expect_isa_limit_none_refuses_simd(s.blob, shade_all(s));
}

TEST(ShSimdDispatch, CompiledOutSimdIsUnsupported) {
  if (PRT_TEST_SIMD_COMPILED) GTEST_SKIP() << "SIMD is compiled in (see the `scalar` preset)";
  const Scene s;
  expect_compiled_out_simd_unsupported(s.blob, shade_all(s));
}

TEST(ShSimdDispatch, GlIsNotShadedHere) {
  const Scene s;
  expect_gl_not_shaded_here(s.blob, shade_all(s));
}

}  // namespace
