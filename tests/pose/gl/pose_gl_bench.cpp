// SPDX-License-Identifier: MIT
// Shading throughput of technique `pose` per backend, printed, never asserted: prt_pose_shade on
// the scalar reference and SIMD, and prt_gl_pose_shade on a headless EGL context (shade +
// glFinish, and shade + prt_gl_pose_read of every vertex), for both models on a random section
// of 35,947 vertices (the Stanford bunny's count), order 6, 16-bit basis, q 22, 20 joints. Each
// call includes its per-frame CPU work (features, coefficients, folding, skeleton). On Mesa
// llvmpipe the "GPU" is the CPU (LP_NUM_THREADS threads, default: all cores).
//
//   prt_bench_pose_gl [--benchmark_filter=...] [google benchmark flags]
#include <benchmark/benchmark.h>
#include <prt/prt.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "pose/pose_blob.hpp"
#include "support/bench_gl.hpp"

namespace {

constexpr uint32_t kVertices = 35947, kOrder = 6, kBasisDims = 22, kJoints = 20;

struct Figure {
  std::string what;
  double vertices_per_second = 0.0;
};
std::vector<Figure> g_figures;

prt_bench::SharedGl g_gl;

// One asset in its own context, a pose and a light.
struct Bench {
  prt_context* context = nullptr;
  prt_test::PoseSection section;
  std::unique_ptr<prt_test::LoadedAsset> loaded;
  std::vector<float> rotations, light;
  prt_pose_input pose{};
  prt_pose_light pose_light{};
  explicit Bench(uint32_t model)
      : section(prt_test::random_section(kOrder, kVertices, kJoints, 8, kBasisDims, 16, model,
                                         7 + model)) {
    prt_context_create(nullptr, &context);
    loaded = std::make_unique<prt_test::LoadedAsset>(context, prt_test::pose_blob(section));
    rotations = prt_test::random_rotations(kJoints, 11);
    pose = prt_test::pose_of(rotations);
    std::mt19937 rng(model);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (uint32_t i = 0; i < 3 * kOrder * kOrder; ++i) light.push_back(unit(rng));
    pose_light.struct_size = sizeof pose_light;
    pose_light.light_rgb = light.data();
  }
  ~Bench() {
    loaded.reset();
    prt_context_destroy(context);
  }
  bool ok() const { return loaded->result == PRT_OK; }
};

void record(const std::string& what, double vertices, double seconds) {
  // Google Benchmark calls a benchmark several times while it sizes the run: keep the last.
  if (!g_figures.empty() && g_figures.back().what == what)
    g_figures.back().vertices_per_second = vertices / seconds;
  else
    g_figures.push_back({what, vertices / seconds});
}

void BM_CpuShade(benchmark::State& state, uint32_t model, prt_backend backend) {
  Bench bench(model);
  std::vector<float> rgb(3 * size_t(kVertices));
  if (!bench.ok() || prt_pose_shade(bench.loaded->asset, backend, &bench.pose, &bench.pose_light, 0,
                                    kVertices, rgb.data()) != PRT_OK) {
    state.SkipWithError("prt_pose_shade failed (or the backend is not usable here)");
    return;
  }
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    prt_pose_shade(bench.loaded->asset, backend, &bench.pose, &bench.pose_light, 0, kVertices,
                   rgb.data());
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(rgb.data());
  }
  const double vertices = double(kVertices) * double(state.iterations());
  state.counters["vertices/s"] = benchmark::Counter(vertices, benchmark::Counter::kIsRate);
  record(
      std::string(backend == PRT_BACKEND_CPU ? "cpu" : "simd") + ", model " + std::to_string(model),
      vertices, seconds);
}

void BM_GlShade(benchmark::State& state, uint32_t model, bool readback) {
  if (!g_gl.get()) {
    state.SkipWithError(g_gl.missing().c_str());
    return;
  }
  Bench bench(model);
  prt_gl_pose_shader* shader = nullptr;
  if (!bench.ok() || prt_gl_pose_create(bench.context, bench.loaded->asset, headless_gl_get_proc,
                                        g_gl.get(), &shader) != PRT_OK) {
    state.SkipWithError(
        ("prt_gl_pose_create failed: " + std::string(prt_context_last_message(bench.context)))
            .c_str());
    return;
  }
  using FinishFn = void (*)(void);
  FinishFn finish;
  void* address = headless_gl_get_proc(nullptr, "glFinish");
  std::memcpy(&finish, &address, sizeof finish);
  std::vector<float> rgb(3 * size_t(kVertices));
  // The first dispatch compiles the shader in llvmpipe: keep it out of the timing.
  prt_gl_pose_shade(shader, &bench.pose, &bench.pose_light, 0, kVertices);
  prt_gl_pose_read(shader, 0, kVertices, rgb.data());
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    prt_gl_pose_shade(shader, &bench.pose, &bench.pose_light, 0, kVertices);
    if (readback)
      prt_gl_pose_read(shader, 0, kVertices, rgb.data());
    else
      finish();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(rgb.data());
  }
  prt_gl_pose_destroy(shader);
  const double vertices = double(kVertices) * double(state.iterations());
  state.counters["vertices/s"] = benchmark::Counter(vertices, benchmark::Counter::kIsRate);
  record("gl, model " + std::to_string(model) + (readback ? ", with readback" : ", no readback"),
         vertices, seconds);
}

void register_all() {
  for (uint32_t model : {0u, 1u}) {
    const std::string m = "/model:" + std::to_string(model);
    benchmark::RegisterBenchmark(("BM_CpuShade" + m).c_str(), BM_CpuShade, model, PRT_BACKEND_CPU)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MinTime(0.2);
    benchmark::RegisterBenchmark(("BM_SimdShade" + m).c_str(), BM_CpuShade, model, PRT_BACKEND_SIMD)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MinTime(0.2);
    for (bool readback : {false, true})
      benchmark::RegisterBenchmark(
          ("BM_GlShade" + m + (readback ? "/with_readback" : "/no_readback")).c_str(), BM_GlShade,
          model, readback)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->MinTime(0.2);
  }
}

void print_summary() {
  std::printf("\nsummary: pose shading, %u vertices, order %u, q %u, 16-bit, %u joints%s%s\n",
              kVertices, kOrder, kBasisDims, kJoints, g_gl.renderer().empty() ? "" : "; gl on ",
              g_gl.renderer().c_str());
  if (!g_gl.missing().empty()) std::printf("  gl: %s\n", g_gl.missing().c_str());
  std::printf("  %-32s %10s\n", "backend", "Mvert/s");
  for (const Figure& f : g_figures)
    std::printf("  %-32s %10.2f\n", f.what.c_str(), f.vertices_per_second * 1e-6);
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary();
  g_gl.destroy();
  return 0;
}
