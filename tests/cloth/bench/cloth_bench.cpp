// SPDX-License-Identifier: MIT
// prt_bench_cloth: frames per second of cloth shading (prt_cloth_shade_workers) at 640x480, full
// screen, on a pool of one thread per core, for linen_plain and polyester_satin_charmeuse over
// synthetic tables of a realistic size (N_xi 32, 10 levels, 16x16 views, rank 16) under a
// fitted-sky-like light (ten lobes of sharpness 5..100 over the sphere and a sun of 5000):
//   flat:   a flat patch seen in perspective (one frame for every pixel, the view per pixel);
//   draped: a procedural wavy surface (every pixel's frame differs).
// The work cuts are added one at a time, from the straight method (every lobe, every copy of a
// tangent, each tangent's terms its own, nothing kept across pixels): culling hidden and weak
// lobes, deduplicated tangents (a tangent of multiplicity m shaded once), per-lobe terms shared
// across tangents, and the frame cache (pixels that share a frame); then, as a last step, the
// coarsest quadrature the trade finds accurate enough for linen (1 theta panel, 2 phi nodes: a
// setting, not a saving). The summary gives each step's
// speed-up over the straight method and over the step before, of the same backend in the same
// run. The scalar reference has only the culling switch (it always shades distinct tangents); it
// shades every 16th row and is extrapolated (a full frame takes it tens of seconds). Printed,
// never asserted.
// Frames per second are given by the wall clock and, since the machine may be shared, by the
// process's CPU time (threads x frame / CPU seconds: what the pool would give on cores of its
// own); the speed-ups are by CPU time.
#include <benchmark/benchmark.h>
#include <prt/prt_cloth_asset.h>
#include <prt/prt_workers.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cloth/simd/cloth_synthetic.hpp"
#include "support/bench_triad.hpp"  // process_cpu_seconds

namespace {

constexpr std::uint32_t kWidth = 640, kHeight = 480;

struct Screen {
  std::vector<float> normals, warps, views;
  std::uint32_t rows = 0;
  prt_cloth_pixels pixels() const {
    prt_cloth_pixels p{};
    p.struct_size = sizeof p;
    p.normals = normals.data();
    p.warps = warps.data();
    p.views = views.data();
    return p;
  }
};

void normalize(float v[3]) {
  const float l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int i = 0; i < 3; ++i) v[i] /= l;
}

// A camera at (0, -3, 2.2) looking down at the plane z = 0 (vertical field of view 50 degrees,
// pitched 40 degrees down: every pixel sees the plane). Rows `row_step` apart. The wavy surface
// is z = a sin(3 x) cos(2 y) + a/2 sin(5 y + x): its normal and warp (the x tangent) at the point
// where the pixel's ray meets z = 0; the view from there to the eye.
Screen screen(bool draped, std::uint32_t row_step) {
  const float eye[3] = {0.0f, -3.0f, 2.2f};
  const float pitch = 40.0f * 3.14159265f / 180.0f, half = std::tan(25.0f * 3.14159265f / 180.0f);
  const float fwd[3] = {0.0f, std::cos(pitch), -std::sin(pitch)};
  const float up[3] = {0.0f, std::sin(pitch), std::cos(pitch)};
  const float right[3] = {1.0f, 0.0f, 0.0f};
  const float a = draped ? 0.12f : 0.0f;
  Screen s;
  for (std::uint32_t y = 0; y < kHeight; y += row_step) {
    ++s.rows;
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const float u = (2.0f * (float(x) + 0.5f) / kWidth - 1.0f) * half * kWidth / kHeight;
      const float v = (1.0f - 2.0f * (float(y) + 0.5f) / kHeight) * half;
      float d[3];
      for (int i = 0; i < 3; ++i) d[i] = fwd[i] + u * right[i] + v * up[i];
      normalize(d);
      const float t = -eye[2] / d[2];
      const float px = eye[0] + t * d[0], py = eye[1] + t * d[1];
      const float hx = a * 3.0f * std::cos(3.0f * px) * std::cos(2.0f * py) +
                       a * 0.5f * std::cos(5.0f * py + px);
      const float hy = -a * 2.0f * std::sin(3.0f * px) * std::sin(2.0f * py) +
                       a * 2.5f * std::cos(5.0f * py + px);
      float n[3] = {-hx, -hy, 1.0f}, w[3] = {1.0f, 0.0f, hx}, view[3] = {-d[0], -d[1], -d[2]};
      normalize(n);
      normalize(w);
      s.normals.insert(s.normals.end(), n, n + 3);
      s.warps.insert(s.warps.end(), w, w + 3);
      s.views.insert(s.views.end(), view, view + 3);
    }
  }
  return s;
}

struct Step {
  const char* name;
  std::uint32_t flags;
  bool simd_only;
  std::uint32_t theta_segments = 0, phi_nodes = 0;  // 0: the defaults
};

constexpr std::uint32_t kNoSaving =
    PRT_CLOTH_TANGENT_COPIES | PRT_CLOTH_NO_LOBE_SHARING | PRT_CLOTH_NO_FRAME_CACHE;
const Step kSteps[] = {
    {"straight", PRT_CLOTH_KEEP_HIDDEN_LOBES | PRT_CLOTH_KEEP_WEAK_LOBES | kNoSaving, false},
    {"+culling", kNoSaving, false},
    {"+dedup", PRT_CLOTH_NO_LOBE_SHARING | PRT_CLOTH_NO_FRAME_CACHE, true},
    {"+sharing", PRT_CLOTH_NO_FRAME_CACHE, true},
    {"+frame_cache", 0u, true},
    // Not a work cut but a setting: the coarsest quadrature whose accuracy cost the trade
    // measures (docs/cloth/trade.md), for what the integrals' node count is worth.
    {"+coarse_quad", 0u, true, 1u, 2u},
};
constexpr int kStepCount = int(sizeof kSteps / sizeof kSteps[0]);
const char* const kFabrics[] = {"linen_plain", "polyester_satin_charmeuse"};
const prt_backend kBackends[] = {PRT_BACKEND_CPU, PRT_BACKEND_SIMD};

// What every case shares: the asset, the pool, the light and the screens.
struct Bench {
  prt::ContextPtr context = prt::create_context().handle;
  std::vector<std::uint8_t> blob;
  prt_asset* asset = nullptr;
  prt_workers* workers = nullptr;
  std::uint32_t threads = std::max(1u, std::thread::hardware_concurrency());
  prt_test::SyntheticGrid grid;
  std::vector<prt_cloth_lobe> lobes = prt_test::sky_lobes(10, 5.0f, 100.0f, true, 3);
  Screen screens[2][2];  // [draped][sparse]
  // frames per second by wall clock and by CPU time, per case; 0 where it did not run
  double fps[2][2][2][kStepCount][2] = {};  // [draped][fabric][backend][step][cpu]

  Bench() {
    grid.xi_size = 32;
    grid.levels = 10;
    grid.view_theta = grid.view_phi = 16;
    grid.rank = grid.cone_rank = 16;
    grid.bits = 16;
    blob = prt_test::synthetic_cloth_blob(grid, {kFabrics[0], kFabrics[1]}, 1);
    if (prt_asset_load_memory(context.get(), blob.data(), blob.size(), PRT_VALIDATE_FULL, &asset) !=
        PRT_OK) {
      std::fprintf(stderr, "load: %s\n", prt_context_last_message(context.get()));
      std::exit(1);
    }
    prt_workers_desc desc = prt::sized<prt_workers_desc>();
    desc.thread_count = threads;
    if (prt_workers_create(context.get(), &desc, &workers) != PRT_OK) std::exit(1);
    for (int d = 0; d < 2; ++d)
      for (int sparse = 0; sparse < 2; ++sparse)
        screens[d][sparse] = screen(d != 0, sparse ? 16 : 1);
  }
  ~Bench() {
    prt_workers_destroy(workers);
    prt_asset_destroy(asset);
  }
};

Bench* g_bench = nullptr;

// One frame per iteration; the scalar reference on every 16th row, extrapolated.
void shade_case(benchmark::State& state, int draped, int fabric, int backend, int step) {
  Bench& b = *g_bench;
  const Screen& s = b.screens[draped][kBackends[backend] == PRT_BACKEND_CPU ? 1 : 0];
  const double share = double(s.rows) / kHeight;
  prt_cloth_settings settings = prt::sized<prt_cloth_settings>();
  settings.flags = kSteps[step].flags;
  settings.theta_segments = kSteps[step].theta_segments;
  settings.phi_nodes = kSteps[step].phi_nodes;
  prt_cloth_light light = prt::sized<prt_cloth_light>();
  light.lobe_count = std::uint32_t(b.lobes.size());
  light.lobes = b.lobes.data();
  const prt_cloth_pixels pixels = s.pixels();
  const std::uint32_t count = std::uint32_t(s.normals.size() / 3);
  std::vector<float> out(3 * std::size_t(count));
  double wall = 0.0, cpu = 0.0;
  for (auto _ : state) {
    const double c0 = prt_bench::process_cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    const prt_result r =
        prt_cloth_shade_workers(b.workers, b.asset, kBackends[backend], std::uint32_t(fabric),
                                nullptr, &light, &settings, &pixels, 0, count, out.data());
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    cpu += prt_bench::process_cpu_seconds() - c0;
    if (r != PRT_OK) {
      state.SkipWithError(prt_result_string(r));
      return;
    }
    benchmark::DoNotOptimize(out.data());
  }
  const double frames = share * double(state.iterations());
  state.counters["fps"] = frames / wall;
  state.counters["fps_cpu"] = b.threads * frames / cpu;
  b.fps[draped][fabric][backend][step][0] = frames / wall;
  b.fps[draped][fabric][backend][step][1] = b.threads * frames / cpu;
}

void register_cases(bool simd) {
  for (int d = 0; d < 2; ++d)
    for (int f = 0; f < 2; ++f)
      for (int be = 0; be < 2; ++be)
        for (int st = 0; st < kStepCount; ++st) {
          const bool cpu = kBackends[be] == PRT_BACKEND_CPU;
          if ((cpu && kSteps[st].simd_only) || (!cpu && !simd)) continue;
          const std::string name = std::string("Shade/") + (d ? "draped/" : "flat/") + kFabrics[f] +
                                   "/" + prt_backend_name(kBackends[be]) + "/" + kSteps[st].name;
          benchmark::RegisterBenchmark(
              name.c_str(),
              [d, f, be, st](benchmark::State& state) { shade_case(state, d, f, be, st); })
              ->Iterations(cpu ? 1 : 2)
              ->UseRealTime()
              ->Unit(benchmark::kMillisecond);
        }
}

void print_summary() {
  const Bench& b = *g_bench;
  if (std::all_of(&b.fps[0][0][0][0][0], &b.fps[0][0][0][0][0] + sizeof b.fps / sizeof(double),
                  [](double x) { return x == 0.0; }))
    return;  // nothing ran (listed or filtered out)
  std::printf(
      "\nsummary: cloth shading at %ux%u on %u threads, K = %zu lobes, tables N_xi %u L %u "
      "views %ux%u rank %u (scalar: every 16th row, extrapolated)\n",
      kWidth, kHeight, b.threads, b.lobes.size(), b.grid.xi_size, b.grid.levels, b.grid.view_theta,
      b.grid.view_phi, b.grid.rank);
  std::printf("  %-7s %-26s %-7s %-13s %9s %9s %12s %8s\n", "scene", "fabric", "backend", "step",
              "fps wall", "fps cpu", "vs straight", "vs last");
  for (int d = 0; d < 2; ++d)
    for (int f = 0; f < 2; ++f)
      for (int be = 0; be < 2; ++be) {
        double first = 0.0, last = 0.0;
        for (int st = 0; st < kStepCount; ++st) {
          const double wall = b.fps[d][f][be][st][0], cpu = b.fps[d][f][be][st][1];
          if (cpu <= 0.0) continue;
          if (first == 0.0) first = last = cpu;
          std::printf("  %-7s %-26s %-7s %-13s %9.3f %9.3f %12.2f %8.2f\n", d ? "draped" : "flat",
                      kFabrics[f], prt_backend_name(kBackends[be]), kSteps[st].name, wall, cpu,
                      cpu / first, cpu / last);
          last = cpu;
        }
      }
  std::printf(
      "  (the issue's target: >= 4 fps for linen at 640x480 on 2 cores on the SIMD path)\n");
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  Bench bench;
  g_bench = &bench;
  register_cases(prt_context_backend(bench.context.get()) == PRT_BACKEND_SIMD);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary();
  return 0;
}
