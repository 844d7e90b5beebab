// SPDX-License-Identifier: MIT
// GL relight throughput of technique `wavelet` (prt_gl_wavelet_*) on a headless EGL context, in
// one run with the memory-bandwidth roofline it is compared with; printed, never asserted.
//  - STREAM triad on 1 and 2 threads (bench_triad.hpp);
//  - prt_gl_wavelet_shade of the bunny-sized, bake-shaped transfer of wavelet_bench_asset.hpp
//    (35,947 vertices, N = 64 cube, about 1000 pairs per vertex): vertices/s and frames/s
//    excluding readback (light upload + shade + glFinish) and including it (+ prt_gl_wavelet_read
//    of every vertex), next to the implementation report's 3 frames/s for 40,000 vertices. On
//    Mesa llvmpipe the "GPU" is the CPU (LP_NUM_THREADS threads, default: all cores), so the CPU's
//    memory roofline applies: the summary gives the rows streamed per second (pairs, block counts,
//    row start, vertex scale + 12 B radiance written, + 12 B read back) as a share of the triad
//    on as many threads as llvmpipe uses, alone and with the light gathers (16 B per pair).
//
//   prt_bench_wavelet_gl [--benchmark_filter=...] [google benchmark flags]
#include <benchmark/benchmark.h>
#include <prt/prt.h>
#include <prt/prt_gl.h>
#include <prt/prt_wavelet_asset.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "support/bench_gl.hpp"
#include "support/bench_triad.hpp"
#include "wavelet/wavelet_bench_asset.hpp"

namespace {

struct GlFigure {
  bool readback = false;
  double vertices_per_second = 0.0;      // by wall clock
  double vertices_per_cpu_second = 0.0;  // by the process's CPU time (llvmpipe's threads too)
};

struct Figures {
  double triad[3] = {0, 0, 0};      // bytes/s by thread count 1, 2, by wall clock
  double triad_cpu[3] = {0, 0, 0};  // the same by the CPU time of the triad's threads
  std::vector<GlFigure> gl;
  prt_bench::WaveletTraffic traffic;
} g_figures;

prt_bench::SharedGl g_gl;

// The memory roofline (bench_triad.hpp), by wall clock and by CPU time.
void BM_StreamTriad(benchmark::State& state) {
  const int threads = int(state.range(0));
  const prt_bench::Rate rate = prt_bench::stream_triad(state, threads);
  g_figures.triad[threads] = rate.wall;
  g_figures.triad_cpu[threads] = rate.cpu;
}
BENCHMARK(BM_StreamTriad)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(0.5);

// The asset in its own context with its GL shader and a prepared light; built once.
struct GlBench {
  prt_context* context = nullptr;
  prt_test::Bytes blob;
  std::unique_ptr<prt_test::LoadedAsset> loaded;
  prt_gl_wavelet_shader* shader = nullptr;
  std::vector<float> light;
  GlBench() {
    prt_context_create(nullptr, &context);
    const prt_test::WvltTransfer t = prt_bench::bake_shaped_transfer();
    g_figures.traffic = prt_bench::wavelet_traffic(t);
    blob = prt_test::wvlt_make_blob(prt_test::wvlt_encode(t), t.vertices);
    loaded = std::make_unique<prt_test::LoadedAsset>(context, blob);
    light = prt_test::wvlt_random_light(t.coefficients(), 3);
    if (loaded->result == PRT_OK &&
        prt_wavelet_prepare_light(loaded->asset, light.data(), light.data(), nullptr) == PRT_OK)
      prt_gl_wavelet_create(context, loaded->asset, headless_gl_get_proc, g_gl.get(), &shader);
  }
  ~GlBench() {
    prt_gl_wavelet_destroy(shader);
    loaded.reset();
    prt_context_destroy(context);
  }
  std::string error() const { return prt_context_last_message(context); }
};

// Made on first use, destroyed in main while the GL context is still current.
std::unique_ptr<GlBench> g_bench;
GlBench& bench() {
  if (!g_bench) g_bench = std::make_unique<GlBench>();
  return *g_bench;
}

void BM_GlRelight(benchmark::State& state, bool readback) {
  if (!g_gl.get()) {
    state.SkipWithError(g_gl.missing().c_str());
    return;
  }
  GlBench& b = bench();
  if (!b.shader) {
    state.SkipWithError(("prt_gl_wavelet_create failed: " + b.error()).c_str());
    return;
  }
  const uint32_t vertices = prt_bench::kBunnyVertices;
  using FinishFn = void (*)(void);
  FinishFn finish;
  void* address = headless_gl_get_proc(nullptr, "glFinish");
  std::memcpy(&finish, &address, sizeof finish);
  std::vector<float> rgb(3 * size_t(vertices));
  // The first dispatch compiles the shader in llvmpipe: keep it out of the timing.
  prt_gl_wavelet_shade(b.shader, b.light.data(), 0, vertices);
  prt_gl_wavelet_read(b.shader, 0, vertices, rgb.data());
  double seconds = 0.0, cpu_seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = prt_bench::process_cpu_seconds();
    prt_gl_wavelet_shade(b.shader, b.light.data(), 0, vertices);
    if (readback)
      prt_gl_wavelet_read(b.shader, 0, vertices, rgb.data());
    else
      finish();
    cpu_seconds += prt_bench::process_cpu_seconds() - cpu_start;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(rgb.data());
  }
  const double shaded = double(vertices) * double(state.iterations());
  state.counters["vertices/s"] = benchmark::Counter(shaded, benchmark::Counter::kIsRate);
  state.counters["frames/s"] =
      benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  GlFigure figure;
  figure.readback = readback;
  figure.vertices_per_second = shaded / seconds;
  figure.vertices_per_cpu_second = shaded / cpu_seconds;
  // Google Benchmark calls this several times while it sizes the run: keep the last call.
  std::vector<GlFigure>& figures = g_figures.gl;
  if (!figures.empty() && figures.back().readback == readback)
    figures.back() = figure;
  else
    figures.push_back(figure);
}
BENCHMARK_CAPTURE(BM_GlRelight, no_readback, false)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(0.5);
BENCHMARK_CAPTURE(BM_GlRelight, with_readback, true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(0.5);

// llvmpipe's thread count: LP_NUM_THREADS, else one per core (capped at 2 for the triad we have).
void print_summary() {
  const Figures& f = g_figures;
  const prt_bench::WaveletTraffic& w = f.traffic;
  std::printf("\nsummary\n");
  std::printf(
      "  memory bandwidth (triad), by wall clock: %.2f GB/s on 1 thread, %.2f GB/s on 2; by CPU "
      "time: %.2f, %.2f\n",
      f.triad[1] * 1e-9, f.triad[2] * 1e-9, f.triad_cpu[1] * 1e-9, f.triad_cpu[2] * 1e-9);
  if (!g_gl.missing().empty()) {
    std::printf("  gl: %s\n", g_gl.missing().c_str());
    return;
  }
  const int threads = prt_bench::llvmpipe_threads();
  std::printf(
      "\n  gl relight on %s: %u vertices, cube N = %u, %.0f pairs per vertex; per vertex %.0f B "
      "of rows + 12 B radiance (+ 12 B read back), %.0f B of light gathered; %% of the "
      "%d-thread triad\n",
      g_gl.renderer().c_str(), prt_bench::kBunnyVertices, prt_bench::kWaveletSize,
      w.pairs_per_vertex, w.streamed_per_vertex, w.gathered_per_vertex, threads);
  std::printf("  paper (Ng et al. 2003 implementation report): %.0f frames/s for %.0f vertices\n",
              prt_bench::kPaperFps, prt_bench::kPaperVertices);
  // By wall clock (what a frame costs on this, possibly shared, machine) and per second of the
  // process's CPU time summed over llvmpipe's threads (not diluted by other load; the triad by
  // CPU time on as many threads is its roofline).
  std::printf("  %-10s %-9s %9s %9s %12s %16s\n", "readback", "by", "Mvert/s", "frames/s",
              "rows % triad", "+gathers % triad");
  for (const GlFigure& g : f.gl)
    for (int by_cpu = 0; by_cpu < 2; ++by_cpu) {
      const double rows = w.streamed_per_vertex + 12.0 + (g.readback ? 12.0 : 0.0);
      const double triad = by_cpu ? f.triad_cpu[threads] : f.triad[threads];
      const double rate = by_cpu ? g.vertices_per_cpu_second : g.vertices_per_second;
      if (triad <= 0.0) continue;
      std::printf("  %-10s %-9s %9.3f %9.1f %11.0f%% %15.0f%%\n",
                  g.readback ? "included" : "excluded", by_cpu ? "CPU time" : "wall", rate * 1e-6,
                  rate / prt_bench::kBunnyVertices, 100.0 * rate * rows / triad,
                  100.0 * rate * (rows + w.gathered_per_vertex) / triad);
    }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary();
  g_bench.reset();
  g_gl.destroy();
  return 0;
}
