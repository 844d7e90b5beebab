// SPDX-License-Identifier: MIT
// Technique `sh` benchmarks, all in one run so that their figures compare; printed, never
// asserted:
//  - the memory-bandwidth roofline: STREAM triad on 1 and 2 threads;
//  - CPU shading (prt_sh_shade) of the bunny's transfer, baked here (unshadowed: quick, and the
//    SHTR layout is the same for every kind), at orders 2/4/6/8 and 8/16 bits on cpu, simd with
//    SSE4.1, AVX2 and AVX-512 (its fixed-point kernel for 8 bits, the AVX2 one for 16), on 1
//    thread and on 2 threads over split vertex ranges: vertices/s
//    and the share of the triad (on as many threads) that the quantised data read amounts to.
//    The bunny's transfer (at most 14 MB) can stay in a large L3 cache, so one more case tiles it
//    to 1M vertices (order 6, 8 bits, 108 MB) to measure shading streamed from memory;
//  - bake throughput: a shadowed bake of the bunny (compute_sh_transfer, 1 thread) in rays/s as a
//    share of the best raw rtcOccluded1/4/8/16 on the same mesh with rays like the bake's (from
//    every vertex, cosine-distributed about its normal).
// Every rate is given by wall clock and by the CPU time of the threads doing the work: on a
// shared machine the second is not diluted by time spent descheduled (but two threads that did
// not really run at once add up to more than the machine can do together).
//
//   prt_bench_sh [--benchmark_filter=...] [google benchmark flags]
#include <benchmark/benchmark.h>
#include <prt/format/blob_writer.hpp>
#include <prt/prt.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/embree_scene.hpp"
#include "prt/baker/sampling.hpp"
#include "prt/baker/sh/sh_blob.hpp"
#include "prt/baker/sh/sh_transfer.hpp"
#include "support/bench_backends.hpp"
#include "support/bench_embree.hpp"
#include "support/bench_triad.hpp"

namespace {

using namespace prt::bake;
using prt_bench::Backend;
using prt_bench::kBackendCount;
using prt_bench::kBackends;

constexpr uint32_t kTiledVertices = 1u << 20;
constexpr uint32_t kBakeOrder = 6, kBakeRays = 64;

// --- Figures kept for the summary (the last measurement of each benchmark) -----------------

// One (order, bits, asset) row of the summary: a rate per backend and thread count.
struct ShadingRow {
  uint32_t order = 0, bits = 0, vertices = 0;
  bool tiled = false;
  double bytes_per_vertex = 0.0;
  // [backend][threads - 1][benchmark thread]: vertices/s (wall, own CPU time); their sum over
  // benchmark threads is the throughput.
  prt_bench::Rate per_thread[kBackendCount][2][2];
  prt_bench::Rate total(int backend, int threads) const {
    prt_bench::Rate sum;
    for (const prt_bench::Rate& r : per_thread[backend][threads - 1])
      sum.wall += r.wall, sum.cpu += r.cpu;
    return sum;
  }
};

struct Figures {
  prt_bench::Rate triad[3];         // bytes/s by thread count 1, 2
  std::vector<ShadingRow> shading;  // in registration order
  prt_bench::Rate bake_rays;        // rays/s
  prt_bench::Rate raw_robust;       // rtcOccluded16 with the bake's scene flags
  prt_bench::BestRaw raw_best;      // the fastest raw rtcOccludedN
  uint32_t mesh_vertices = 0;
  std::string mesh_name, bake_skipped;
  std::mutex mutex;
} g_figures;

// --- The bunny ------------------------------------------------------------------------------

std::filesystem::path bunny_path() {
  return std::filesystem::path(PRT_SHARED_DIR) / "assets/meshes/stanford-bunny.obj";
}

const Scene& mesh_scene() {
  static const Scene scene = [] {
    if (std::filesystem::exists(bunny_path())) {
      g_figures.mesh_name = "stanford-bunny.obj";
      return import_scene(bunny_path().string(), Context{});
    }
    g_figures.mesh_name = "built-in demo scene (bunny not found)";
    return make_demo_scene();
  }();
  return scene;
}

// Unshadowed transfer at the highest order shaded; lower orders are its first order^2
// coefficients (bands 0..order-1).
const ShTransfer& full_transfer() {
  static const ShTransfer transfer = [] {
    ShTransferSettings settings;
    settings.order = 8;
    settings.kind = ShTransferKind::Unshadowed;
    settings.rays = 64;
    return compute_sh_transfer(mesh_scene(), nullptr, settings, Context{});
  }();
  return transfer;
}

ShTransfer truncated_transfer(uint32_t order) {
  const ShTransfer& full = full_transfer();
  ShTransfer t;
  t.order = order;
  t.kind = full.kind;
  t.vertex_count = full.vertex_count;
  for (std::size_t v = 0; v < full.vertex_count; ++v)
    for (int c = 0; c < 3; ++c) {
      const float* row = full.vertex_channel(v, c);
      t.coefficients.insert(t.coefficients.end(), row, row + std::size_t(order) * order);
    }
  return t;
}

// The SHTR section's bytes with the vertex values repeated until `vertices` (header: vertex
// count at byte 4; then 8 bytes of offset/scale per coefficient; then the values; padded to 4).
std::vector<uint8_t> tile_shtr(const std::vector<uint8_t>& shtr, const QuantizedShTransfer& q,
                               uint32_t vertices) {
  const std::size_t params_end = PRT_BLOB_SHTR_HEADER_SIZE + 8 * 3 * q.coefficient_count();
  const std::size_t stride = 3 * q.coefficient_count() * (q.bits / 8);
  std::vector<uint8_t> tiled(shtr.begin(), shtr.begin() + params_end);
  prt_le_store_u32(tiled.data() + 4, vertices);
  for (uint32_t v = 0; v < vertices; ++v) {
    const auto from = shtr.begin() + params_end + (v % q.vertex_count) * stride;
    tiled.insert(tiled.end(), from, from + stride);
  }
  tiled.resize((tiled.size() + 3) / 4 * 4, 0);
  return tiled;
}

// A blob whose only payload is the given SHTR section (with the positions and triangle a
// container for `sh` needs; their contents do not matter to shading).
std::vector<uint8_t> shtr_only_blob(const std::vector<uint8_t>& shtr, uint32_t vertices) {
  prt::format::BlobWriter writer;
  prt::format::SectionOptions required;
  required.required = true;
  const std::vector<float> positions(std::size_t(vertices) * 3, 0.0f);
  const uint32_t triangle[3] = {0, 1, 2};
  writer.add_section(PRT_BLOB_TAG_VPOS, positions.data(), positions.size() * 4, vertices, required);
  writer.add_section(PRT_BLOB_TAG_TRIS, triangle, sizeof triangle, 1, required);
  writer.add_section(PRT_BLOB_TAG_SHTR, shtr.data(), shtr.size(), vertices, required);
  return writer.finish();
}

struct Blob {
  std::vector<uint8_t> bytes;
  uint32_t vertices = 0;
  double bytes_per_vertex = 0.0;  // quantised transfer read per shaded vertex
};

// Blobs by (order, bits, tiled), built once; defined before g_assets, whose assets borrow them, so
// that they are destroyed after it.
std::map<std::tuple<uint32_t, uint32_t, bool>, Blob> g_blobs;
std::mutex g_blobs_mutex;

// The bunny's blob at (order, bits), tiled to kTiledVertices when `tiled`.
const Blob& blob(uint32_t order, uint32_t bits, bool tiled) {
  const std::lock_guard<std::mutex> lock(g_blobs_mutex);
  Blob& b = g_blobs[{order, bits, tiled}];
  if (!b.bytes.empty()) return b;
  const QuantizedShTransfer q = quantize_sh_transfer(truncated_transfer(order), int(bits));
  if (tiled) {
    b.bytes = shtr_only_blob(tile_shtr(encode_shtr_section(q), q, kTiledVertices), kTiledVertices);
    b.vertices = kTiledVertices;
  } else {
    b.bytes = build_sh_blob(mesh_scene(), q, "");
    b.vertices = static_cast<uint32_t>(q.vertex_count);
    g_figures.mesh_vertices = b.vertices;
  }
  b.bytes_per_vertex = 3.0 * q.coefficient_count() * (bits / 8);
  return b;
}

// --- Backends ---------------------------------------------------------------------------------

// An asset per (backend, blob), made once and shared by the threads; declared after the blobs
// it borrows, so that it is destroyed before them.
class Assets {
 public:
  ~Assets() {
    for (auto& entry : assets_) prt_asset_destroy(entry.second);
  }
  // The asset, or null with `why` set when the backend cannot run here.
  prt_asset* get(int backend_index, const Blob& b, std::string* why) {
    prt_context* ctx = contexts_.usable(backend_index, why);
    if (!ctx) return nullptr;
    const std::lock_guard<std::mutex> lock(mutex_);
    prt_asset*& asset = assets_[{backend_index, &b}];
    if (!asset && prt_asset_load_memory_borrowed(ctx, b.bytes.data(), b.bytes.size(),
                                                 PRT_VALIDATE_FULL, &asset) != PRT_OK) {
      *why = std::string("load failed: ") + prt_context_last_message(ctx);
      return nullptr;
    }
    return asset;
  }

 private:
  prt_bench::BackendContexts contexts_;
  std::mutex mutex_;
  std::map<std::pair<int, const Blob*>, prt_asset*> assets_;
} g_assets;

// --- Benchmarks -----------------------------------------------------------------------------

void BM_StreamTriad(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  g_figures.triad[threads] = prt_bench::stream_triad(state, threads);
}
BENCHMARK(BM_StreamTriad)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Shades this benchmark thread's share of the vertices, once per iteration.
void shade(benchmark::State& state, int backend_index, std::size_t row_index) {
  ShadingRow& row = g_figures.shading[row_index];
  const Backend& backend = kBackends[backend_index];
  const uint32_t order = row.order;
  const Blob& b = blob(order, row.bits, row.tiled);
  std::string why;
  prt_asset* asset = g_assets.get(backend_index, b, &why);
  if (!asset) {
    state.SkipWithError(why.c_str());
    return;
  }
  const uint32_t threads = state.threads(), index = state.thread_index();
  const auto [first, count] = prt_bench::thread_share(state, b.vertices);
  std::vector<float> light(std::size_t(order) * order * 3), out(std::size_t(count) * 3);
  std::mt19937 rng(order);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (float& l : light) l = unit(rng);
  const auto [seconds, cpu_seconds] = prt_bench::time_shading(
      state,
      [&] { return prt_sh_shade(asset, backend.backend, light.data(), first, count, out.data()); },
      out.data());
  const double vertices = double(count) * double(state.iterations());
  state.SetItemsProcessed(static_cast<int64_t>(vertices));
  state.SetBytesProcessed(static_cast<int64_t>(vertices * b.bytes_per_vertex));
  const std::lock_guard<std::mutex> lock(g_figures.mutex);
  row.vertices = b.vertices;
  row.bytes_per_vertex = b.bytes_per_vertex;
  if (seconds > 0.0 && cpu_seconds > 0.0)
    row.per_thread[backend_index][threads - 1][index] = {vertices / seconds,
                                                         vertices / cpu_seconds};
}

void register_shading() {
  for (int tiled = 0; tiled < 2; ++tiled)
    for (const uint32_t order : {2u, 4u, 6u, 8u})
      for (const uint32_t bits : {8u, 16u}) {
        if (tiled && (order != 6 || bits != 8)) continue;
        const std::size_t row = g_figures.shading.size();
        ShadingRow figure;
        figure.order = order, figure.bits = bits, figure.tiled = tiled;
        g_figures.shading.push_back(figure);
        for (int backend = 0; backend < kBackendCount; ++backend)
          for (const int threads : {1, 2}) {
            const std::string name = std::string("Shade/") + kBackends[backend].name +
                                     "/order:" + std::to_string(order) +
                                     "/bits:" + std::to_string(bits) + (tiled ? "/tiled" : "");
            benchmark::RegisterBenchmark(
                name.c_str(), [=](benchmark::State& state) { shade(state, backend, row); })
                ->Threads(threads)
                ->UseRealTime()
                ->MinTime(0.1)
                ->Unit(benchmark::kMicrosecond);
          }
      }
}

// Raw rtcOccludedN, N = state.range(0): the bake is compared with the best of them.
void BM_RawEmbreeOccluded(benchmark::State& state) {
  static const prt_bench::RawEmbree raw(mesh_scene());
  static const prt_bench::VertexRays rays = prt_bench::cosine_vertex_rays(mesh_scene(), kBakeRays);
  const int width = static_cast<int>(state.range(0));
  g_figures.raw_best.offer(prt_bench::raw_occluded_rate_width(state, raw, rays, width), width);
}
[[maybe_unused]] const benchmark::internal::Benchmark* const kRawEmbreeOccluded =
    prt_bench::register_raw_occluded(BM_RawEmbreeOccluded);

// rtcOccluded16 on the same rays through a scene with the bake's flags.
void BM_RawEmbreeOccludedRobust(benchmark::State& state) {
  static const prt_bench::RawEmbree raw(mesh_scene(), RTC_SCENE_FLAG_ROBUST);
  static const prt_bench::VertexRays rays = prt_bench::cosine_vertex_rays(mesh_scene(), kBakeRays);
  g_figures.raw_robust = prt_bench::raw_occluded_rate_width(state, raw, rays, 16);
}
[[maybe_unused]] const benchmark::internal::Benchmark* const kRawEmbreeOccludedRobust =
    prt_bench::register_raw_occluded_robust(BM_RawEmbreeOccludedRobust);

void BM_BakeShadowed(benchmark::State& state) {
  if (!std::filesystem::exists(bunny_path())) {
    g_figures.bake_skipped = "skipped: " + bunny_path().string() + " not found";
    state.SkipWithError(g_figures.bake_skipped.c_str());
    return;
  }
  const Scene& scene = mesh_scene();
  const EmbreeScene embree(scene, Context{});
  ShTransferSettings settings;
  settings.order = kBakeOrder;
  settings.kind = ShTransferKind::Shadowed;
  settings.rays = kBakeRays;
  Context one_thread;
  one_thread.threads = 1;  // compared with single-threaded raw Embree
  uint64_t rays = 0;
  double seconds = 0.0, cpu_seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = prt_bench::process_cpu_seconds();  // the bake may use a worker
    const ShTransfer transfer = compute_sh_transfer(scene, &embree, settings, one_thread);
    cpu_seconds += prt_bench::process_cpu_seconds() - cpu_start;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rays += transfer.rays_traced;
    benchmark::DoNotOptimize(transfer.coefficients.data());
  }
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
  g_figures.bake_rays = {double(rays) / seconds, double(rays) / cpu_seconds};
}
BENCHMARK(BM_BakeShadowed)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

// One table of shading rates, by CPU time or by wall clock: Mvert/s and the share of the triad
// (measured the same way, on as many threads) that the quantised data read amounts to.
void print_shading(const Figures& f, bool by_cpu) {
  std::printf("\n  shading by %s: Mvert/s and %% of the triad on as many threads\n",
              by_cpu ? "CPU time of each thread" : "wall clock");
  std::printf("  order bits B/vert |");
  for (const Backend& backend : kBackends) std::printf(" %-25s|", backend.name);
  std::printf("\n  %17s |", "");
  for (int b = 0; b < kBackendCount; ++b) std::printf(" %12s %12s|", "1 thread", "2 threads");
  std::printf("\n");
  for (const ShadingRow& row : f.shading) {
    if (row.vertices == 0) continue;  // filtered out
    std::printf("  %5u %4u %6.0f |", row.order, row.bits, row.bytes_per_vertex);
    for (int b = 0; b < kBackendCount; ++b)
      for (int threads = 1; threads <= 2; ++threads) {
        const prt_bench::Rate rate = row.total(b, threads);
        const double vertices = by_cpu ? rate.cpu : rate.wall;
        const double triad = by_cpu ? f.triad[threads].cpu : f.triad[threads].wall;
        if (vertices <= 0.0 || triad <= 0.0) {
          std::printf(" %12s", "-");
        } else {
          std::printf(" %7.1f %3.0f%%", vertices * 1e-6,
                      100.0 * vertices * row.bytes_per_vertex / triad);
        }
        if (threads == 2) std::printf("|");
      }
    if (row.tiled) std::printf("  %u vertices (bunny tiled)", row.vertices);
    std::printf("\n");
  }
}

void print_summary() {
  const Figures& f = g_figures;
  std::printf("\nsummary (mesh: %s, %u vertices)\n", f.mesh_name.c_str(), f.mesh_vertices);
  std::printf(
      "  memory bandwidth (triad), by CPU time: %.2f GB/s on 1 thread, %.2f GB/s on 2; "
      "by wall clock: %.2f, %.2f\n",
      f.triad[1].cpu * 1e-9, f.triad[2].cpu * 1e-9, f.triad[1].wall * 1e-9, f.triad[2].wall * 1e-9);
  print_shading(f, /*by_cpu=*/true);
  print_shading(f, /*by_cpu=*/false);
  std::printf("\n");
  if (!f.bake_skipped.empty()) {
    std::printf("  bake: %s\n", f.bake_skipped.c_str());
  } else if (f.bake_rays.cpu > 0.0 && f.raw_best.rate.cpu > 0.0) {
    std::printf(
        "  bake (shadowed, order %u, %u rays/vertex, 1 thread) vs the best raw call, "
        "rtcOccluded%d of 1/4/8/16 (same mesh, rays from its vertices about their normals):\n",
        kBakeOrder, kBakeRays, f.raw_best.width);
    std::printf("    by CPU time:   %.2f vs %.2f Mrays/s = %.0f %%\n", f.bake_rays.cpu * 1e-6,
                f.raw_best.rate.cpu * 1e-6, 100.0 * f.bake_rays.cpu / f.raw_best.rate.cpu);
    std::printf("    by wall clock: %.2f vs %.2f Mrays/s = %.0f %%\n", f.bake_rays.wall * 1e-6,
                f.raw_best.rate.wall * 1e-6, 100.0 * f.bake_rays.wall / f.raw_best.rate.wall);
    prt_bench::print_robust_share(f.bake_rays, f.raw_robust);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_shading();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary();
  return 0;
}
