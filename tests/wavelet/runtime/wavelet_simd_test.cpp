// SPDX-License-Identifier: MIT
// `wavelet` SIMD shading: each instruction set the CPU has (forced through the context's
// simd_isa_limit) against the scalar reference and against a sum in double computed here from
// the stored pairs, within Higham's rounding bound; every row length (the kernels' tails), vertex
// ranges, threads, quick-validated corrupt rows; and the dispatch (AUTO, limits, compiled out,
// GL). DISABLED_BunnySizedTiming prints the relight speed (run it with
// --gtest_also_run_disabled_tests; no timing is asserted).
#include <gtest/gtest.h>

#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <thread>
#include <vector>

#include "support/limited_context.hpp"
#include "support/simd_dispatch.hpp"
#include "wavelet/wavelet_blob_test_util.hpp"
#include "wavelet/wavelet_skip_check.hpp"

namespace {

using namespace prt_test;

// Higham's gamma_n = n u / (1 - n u), u = 2^-24.
double gamma_n(double n) {
  const double u = std::ldexp(1.0, -24);
  return n * u / (1.0 - n * u);
}

// How far SIMD and scalar may be apart for vertex v, channel c, both given the same prepared
// light P. Each computes vs * sum_i q_i P_i: n rounded products summed in some order (scalar: in
// stored order; SSE4.1: two interleaved accumulators; AVX2: FMAs into 2 x 2 lanes plus a tail,
// then the lanes added), each term passing through at most n roundings (Higham's dot-product
// bound: |error| <= gamma_n sum |q_i P_i|), then one rounding for the vertex scale. So each is
// within gamma_{n+1} vs sum |q P| of the exact value, and they are within twice that of each other.
double simd_bound(const WvltTransfer& t, const std::vector<float>& prepared, uint32_t v,
                  uint32_t c) {
  double magnitude = 0;
  for (const WvltPair& p : t.rows[v])
    magnitude += std::fabs(double(p.q) * double(prepared[4 * size_t(p.j) + c]));
  const double n = double(t.rows[v].size());
  return 2.0 * gamma_n(n + 1.0) * double(t.vertex_scale[3 * size_t(v) + c]) * magnitude;
}

// One instruction set, forced by the context's ISA limit; skipped where the CPU lacks it.
class WaveletSimd : public SimdIsaTest {
 protected:
  // SIMD vs scalar within simd_bound, and SIMD vs the double reference (unprepared light).
  void expect_simd_matches(const WvltTransfer& t, uint32_t light_seed) {
    LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
    ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx);
    const std::vector<float> light = wvlt_random_light(t.coefficients(), light_seed);
    std::vector<float> prepared(light.size());
    ASSERT_EQ(prt_wavelet_prepare_light(a.asset, light.data(), prepared.data(), nullptr), PRT_OK);
    std::vector<float> simd(3 * size_t(t.vertices)), scalar(simd.size());
    ASSERT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, prepared.data(), nullptr, 0, t.vertices,
                                simd.data()),
              PRT_OK);
    ASSERT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_CPU, prepared.data(), nullptr, 0, t.vertices,
                                scalar.data()),
              PRT_OK);
    for (uint32_t v = 0; v < t.vertices; ++v) {
      double reference[3], magnitude[3];
      wvlt_reference_shade(t, light, v, reference, magnitude);
      for (uint32_t c = 0; c < 3; ++c) {
        const size_t k = 3 * size_t(v) + c;
        ASSERT_NEAR(simd[k], scalar[k], simd_bound(t, prepared, v, c) + 1e-30)
            << "vertex " << v << " channel " << c << " (" << t.rows[v].size() << " pairs)";
        // Against the exact sum: one more rounding per term for bs L.
        ASSERT_NEAR(simd[k], reference[c],
                    gamma_n(double(t.rows[v].size()) + 2.0) * magnitude[c] + 1e-30)
            << "vertex " << v << " channel " << c;
      }
    }
  }
};

TEST_P(WaveletSimd, MatchesScalarOnCube16) {
  expect_simd_matches(wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 40, 100, 11), 12);
}

TEST_P(WaveletSimd, MatchesScalarOnCube64With1000NonZeros) {
  expect_simd_matches(wvlt_random(PRT_WAVELET_PARAM_CUBE, 64, 60, 1000, 13), 14);
}

TEST_P(WaveletSimd, MatchesScalarOnParaboloid128) {
  expect_simd_matches(wvlt_random(PRT_WAVELET_PARAM_DUAL_PARABOLOID, 128, 8, 3000, 15), 16);
}

TEST_P(WaveletSimd, EveryRowLengthAndBlockFill) {
  // Rows of 0..40 pairs (every tail of the 2- and 4-pair steps), then a full 256-pair block.
  WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 42, 40, 17);
  for (uint32_t v = 0; v < 41; ++v) t.rows[v].resize(v);
  t.rows[41].clear();
  for (uint32_t i = 0; i < 256; ++i) t.rows[41].push_back({512 + i, int8_t(i % 2 ? 127 : -127)});
  expect_simd_matches(t, 18);
}

TEST_P(WaveletSimd, ZeroLightBlocksAreSkippedExactly) {
  expect_zero_light_blocks_skipped(ctx, PRT_BACKEND_SIMD);
}

TEST_P(WaveletSimd, AllZeroRowIsExactlyZero) {
  WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 3, 20, 19);
  t.rows[1].clear();
  LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  const std::vector<float> light(4 * size_t(t.coefficients()), 3e30f);
  std::vector<float> rgb(9, -1.0f);
  ASSERT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, light.data(), nullptr, 1, 1, rgb.data()),
            PRT_OK);
  for (uint32_t c = 0; c < 3; ++c) EXPECT_EQ(rgb[c], 0.0f);
  EXPECT_EQ(rgb[3], -1.0f);  // nothing written past the range
}

TEST_P(WaveletSimd, RangesAndThreadsGiveTheSameBits) {
  const WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 32, 96, 300, 20);
  LoadedAsset a(ctx, wvlt_make_blob(wvlt_encode(t), t.vertices));
  ASSERT_EQ(a.result, PRT_OK);
  const std::vector<float> light = wvlt_random_light(t.coefficients(), 21);
  std::vector<float> whole(3 * size_t(t.vertices)), threaded(whole.size()), part(3 * 7 + 1, -2.0f);
  ASSERT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, light.data(), nullptr, 0, t.vertices,
                              whole.data()),
            PRT_OK);
  ASSERT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, light.data(), nullptr, 50, 7, part.data()),
            PRT_OK);
  EXPECT_EQ(std::memcmp(part.data(), whole.data() + 150, 21 * 4), 0);
  EXPECT_EQ(part[21], -2.0f);
  std::vector<std::thread> pool;
  std::vector<prt_result> results(3);
  for (uint32_t i = 0; i < 3; ++i)
    pool.emplace_back([&, i] {
      results[i] = prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, light.data(), nullptr, 32 * i, 32,
                                     threaded.data() + 96 * size_t(i));
    });
  for (auto& thread : pool) thread.join();
  for (prt_result r : results) EXPECT_EQ(r, PRT_OK);
  EXPECT_EQ(std::memcmp(threaded.data(), whole.data(), whole.size() * 4), 0);
  EXPECT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, light.data(), nullptr, 90, 7, part.data()),
            PRT_ERROR_INVALID_ARGUMENT);
}

TEST_P(WaveletSimd, CorruptRowAtQuickValidationIsReported) {
  WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 5, 30, 22);
  Bytes section = wvlt_encode(t);
  // Vertex 4's last block claims 200 more pairs than the section holds after it.
  const size_t at = wvlt_offsets(t).counts + 2 * (size_t(4) * t.blocks() + t.blocks() - 1);
  put_u16(section, at, uint16_t(prt_le_load_u16(section.data() + at) + 200));
  LoadedAsset a(ctx, wvlt_make_blob(section, t.vertices), PRT_VALIDATE_QUICK);
  ASSERT_EQ(a.result, PRT_OK);
  const std::vector<float> light = wvlt_random_light(t.coefficients(), 23);
  std::vector<float> rgb(15);
  EXPECT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, light.data(), nullptr, 0, 4, rgb.data()),
            PRT_OK);
  EXPECT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_SIMD, light.data(), nullptr, 0, 5, rgb.data()),
            PRT_ERROR_CORRUPT);
}

INSTANTIATE_TEST_SUITE_P(Isa, WaveletSimd, kSimdIsas, isa_test_name);

// --- Dispatch -------------------------------------------------------------------------------

struct Scene {
  WvltTransfer t = wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 50, 200, 30);
  std::vector<float> light = wvlt_random_light(t.coefficients(), 31);
  Bytes blob = wvlt_make_blob(wvlt_encode(t), t.vertices);
};

// Shades all of the scene's asset on a backend.
ShadeAll shade_all(const Scene& s) {
  return [&s](const prt_asset* asset, prt_backend backend, std::vector<float>* out) {
    out->assign(3 * size_t(s.t.vertices), 0.0f);
    return prt_wavelet_shade(asset, backend, s.light.data(), nullptr, 0, s.t.vertices, out->data());
  };
}

TEST(WaveletSimdDispatch, AutoPicksSimdWhenUsable) {
  if (!simd_usable(limited_context().get()))
    GTEST_SKIP() << "SIMD not usable here (compiled out or no SSE4.1)";
  const Scene s;
  expect_auto_shades_as_simd(s.blob, shade_all(s));
}

TEST(WaveletSimdDispatch, ContextLimitedToCpuRefusesSimd) {
  const Scene s;
  expect_cpu_limit_refuses_simd(s.blob, shade_all(s));
}

TEST(WaveletSimdDispatch, IsaLimitNoneRefusesSimd) {
  const Scene s;
  expect_isa_limit_none_refuses_simd(s.blob, shade_all(s));
}

TEST(WaveletSimdDispatch, CompiledOutSimdIsUnsupported) {
  if (PRT_TEST_SIMD_COMPILED) GTEST_SKIP() << "SIMD is compiled in (see the `scalar` preset)";
  const Scene s;
  expect_compiled_out_simd_unsupported(s.blob, shade_all(s));
}

TEST(WaveletSimdDispatch, GlAndUnknownBackendsAreNotShadedHere) {
  const Scene s;
  expect_gl_not_shaded_here(s.blob, shade_all(s));
  // A value outside the enum, called directly (a std::function would load it as a prt_backend,
  // which UBSan rightly reports).
  const prt::ContextPtr context = limited_context();
  LoadedAsset a(context.get(), s.blob);
  ASSERT_EQ(a.result, PRT_OK);
  std::vector<float> out(3 * size_t(s.t.vertices));
  EXPECT_EQ(prt_wavelet_shade(a.asset, prt_backend(77), s.light.data(), nullptr, 0, s.t.vertices,
                              out.data()),
            PRT_ERROR_INVALID_ARGUMENT);
}

// --- Timing (manual) ------------------------------------------------------------------------

// CPU time of the calling thread: this machine is shared, and wall-clock figures there are
// diluted by the time the thread spends descheduled.
double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// STREAM triad a = b + s c over 3 x 64 MiB, best of 5, bytes per thread-CPU second by STREAM's
// convention (two reads and a write of 8 bytes per element).
double triad_bytes_per_second() {
  const size_t n = size_t(1) << 23;
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  double best = 1e30;
  for (int rep = 0; rep < 5; ++rep) {
    const double start = thread_seconds();
    for (size_t i = 0; i < n; ++i) a[i] = b[i] + 3.0 * c[i];
    best = std::min(best, thread_seconds() - start);
  }
  volatile double sink = a[n / 2];
  (void)sink;
  return 24.0 * double(n) / best;
}

// Prints scalar, SSE4.1 and AVX2 frame times for one transfer (best of 7, one thread).
void time_backends(const char* title, const WvltTransfer& t) {
  const Bytes blob = wvlt_make_blob(wvlt_encode(t), t.vertices);
  const std::vector<float> light = wvlt_random_light(t.coefficients(), 41);
  // Bytes one frame must stream: pairs, counts, row starts and vertex scales.
  const WvltOffsets o = wvlt_offsets(t);
  const double frame_bytes = double(o.payload_end - o.vertex_scale);
  const double triad = triad_bytes_per_second();
  std::printf(
      "%s: frame reads %.1f MB, light %.0f KB; STREAM triad %.2f GB/s -> roofline %.2f "
      "ms/frame\n",
      title, frame_bytes * 1e-6, 16e-3 * t.coefficients(), triad * 1e-9, 1e3 * frame_bytes / triad);
  const prt_simd_isa isas[] = {PRT_SIMD_ISA_NONE, PRT_SIMD_ISA_SSE41, PRT_SIMD_ISA_AVX2,
                               PRT_SIMD_ISA_AVX512};
  for (prt_simd_isa isa : isas) {
    const prt::ContextPtr limited = limited_context(PRT_BACKEND_AUTO, isa);
    prt_backend_info info = prt::sized<prt_backend_info>();
    prt_backend_get_info(limited.get(), PRT_BACKEND_SIMD, &info);
    if (isa != PRT_SIMD_ISA_NONE && (!info.usable || info.isa != isa)) continue;
    LoadedAsset a(limited.get(), blob);
    ASSERT_EQ(a.result, PRT_OK);
    std::vector<float> prepared(light.size()), rgb(3 * size_t(t.vertices));
    ASSERT_EQ(prt_wavelet_prepare_light(a.asset, light.data(), prepared.data(), nullptr), PRT_OK);
    const prt_backend backend = isa == PRT_SIMD_ISA_NONE ? PRT_BACKEND_CPU : PRT_BACKEND_SIMD;
    double best = 1e30;
    for (int rep = 0; rep < 7; ++rep) {
      const double start = thread_seconds();
      ASSERT_EQ(
          prt_wavelet_shade(a.asset, backend, prepared.data(), nullptr, 0, t.vertices, rgb.data()),
          PRT_OK);
      best = std::min(best, thread_seconds() - start);
    }
    std::printf("  %-7s %7.2f ms/frame  %6.1f fps  %5.2f GB/s  %4.0f%% of triad\n",
                isa == PRT_SIMD_ISA_NONE ? "scalar" : prt_simd_isa_name(isa), 1e3 * best,
                1.0 / best, frame_bytes / best * 1e-9, 100.0 * frame_bytes / best / triad);
  }
}

// A bunny-sized case: 36k vertices, 1000 non-zeros each, N = 64 (random indices:
// every light load a cache miss in L1), then the same pairs over an N = 16 cube whose 24 KB light
// stays in L1, which shows what the scattered light loads cost.
TEST(WaveletSimdTiming, DISABLED_BunnySizedTiming) {
  time_backends("N = 64", wvlt_random(PRT_WAVELET_PARAM_CUBE, 64, 36000, 1000, 40));
  time_backends("N = 16", wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 36000, 1000, 42));
}

}  // namespace
