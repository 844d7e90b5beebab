// SPDX-License-Identifier: MIT
// Technique `wavelet` relight benchmarks on the CPU, all in one run so that their figures
// compare; printed, never asserted:
//  - the memory-bandwidth roofline: STREAM triad on 1 and 2 threads (bench_triad.hpp);
//  - relight: prt_wavelet_shade of a bunny-sized transfer (35,947 vertices, N = 64 cube, rows
//    shaped like a `--keep 1000` bake: wavelet_bench_asset.hpp) on cpu, simd with SSE4.1 and simd
//    with AVX2, on 1 thread and on 2 threads over split vertex ranges: vertices/s, frames/s of
//    the bunny next to the implementation report's 3 frames/s for 40,000 vertices, and the bytes
//    read per second as a share of the triad on as many threads — the rows streamed (pairs,
//    block counts, row start, vertex scale) alone, and with the light gathers (16 B per pair,
//    mostly cache hits) added;
//  - bake throughput: compute_wavelet_transfer of the Stanford bunny (every 16th vertex, cube
//    N = 32, one ray per texel, 1 thread) in rays/s as a share of the best raw rtcOccluded1/4/8/16
//    on the same mesh (bench_embree.hpp; skipped without the shared assets);
//  - relight at M: the same shading on the best SIMD backend, 1 thread, under the environment
//    below cut to M light coefficients: blocks of zero light are skipped, so fewer coefficients
//    shade faster; ms per frame, the ratio to M = all measured in the same run, frames/s and,
//    at M = 300, the ratio to issue 12's marks (N = 64, K = 1000: 70 frames/s; N = 32, K = 307
//    rows: 200 frames/s). With AVX2 the load repacks the rows into 8-vertex tiles (dense coarse
//    corners, fine pairs by group of zero light skipped); the load time and bytes that adds are
//    printed against a load without it (an SSE4.1-limited context) in the same run;
//  - the per-frame light update: resample a 1k lat-long map (spiaggia_di_mondello_1k.hdr, or a
//    synthetic sky with a sun when the shared assets are absent) under a rotation that changes
//    every frame, Haar-transform, keep M coefficients, prepare for the asset; ms per step, by
//    prt_wavelet_resample per frame (the old path), by a prepared prt_wavelet_source on the
//    best SIMD instruction set (the same result) and by one with PRT_WAVELET_SOURCE_REDUCE_2X2
//    (not the same result), with the ratio to the old path in this run.
// Rates are given by wall clock and by the CPU time of the threads doing the work (this machine
// may be shared; see sh_bench.cpp).
//
//   prt_bench_wavelet [--benchmark_filter=...] [google benchmark flags]
#include <benchmark/benchmark.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "prt/baker/context.hpp"
#include "prt/baker/wavelet/wavelet_transfer.hpp"
#include "prt/io/envmap.hpp"
#include "support/bench_backends.hpp"
#include "support/bench_embree.hpp"
#include "support/bench_triad.hpp"
#include "wavelet/wavelet_bench_asset.hpp"

namespace {

// --- Figures kept for the summary (the last measurement of each benchmark) -----------------

using prt_bench::Backend;
using prt_bench::kBackendCount;
using prt_bench::kBackends;

struct LightFigure {
  uint32_t m = 0;
  int path = 0;  // 0 prt_wavelet_resample per frame, 1 prt_wavelet_source, 2 the same reduced
  double resample = 0, transform = 0, select = 0, prepare = 0;  // seconds per frame
};

struct Figures {
  prt_bench::Rate triad[3];  // bytes/s by thread count 1, 2
  // [backend][threads - 1][benchmark thread]: vertices/s (wall, own CPU time).
  prt_bench::Rate shading[kBackendCount][2][2];
  prt_bench::WaveletTraffic traffic;
  std::vector<LightFigure> light;
  struct RelightAtM {
    uint32_t size, m;  // face size N, M (0 = all)
    double seconds;    // per frame
  };
  std::vector<RelightAtM> relight_at_m;
  struct LoadCost {
    uint32_t size = 0;
    double tiled = 0, plain = 0;              // seconds per quick-validated load
    double tiled_bytes = 0, plain_bytes = 0;  // bytes the loaded asset holds from the allocator
    double section_bytes = 0;
  };
  std::vector<LoadCost> load_cost;
  std::string relight_at_m_backend;
  std::string env_name;
  prt_bench::Rate bake_rays;    // rays/s
  prt_bench::Rate raw_robust;   // rtcOccluded16 with the bake's scene flags
  prt_bench::BestRaw raw_best;  // the fastest raw rtcOccludedN
  std::string bake_skipped;
  std::mutex mutex;
} g_figures;

// --- Bake throughput against raw Embree -------------------------------------------------------

constexpr uint32_t kBakeSize = 32, kBakeStride = 16;

std::filesystem::path bunny_path() {
  return std::filesystem::path(PRT_SHARED_DIR) / "assets/meshes/stanford-bunny.obj";
}

const prt::bake::Scene& bunny() {
  static const prt::bake::Scene scene =
      prt::bake::import_scene(bunny_path().string(), prt::bake::Context{});
  return scene;
}

bool skip_without_bunny(benchmark::State& state) {
  if (std::filesystem::exists(bunny_path())) return false;
  g_figures.bake_skipped = "skipped: " + bunny_path().string() + " not found";
  state.SkipWithError(g_figures.bake_skipped.c_str());
  return true;
}

// Raw rtcOccludedN, N = state.range(0): the bake is compared with the best of them.
void BM_RawEmbreeOccluded(benchmark::State& state) {
  if (skip_without_bunny(state)) return;
  static const prt_bench::RawEmbree raw(bunny());
  static const prt_bench::VertexRays rays = prt_bench::cosine_vertex_rays(bunny(), 64);
  const int width = static_cast<int>(state.range(0));
  g_figures.raw_best.offer(prt_bench::raw_occluded_rate_width(state, raw, rays, width), width);
}
[[maybe_unused]] const benchmark::internal::Benchmark* const kRawEmbreeOccluded =
    prt_bench::register_raw_occluded(BM_RawEmbreeOccluded);

// rtcOccluded16 on the same rays through a scene with the bake's flags.
void BM_RawEmbreeOccludedRobust(benchmark::State& state) {
  if (skip_without_bunny(state)) return;
  static const prt_bench::RawEmbree raw(bunny(), RTC_SCENE_FLAG_ROBUST);
  static const prt_bench::VertexRays rays = prt_bench::cosine_vertex_rays(bunny(), 64);
  g_figures.raw_robust = prt_bench::raw_occluded_rate_width(state, raw, rays, 16);
}
[[maybe_unused]] const benchmark::internal::Benchmark* const kRawEmbreeOccludedRobust =
    prt_bench::register_raw_occluded_robust(BM_RawEmbreeOccludedRobust);

void BM_BakeWavelet(benchmark::State& state) {
  if (skip_without_bunny(state)) return;
  const prt::bake::EmbreeScene embree(bunny(), prt::bake::Context{});
  prt::bake::WaveletTransferSettings settings;
  settings.size = kBakeSize;
  settings.keep = prt::bake::default_wavelet_keep(PRT_WAVELET_PARAM_CUBE, kBakeSize);
  settings.vertex_stride = kBakeStride;
  prt::bake::Context one_thread;
  one_thread.threads = 1;  // compared with single-threaded raw Embree
  uint64_t rays = 0;
  double seconds = 0.0, cpu_seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = prt_bench::process_cpu_seconds();
    const prt::bake::WaveletTransfer transfer =
        prt::bake::compute_wavelet_transfer(bunny(), &embree, settings, one_thread);
    cpu_seconds += prt_bench::process_cpu_seconds() - cpu_start;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rays += transfer.rays_traced;
    benchmark::DoNotOptimize(transfer.value.data());
  }
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
  g_figures.bake_rays = {double(rays) / seconds, double(rays) / cpu_seconds};
}
BENCHMARK(BM_BakeWavelet)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

void print_bake() {
  const Figures& f = g_figures;
  if (!f.bake_skipped.empty()) {
    std::printf("\n  bake: %s\n", f.bake_skipped.c_str());
    return;
  }
  if (!(f.bake_rays.cpu > 0.0 && f.raw_best.rate.cpu > 0.0)) return;  // filtered out
  std::printf(
      "\n  bake (cube %u, 1 ray per texel above the horizon, every %u-th bunny vertex, 1 thread) "
      "vs the best raw call, rtcOccluded%d of 1/4/8/16 (same mesh, rays from its vertices about "
      "their normals):\n",
      kBakeSize, kBakeStride, f.raw_best.width);
  std::printf("    by CPU time:   %.2f vs %.2f Mrays/s = %.0f %%\n", f.bake_rays.cpu * 1e-6,
              f.raw_best.rate.cpu * 1e-6, 100.0 * f.bake_rays.cpu / f.raw_best.rate.cpu);
  std::printf("    by wall clock: %.2f vs %.2f Mrays/s = %.0f %%\n", f.bake_rays.wall * 1e-6,
              f.raw_best.rate.wall * 1e-6, 100.0 * f.bake_rays.wall / f.raw_best.rate.wall);
  prt_bench::print_robust_share(f.bake_rays, f.raw_robust);
}

prt_bench::Rate shading_total(int backend, int threads) {
  prt_bench::Rate sum;
  for (const prt_bench::Rate& r : g_figures.shading[backend][threads - 1])
    sum.wall += r.wall, sum.cpu += r.cpu;
  return sum;
}

// --- The asset ------------------------------------------------------------------------------

// The transfer, its blob, and per backend an asset borrowing the blob; made once.
class Assets {
 public:
  ~Assets() {
    for (prt_asset* a : assets_) prt_asset_destroy(a);
  }
  // The asset for a backend, or null with `why` set when the backend cannot run here.
  prt_asset* get(int backend_index, std::string* why) {
    prt_context* ctx = contexts_.usable(backend_index, why);
    if (!ctx) return nullptr;
    const std::lock_guard<std::mutex> lock(mutex_);
    build();
    prt_asset*& asset = assets_[backend_index];
    if (!asset && prt_asset_load_memory_borrowed(ctx, blob_.data(), blob_.size(), PRT_VALIDATE_FULL,
                                                 &asset) != PRT_OK) {
      *why = std::string("load failed: ") + prt_context_last_message(ctx);
      return nullptr;
    }
    return asset;
  }

 private:
  void build() {
    if (!blob_.empty()) return;
    const prt_test::WvltTransfer t = prt_bench::bake_shaped_transfer();
    g_figures.traffic = prt_bench::wavelet_traffic(t);
    blob_ = prt_test::wvlt_make_blob(prt_test::wvlt_encode(t), t.vertices);
  }
  prt_bench::BackendContexts contexts_;
  std::mutex mutex_;
  prt_test::Bytes blob_;
  prt_asset* assets_[kBackendCount] = {};
} g_assets;

// A prepared light for shading: any values do (the loop reads every stored pair regardless).
std::vector<float> shading_light(const prt_asset* asset) {
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  prt_wavelet_get_info(asset, &info);
  std::vector<float> light = prt_test::wvlt_random_light(info.coefficient_count, 3);
  prt_wavelet_prepare_light(asset, light.data(), light.data(), nullptr);
  return light;
}

// --- Benchmarks -----------------------------------------------------------------------------

void BM_StreamTriad(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  g_figures.triad[threads] = prt_bench::stream_triad(state, threads);
}
BENCHMARK(BM_StreamTriad)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Shades this benchmark thread's share of the vertices, once per iteration.
void BM_Relight(benchmark::State& state, int backend_index) {
  const Backend& backend = kBackends[backend_index];
  std::string why;
  prt_asset* asset = g_assets.get(backend_index, &why);
  if (!asset) {
    state.SkipWithError(why.c_str());
    return;
  }
  const uint32_t vertices = prt_bench::kBunnyVertices;
  const uint32_t threads = state.threads(), index = state.thread_index();
  const auto [first, count] = prt_bench::thread_share(state, vertices);
  const std::vector<float> light = shading_light(asset);
  std::vector<float> out(std::size_t(count) * 3);
  const auto [seconds, cpu_seconds] = prt_bench::time_shading(
      state,
      [&] {
        return prt_wavelet_shade(asset, backend.backend, light.data(), nullptr, first, count,
                                 out.data());
      },
      out.data());
  const double shaded = double(count) * double(state.iterations());
  state.SetItemsProcessed(static_cast<int64_t>(shaded));
  state.SetBytesProcessed(static_cast<int64_t>(shaded * g_figures.traffic.streamed_per_vertex));
  state.counters["frames/s"] =
      benchmark::Counter(shaded / double(vertices), benchmark::Counter::kIsRate);
  const std::lock_guard<std::mutex> lock(g_figures.mutex);
  if (seconds > 0.0 && cpu_seconds > 0.0)
    g_figures.shading[backend_index][threads - 1][index] = {shaded / seconds, shaded / cpu_seconds};
}

void register_relight() {
  for (int backend = 0; backend < kBackendCount; ++backend)
    for (const int threads : {1, 2}) {
      const std::string name = std::string("Relight/") + kBackends[backend].name;
      benchmark::RegisterBenchmark(name.c_str(), BM_Relight, backend)
          ->Threads(threads)
          ->UseRealTime()
          ->MinTime(0.3)
          ->Unit(benchmark::kMillisecond);
    }
}

// The environment: the 1k beach map the accuracy test uses, or a synthetic sky with a sun.
struct LatLong {
  std::vector<float> rgb;
  uint32_t width = 0, height = 0;
};
const LatLong& environment() {
  static const LatLong env = [] {
    LatLong e;
    const std::filesystem::path path =
        std::filesystem::path(PRT_SHARED_DIR) / "assets/envmaps/spiaggia_di_mondello_1k.hdr";
    try {
      if (std::filesystem::exists(path)) {
        const prt::io::EnvMap map =
            prt::io::load_envmap(path.string(), prt::io::EnvMapping::LatLong);
        e.rgb = map.pixels();
        e.width = uint32_t(map.width()), e.height = uint32_t(map.height());
        g_figures.env_name = path.filename().string();
      }
    } catch (const std::exception& error) {
      g_figures.env_name = std::string("(") + error.what() + ") ";
    }
    if (e.rgb.empty() || e.width != 2 * e.height) {
      e.width = 1024, e.height = 512;
      e.rgb.assign(3 * size_t(e.width) * e.height, 0.5f);
      for (uint32_t y = 100; y < 108; ++y)  // a 10^4 sun
        for (uint32_t x = 300; x < 308; ++x)
          for (uint32_t c = 0; c < 3; ++c) e.rgb[3 * (size_t(y) * e.width + x) + c] = 5000.0f;
      g_figures.env_name += "synthetic 1024x512 sky with a sun";
    }
    return e;
  }();
  return env;
}

// The per-frame light update for M kept coefficients (0 = all), under a rotation that turns by
// one degree per frame.
void BM_LightUpdate(benchmark::State& state) {
  const uint32_t m = uint32_t(state.range(0));
  const int path = int(state.range(1));
  std::string why;
  prt_asset* asset = g_assets.get(0, &why);
  if (!asset) {
    state.SkipWithError(why.c_str());
    return;
  }
  const LatLong& env = environment();
  const uint32_t coefficients =
      prt_wavelet_coefficient_count(PRT_WAVELET_PARAM_CUBE, prt_bench::kWaveletSize);
  std::vector<float> light(4 * size_t(coefficients)), prepared(light.size());
  std::vector<uint8_t> zero_blocks(coefficients / 256);
  // The source: once per map, outside the frame loop (a default context: the best SIMD ISA).
  auto [context, made] = prt::create_context();
  prt_wavelet_source* source = nullptr;
  if (path > 0 && made == PRT_OK) {
    const prt_env_image still = prt::latlong_env(env.width, env.height, env.rgb.data(), 3);
    prt_wavelet_source_desc desc = prt::sized<prt_wavelet_source_desc>();
    desc.param = PRT_WAVELET_PARAM_CUBE;
    desc.size = prt_bench::kWaveletSize;
    desc.env = &still;
    desc.flags = path == 2 ? uint32_t(PRT_WAVELET_SOURCE_REDUCE_2X2) : 0u;
    made = prt_wavelet_source_create(context.get(), &desc, &source);
  }
  if (made != PRT_OK) {
    state.SkipWithError(prt_result_string(made));
    return;
  }
  double seconds[4] = {0, 0, 0, 0};
  int frame = 0;
  auto lap = [](std::chrono::steady_clock::time_point& t) {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - t).count();
    t = now;
    return s;
  };
  for (auto _ : state) {
    const double angle = 0.017453292519943295 * (frame++ % 360);
    const float c = float(std::cos(angle)), s = float(std::sin(angle));
    const float rotation[9] = {c, 0, s, 0, 1, 0, -s, 0, c};
    auto t = std::chrono::steady_clock::now();
    const prt_env_image image =
        prt::latlong_env(env.width, env.height, env.rgb.data(), 3, rotation);
    prt_result r = source ? prt_wavelet_source_resample(source, rotation, light.data())
                          : prt_wavelet_resample(PRT_WAVELET_PARAM_CUBE, prt_bench::kWaveletSize,
                                                 &image, light.data());
    seconds[0] += lap(t);
    if (r == PRT_OK)
      r = prt_wavelet_transform_light(PRT_WAVELET_PARAM_CUBE, prt_bench::kWaveletSize,
                                      light.data());
    seconds[1] += lap(t);
    if (r == PRT_OK)
      r = prt_wavelet_select_light(PRT_WAVELET_PARAM_CUBE, prt_bench::kWaveletSize,
                                   m ? m : coefficients, light.data());
    seconds[2] += lap(t);
    if (r == PRT_OK)
      r = prt_wavelet_prepare_light(asset, light.data(), prepared.data(), zero_blocks.data());
    seconds[3] += lap(t);
    if (r != PRT_OK) {
      state.SkipWithError(prt_result_string(r));
      break;
    }
    benchmark::DoNotOptimize(prepared.data());
  }
  prt_wavelet_source_destroy(source);
  const double frames = double(state.iterations());
  state.counters["frames/s"] = benchmark::Counter(frames, benchmark::Counter::kIsRate);
  const char* names[4] = {"resample_ms", "transform_ms", "select_ms", "prepare_ms"};
  for (int i = 0; i < 4; ++i) state.counters[names[i]] = 1e3 * seconds[i] / frames;
  LightFigure figure;
  figure.m = m;
  figure.path = path;
  figure.resample = seconds[0] / frames, figure.transform = seconds[1] / frames;
  figure.select = seconds[2] / frames, figure.prepare = seconds[3] / frames;
  std::vector<LightFigure>& figures = g_figures.light;
  if (!figures.empty() && figures.back().m == m && figures.back().path == path)
    figures.back() = figure;
  else
    figures.push_back(figure);
}
BENCHMARK(BM_LightUpdate)
    ->ArgNames({"M", "path"})
    ->ArgsProduct({{64, 256, 1024, 0}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(0.3);

// The environment's light cut to M coefficients (0 = all) and prepared for the asset, with its
// zero-block mask in *zero_blocks.
std::vector<float> environment_light(prt_asset* asset, uint32_t m,
                                     std::vector<uint8_t>* zero_blocks) {
  const LatLong& env = environment();
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  prt_wavelet_get_info(asset, &info);
  const uint32_t size = info.size,
                 coefficients = prt_wavelet_coefficient_count(PRT_WAVELET_PARAM_CUBE, size);
  std::vector<float> light(4 * size_t(coefficients));
  zero_blocks->assign(coefficients / 256, 0);
  const prt_env_image image = prt::latlong_env(env.width, env.height, env.rgb.data());
  prt_result r = prt_wavelet_resample(PRT_WAVELET_PARAM_CUBE, size, &image, light.data());
  if (r == PRT_OK) r = prt_wavelet_transform_light(PRT_WAVELET_PARAM_CUBE, size, light.data());
  if (r == PRT_OK)
    r = prt_wavelet_select_light(PRT_WAVELET_PARAM_CUBE, size, m ? m : coefficients, light.data());
  if (r == PRT_OK)
    r = prt_wavelet_prepare_light(asset, light.data(), light.data(), zero_blocks->data());
  if (r != PRT_OK) light.clear();
  return light;
}

// Rows shaped like a `--cube 32 --keep 307` bake: every coarse coefficient of levels -1..2 and
// a share of levels 3 and 4 on three faces, about 307 per vertex.
constexpr double kKeep307Share[8] = {1.0, 1.0, 1.0, 1.0, 0.17, 0.008, 0.0, 0.0};

// Counts the bytes an asset holds from its context's allocator.
struct CountingAllocator {
  std::mutex mutex;
  double live = 0;
  static void* alloc(void* user, size_t size, size_t align) {
    auto* self = static_cast<CountingAllocator*>(user);
    void* p = ::operator new(size, std::align_val_t(align < 16 ? 16 : align));
    const std::lock_guard<std::mutex> lock(self->mutex);
    self->live += double(size);
    return p;
  }
  static void free(void* user, void* ptr, size_t size) {
    auto* self = static_cast<CountingAllocator*>(user);
    ::operator delete(ptr, std::align_val_t(16));
    const std::lock_guard<std::mutex> lock(self->mutex);
    self->live -= double(size);
  }
};

// The relight-at-M assets by face size (64: the bunny of g_assets' rows; 32: keep-307 rows),
// each loaded in a context without limits (the best SIMD backend) and timed against a load in
// an SSE4.1-limited context, which makes no tiles.
class MarkAssets {
 public:
  ~MarkAssets() {
    for (auto& [size, entry] : entries_) prt_asset_destroy(entry.asset);
  }
  prt_context* context() const { return context_.get(); }
  prt_asset* get(uint32_t size) {
    const std::lock_guard<std::mutex> lock(mutex_);
    Entry& e = entries_[size];
    if (!e.asset) load(size, &e);
    return e.asset;
  }

 private:
  struct Entry {
    prt_test::Bytes blob;
    prt_asset* asset = nullptr;
  };
  // The best of three loads' seconds, and the bytes the last one holds.
  static std::pair<double, double> time_load(const prt_test::Bytes& blob, prt_simd_isa limit) {
    CountingAllocator counter;
    prt_allocator allocator{CountingAllocator::alloc, CountingAllocator::free, &counter};
    prt_context_desc desc = prt::sized<prt_context_desc>();
    desc.allocator = &allocator;
    desc.simd_isa_limit = limit;
    auto [context, made] = prt::create_context(&desc);
    if (made != PRT_OK) return {0.0, 0.0};
    double best = 1e30, bytes = 0;
    for (int run = 0; run < 3; ++run) {
      const double before = counter.live;
      prt_asset* asset = nullptr;
      const auto start = std::chrono::steady_clock::now();
      const prt_result r = prt_asset_load_memory_borrowed(context.get(), blob.data(), blob.size(),
                                                          PRT_VALIDATE_QUICK, &asset);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (r != PRT_OK) return {0.0, 0.0};
      best = std::min(best, seconds);
      bytes = counter.live - before;
      prt_asset_destroy(asset);
    }
    return {best, bytes};
  }
  void load(uint32_t size, Entry* e) {
    const prt_test::WvltTransfer t =
        size == prt_bench::kWaveletSize
            ? prt_bench::bake_shaped_transfer()
            : prt_bench::bake_shaped_transfer(prt_bench::kBunnyVertices, size, 1, kKeep307Share);
    const prt_test::Bytes section = prt_test::wvlt_encode(t);
    e->blob = prt_test::wvlt_make_blob(section, t.vertices);
    if (!context_) context_ = std::move(prt::create_context(nullptr).handle);
    if (!context_ || prt_asset_load_memory_borrowed(context_.get(), e->blob.data(), e->blob.size(),
                                                    PRT_VALIDATE_FULL, &e->asset) != PRT_OK) {
      e->asset = nullptr;
      return;
    }
    Figures::LoadCost cost;
    cost.size = size;
    cost.section_bytes = double(section.size());
    std::tie(cost.tiled, cost.tiled_bytes) = time_load(e->blob, PRT_SIMD_ISA_AUTO);
    std::tie(cost.plain, cost.plain_bytes) = time_load(e->blob, PRT_SIMD_ISA_SSE41);
    g_figures.load_cost.push_back(cost);
  }
  std::mutex mutex_;
  prt::ContextPtr context_;
  std::map<uint32_t, Entry> entries_;
} g_mark_assets;

// Every vertex on the best SIMD backend, one thread, under the environment cut to M terms
// (state.range(0), 0 = all) on the asset of face size state.range(1).
void BM_RelightAtM(benchmark::State& state) {
  const uint32_t m = uint32_t(state.range(0)), size = uint32_t(state.range(1));
  prt_asset* asset = g_mark_assets.get(size);
  std::vector<uint8_t> zero_blocks;
  const std::vector<float> light =
      asset ? environment_light(asset, m, &zero_blocks) : std::vector<float>();
  if (light.empty()) {
    state.SkipWithError(asset ? "light update failed" : "load failed");
    return;
  }
  std::vector<float> out(3 * size_t(prt_bench::kBunnyVertices));
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const prt_result r =
        prt_wavelet_shade(asset, PRT_BACKEND_AUTO, light.data(), zero_blocks.data(), 0,
                          prt_bench::kBunnyVertices, out.data());
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (r != PRT_OK) {
      state.SkipWithError(prt_result_string(r));
      return;
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["frames/s"] =
      benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  if (g_figures.relight_at_m_backend.empty()) {
    prt_backend_info info = prt::sized<prt_backend_info>();
    prt_backend_get_info(g_mark_assets.context(), PRT_BACKEND_SIMD, &info);
    g_figures.relight_at_m_backend =
        info.usable ? std::string("simd-") + prt_simd_isa_name(info.isa) : std::string("cpu");
  }
  auto& figures = g_figures.relight_at_m;  // the last run of each (N, M) (benchmark reruns it)
  if (figures.empty() || figures.back().m != m || figures.back().size != size)
    figures.push_back({size, m, 0.0});
  figures.back().seconds = seconds / double(state.iterations());
}
BENCHMARK(BM_RelightAtM)
    ->ArgsProduct({{0, 30, 100, 300, 1000}, {64, 32}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(0.3);

// --- Summary --------------------------------------------------------------------------------

void print_relight(bool by_cpu) {
  const Figures& f = g_figures;
  const prt_bench::WaveletTraffic& w = f.traffic;
  bool any = false;
  for (int b = 0; b < kBackendCount; ++b) any = any || shading_total(b, 1).wall > 0.0;
  if (!any) return;  // filtered out
  std::printf("\n  relight by %s\n", by_cpu ? "CPU time of each thread" : "wall clock");
  std::printf("  %-12s %7s %9s %9s %12s %16s\n", "backend", "threads", "Mvert/s", "frames/s",
              "rows % triad", "+gathers % triad");
  for (int b = 0; b < kBackendCount; ++b)
    for (int threads = 1; threads <= 2; ++threads) {
      const prt_bench::Rate rate = shading_total(b, threads);
      const double vertices = by_cpu ? rate.cpu : rate.wall;
      const double triad = by_cpu ? f.triad[threads].cpu : f.triad[threads].wall;
      if (vertices <= 0.0 || triad <= 0.0) continue;
      std::printf("  %-12s %7d %9.3f %9.1f %11.0f%% %15.0f%%\n", kBackends[b].name, threads,
                  vertices * 1e-6, vertices / prt_bench::kBunnyVertices,
                  100.0 * vertices * w.streamed_per_vertex / triad,
                  100.0 * vertices * (w.streamed_per_vertex + w.gathered_per_vertex) / triad);
    }
}

void print_relight_at_m() {
  const Figures& f = g_figures;
  if (f.relight_at_m.empty()) return;
  std::printf(
      "\n  relight at M light coefficients (%s, %s, 1 thread; zero light skipped), ms per frame, "
      "against M = all in this run, frames/s, and at M = 300 against the mark:\n",
      f.env_name.c_str(), f.relight_at_m_backend.c_str());
  for (const uint32_t size : {64u, 32u}) {
    double all = 0.0;
    for (const auto& r : f.relight_at_m)
      if (r.size == size && r.m == 0) all = r.seconds;
    bool header = false;
    for (const auto& r : f.relight_at_m) {
      if (r.size != size) continue;
      if (!header)
        std::printf("  N = %u, K = %s:\n", size, size == 64 ? "1000" : "307"), header = true;
      const double fps = r.seconds > 0.0 ? 1.0 / r.seconds : 0.0, mark = size == 64 ? 70.0 : 200.0;
      std::printf("  %6s %9.2f ms %6.2f x %8.1f frames/s",
                  r.m ? std::to_string(r.m).c_str() : "all", 1e3 * r.seconds,
                  all > 0.0 ? all / r.seconds : 0.0, fps);
      if (r.m == 300) std::printf("   %.2f x the mark of %.0f frames/s", fps / mark, mark);
      std::printf("\n");
    }
  }
  for (const auto& c : f.load_cost)
    std::printf(
        "  load, N = %u (quick validation, best of 3): %.1f ms with the tiles, %.1f ms without "
        "(%+.1f ms); asset holds %.1f MB with, %.3f MB without (tiles %+.1f MB = %.2f x the "
        "%.1f MB section)\n",
        c.size, 1e3 * c.tiled, 1e3 * c.plain, 1e3 * (c.tiled - c.plain), c.tiled_bytes * 1e-6,
        c.plain_bytes * 1e-6, (c.tiled_bytes - c.plain_bytes) * 1e-6,
        c.section_bytes > 0 ? (c.tiled_bytes - c.plain_bytes) / c.section_bytes : 0.0,
        c.section_bytes * 1e-6);
}

void print_summary() {
  const Figures& f = g_figures;
  const prt_bench::WaveletTraffic& w = f.traffic;
  std::printf("\nsummary\n");
  std::printf(
      "  memory bandwidth (triad), by CPU time: %.2f GB/s on 1 thread, %.2f GB/s on 2; "
      "by wall clock: %.2f, %.2f\n",
      f.triad[1].cpu * 1e-9, f.triad[2].cpu * 1e-9, f.triad[1].wall * 1e-9, f.triad[2].wall * 1e-9);
  if (w.pairs_per_vertex > 0.0) {
    std::printf(
        "  asset: %u vertices, cube N = %u, %.0f pairs per vertex (bake-shaped rows); per vertex "
        "%.0f B of rows streamed + %.0f B of light gathered\n",
        prt_bench::kBunnyVertices, prt_bench::kWaveletSize, w.pairs_per_vertex,
        w.streamed_per_vertex, w.gathered_per_vertex);
    std::printf(
        "  paper (Ng et al. 2003 implementation report): %.0f frames/s for %.0f vertices "
        "= %.2f Mvert/s\n",
        prt_bench::kPaperFps, prt_bench::kPaperVertices,
        prt_bench::kPaperFps * prt_bench::kPaperVertices * 1e-6);
    print_relight(/*by_cpu=*/true);
    print_relight(/*by_cpu=*/false);
  }
  if (!f.light.empty()) {
    std::printf("\n  light update per frame (%s), cube N = %u, ms:\n", f.env_name.c_str(),
                prt_bench::kWaveletSize);
    std::printf("  %6s %-9s %9s %9s %9s %9s %9s %16s\n", "M", "path", "resample", "transform",
                "select", "prepare", "total", "total vs resample");
    auto total = [](const LightFigure& l) {
      return l.resample + l.transform + l.select + l.prepare;
    };
    for (const LightFigure& l : f.light) {
      double old_total = 0;  // prt_wavelet_resample's at the same M in this run
      for (const LightFigure& o : f.light)
        if (o.m == l.m && o.path == 0) old_total = total(o);
      std::printf("  %6s %-9s %9.2f %9.2f %9.2f %9.2f %9.2f",
                  l.m ? std::to_string(l.m).c_str() : "all",
                  l.path == 0 ? "resample" : (l.path == 1 ? "source" : "src 2x2"), 1e3 * l.resample,
                  1e3 * l.transform, 1e3 * l.select, 1e3 * l.prepare, 1e3 * total(l));
      if (l.path > 0 && old_total > 0) std::printf(" %15.2fx", old_total / total(l));
      std::printf("\n");
    }
  }
  print_relight_at_m();
  print_bake();
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_relight();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary();
  return 0;
}
