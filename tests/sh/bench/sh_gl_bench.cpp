// SPDX-License-Identifier: MIT
// GL shading throughput of technique `sh` (prt_gl.h) on a headless EGL context, in one run with
// the memory-bandwidth roofline it is compared with; printed, never asserted.
//  - STREAM triad on 1 and 2 threads (bench_triad.hpp, which needs neither the baker nor Embree);
//  - prt_gl_sh_shade of a random SHTR asset of 35,947 vertices (the Stanford bunny's count), RGB
//    transfer at orders 2/4/6/8 and 8/16 bits: vertices/s excluding readback (shade + glFinish)
//    and including it (shade + prt_gl_sh_read of every vertex). On Mesa llvmpipe the "GPU" is
//    the CPU (LP_NUM_THREADS threads, default: all cores), so the CPU's memory roofline applies:
//    the summary gives the bytes moved per second (quantised transfer read + 12 B of radiance
//    written, + 12 B copied back with readback) as a share of the triad on as many threads as
//    llvmpipe uses.
//
//   prt_bench_sh_gl [--benchmark_filter=...] [google benchmark flags]
#include <benchmark/benchmark.h>
#include <prt/prt.h>
#include <prt/prt_gl.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "sh/sh_blob_test_util.hpp"
#include "support/bench_gl.hpp"
#include "support/bench_triad.hpp"

namespace {

constexpr uint32_t kVertices = 35947, kChannels = 3;

struct GlFigure {
  uint32_t order = 0, bits = 0;
  bool readback = false;
  double vertices_per_second = 0.0, bytes_per_vertex = 0.0;
};

struct Figures {
  double triad[3] = {0, 0, 0};  // bytes/s by thread count 1, 2
  std::vector<GlFigure> gl;
} g_figures;

prt_bench::SharedGl g_gl;

// The memory roofline (bench_triad.hpp), by wall clock: llvmpipe's threads are not ours to time.
void BM_StreamTriad(benchmark::State& state) {
  const int threads = int(state.range(0));
  g_figures.triad[threads] = prt_bench::stream_triad(state, threads).wall;
}
BENCHMARK(BM_StreamTriad)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(0.5);

// One asset in its own context, with its GL shader.
struct GlBench {
  prt_context* context = nullptr;
  std::unique_ptr<prt_test::LoadedAsset> loaded;
  prt_gl_sh_shader* shader = nullptr;
  std::vector<float> light;
  GlBench(uint32_t order, uint32_t bits) {
    prt_context_create(nullptr, &context);
    const prt_test::Transfer t =
        prt_test::random_transfer(order, kVertices, kChannels, bits, order * 100 + bits);
    loaded = std::make_unique<prt_test::LoadedAsset>(
        context, prt_test::make_blob(prt_test::encode(t), kVertices));
    std::mt19937 rng(order);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (uint32_t i = 0; i < 3 * order * order; ++i) light.push_back(unit(rng));
    if (loaded->result == PRT_OK)
      prt_gl_sh_create(context, loaded->asset, headless_gl_get_proc, g_gl.get(), &shader);
  }
  ~GlBench() {
    prt_gl_sh_destroy(shader);
    loaded.reset();
    prt_context_destroy(context);
  }
  std::string error() const { return prt_context_last_message(context); }
};

void BM_GlShade(benchmark::State& state, uint32_t order, uint32_t bits, bool readback) {
  if (!g_gl.get()) {
    state.SkipWithError(g_gl.missing().c_str());
    return;
  }
  GlBench bench(order, bits);
  if (!bench.shader) {
    state.SkipWithError(("prt_gl_sh_create failed: " + bench.error()).c_str());
    return;
  }
  using FinishFn = void (*)(void);
  FinishFn finish;
  void* address = headless_gl_get_proc(nullptr, "glFinish");
  std::memcpy(&finish, &address, sizeof finish);
  std::vector<float> rgb(3 * size_t(kVertices));
  // The first dispatch compiles the shader in llvmpipe: keep it out of the timing.
  prt_gl_sh_shade(bench.shader, bench.light.data(), 0, kVertices);
  prt_gl_sh_read(bench.shader, 0, kVertices, rgb.data());
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    prt_gl_sh_shade(bench.shader, bench.light.data(), 0, kVertices);
    if (readback)
      prt_gl_sh_read(bench.shader, 0, kVertices, rgb.data());
    else
      finish();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(rgb.data());
  }
  const double vertices = double(kVertices) * double(state.iterations());
  state.counters["vertices/s"] = benchmark::Counter(vertices, benchmark::Counter::kIsRate);
  GlFigure figure;
  figure.order = order, figure.bits = bits, figure.readback = readback;
  figure.vertices_per_second = vertices / seconds;
  figure.bytes_per_vertex =
      double(kChannels * order * order * bits / 8) + 12.0 + (readback ? 12.0 : 0.0);
  // Google Benchmark calls this several times while it sizes the run: keep the last call.
  std::vector<GlFigure>& figures = g_figures.gl;
  if (!figures.empty() && figures.back().order == order && figures.back().bits == bits &&
      figures.back().readback == readback)
    figures.back() = figure;
  else
    figures.push_back(figure);
}

void register_gl() {
  for (uint32_t order : {2u, 4u, 6u, 8u})
    for (uint32_t bits : {8u, 16u})
      for (bool readback : {false, true}) {
        const std::string name = "BM_GlShade/order:" + std::to_string(order) +
                                 "/bits:" + std::to_string(bits) +
                                 (readback ? "/with_readback" : "/no_readback");
        benchmark::RegisterBenchmark(name.c_str(), BM_GlShade, order, bits, readback)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinTime(0.2);
      }
}

// llvmpipe's thread count: LP_NUM_THREADS, else one per core (capped at 2 for the triad we have).
void print_summary() {
  const Figures& f = g_figures;
  std::printf("\nsummary\n");
  std::printf("  memory bandwidth (triad): %.2f GB/s on 1 thread, %.2f GB/s on 2 threads\n",
              f.triad[1] * 1e-9, f.triad[2] * 1e-9);
  if (!g_gl.missing().empty()) {
    std::printf("  gl: %s\n", g_gl.missing().c_str());
    return;
  }
  const int threads = prt_bench::llvmpipe_threads();
  std::printf(
      "\n  gl shading on %s, %u vertices, RGB transfer; bytes moved = quantised transfer "
      "+ 12 B radiance written (+ 12 B read back); %% of the %d-thread triad\n",
      g_gl.renderer().c_str(), kVertices, threads);
  std::printf("  %5s %4s %-10s %10s %8s %8s\n", "order", "bits", "readback", "Mvert/s", "GB/s",
              "% triad");
  for (const GlFigure& g : f.gl) {
    const double bytes = g.vertices_per_second * g.bytes_per_vertex;
    const double share = f.triad[threads] > 0.0 ? 100.0 * bytes / f.triad[threads] : 0.0;
    std::printf("  %5u %4u %-10s %10.2f %8.2f %7.0f%%\n", g.order, g.bits,
                g.readback ? "included" : "excluded", g.vertices_per_second * 1e-6, bytes * 1e-9,
                share);
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_gl();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary();
  g_gl.destroy();
  return 0;
}
