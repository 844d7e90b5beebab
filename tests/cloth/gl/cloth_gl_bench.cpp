// SPDX-License-Identifier: MIT
// Frames per second of technique `cloth`'s GL backend, printed, never asserted:
// prt_gl_cloth_shade + glFinish over a G-buffer of random samples (cloth_gl_util.hpp; a tenth not
// cloth) at 640 x 480 and 320 x 240, for linen and satin over synthetic tables (ranks 8) under a
// light of 10 lobes, with the default settings; and the scalar reference (double, one thread) on
// a tile, scaled to the frame's pixels, for scale. On Mesa llvmpipe the "GPU" is the CPU
// (LP_NUM_THREADS threads, default: all cores).
//
//   prt_bench_cloth_gl [--benchmark_filter=...] [google benchmark flags]
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "cloth/gl/cloth_gl_util.hpp"
#include "support/bench_gl.hpp"

namespace {

constexpr uint32_t kLobes = 10;

prt_bench::SharedGl g_gl;

struct Figure {
  std::string what;
  double ms_per_frame = 0.0;
};
std::vector<Figure> g_figures;

void record(const std::string& what, double ms) {
  if (!g_figures.empty() && g_figures.back().what == what)
    g_figures.back().ms_per_frame = ms;
  else
    g_figures.push_back({what, ms});
}

prt_test::ClothAsset bench_asset(const char* fabric_name) {
  return prt_test::ClothAsset(
      prt_test::cloth_section(prt_test::presets({fabric_name}), prt_test::small_grid(), {8}, 1),
      16);
}

void BM_GlShade(benchmark::State& state, const char* fabric_name) {
  const uint32_t width = uint32_t(state.range(0)), height = uint32_t(state.range(1));
  if (!g_gl.get()) {
    state.SkipWithError(g_gl.missing().c_str());
    return;
  }
  prt_test::GlCalls gl;
  const prt_test::ClothAsset asset = bench_asset(fabric_name);
  prt_gl_cloth_shader* raw = nullptr;
  if (!asset.asset() || prt_gl_cloth_create(asset.context.get(), asset.asset(),
                                            headless_gl_get_proc, g_gl.get(), &raw) != PRT_OK) {
    state.SkipWithError(("prt_gl_cloth_create failed: " + asset.message()).c_str());
    return;
  }
  prt_test::GlClothShaderPtr shader(raw);
  const prt_test::GBufferSamples samples = prt_test::random_gbuffer(width, height, 2);
  const float clear[4] = {0, 0, 0, 0};
  prt_test::GlTarget target(gl, samples, 0, 0, clear);
  const prt_gl_cloth_gbuffer gbuffer = target.gbuffer();
  const std::vector<prt_cloth_lobe> lobes = prt_test::random_lobes(kLobes, 3);
  const prt_cloth_light light = prt_test::light_of(lobes);
  // The first draw compiles the shader in llvmpipe: keep it out of the timing.
  prt_gl_cloth_shade(raw, 0, nullptr, &light, nullptr, &gbuffer);
  gl.Finish();
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    prt_gl_cloth_shade(raw, 0, nullptr, &light, nullptr, &gbuffer);
    gl.Finish();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  const double ms = 1e3 * seconds / double(state.iterations());
  state.counters["fps"] = 1e3 / ms;
  record(std::string(fabric_name) + ", " + std::to_string(width) + "x" + std::to_string(height) +
             ", gl",
         ms);
}

// The scalar reference on a 160 x 120 tile, scaled to 640 x 480.
void BM_CpuShade(benchmark::State& state, const char* fabric_name) {
  const prt_test::ClothAsset asset = bench_asset(fabric_name);
  const prt_test::GBufferSamples samples = prt_test::random_gbuffer(160, 120, 2);
  const prt_cloth_pixels pixels = samples.pixels();
  const std::vector<prt_cloth_lobe> lobes = prt_test::random_lobes(kLobes, 3);
  const prt_cloth_light light = prt_test::light_of(lobes);
  std::vector<float> rgb(3 * size_t(samples.count()));
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    prt_cloth_shade(asset.asset(), PRT_BACKEND_CPU, 0, nullptr, &light, nullptr, &pixels, 0,
                    samples.count(), rgb.data());
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  const double ms =
      1e3 * seconds / double(state.iterations()) * (640.0 * 480.0) / double(samples.count());
  state.counters["fps"] = 1e3 / ms;
  record(std::string(fabric_name) + ", 640x480, cpu scalar (one thread)", ms);
}

BENCHMARK_CAPTURE(BM_GlShade, linen_plain, "linen_plain")
    ->Args({640, 480})
    ->Args({320, 240})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_GlShade, polyester_satin_charmeuse, "polyester_satin_charmeuse")
    ->Args({640, 480})
    ->Args({320, 240})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_CpuShade, linen_plain, "linen_plain")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (!g_figures.empty()) {
    std::printf(
        "\ncloth shading, %u lobes, default settings, on %s (%d llvmpipe threads where "
        "llvmpipe):\n",
        kLobes, g_gl.renderer().c_str(), prt_bench::llvmpipe_threads());
    for (const Figure& f : g_figures)
      std::printf("  %-50s %9.1f ms per frame %8.2f frames per second\n", f.what.c_str(),
                  f.ms_per_frame, 1e3 / f.ms_per_frame);
  }
  g_gl.destroy();
  return 0;
}
