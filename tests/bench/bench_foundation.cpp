// SPDX-License-Identifier: MIT
// Foundation benchmarks, all in one run so their figures compare: STREAM-style triad bandwidth,
// raw Embree occlusion rays (rtcOccluded1 and the widest native packet) on a real mesh, and the
// reference renderer's rays per second, printed at the end as a share of raw rtcOccluded1.
//
//   prt_bench_foundation [--benchmark_min_time=0.2] [google benchmark flags]
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <thread>
#include <vector>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/reference.hpp"
#include "prt/baker/sampling.hpp"

#include "support/bench_embree.hpp"
#include "support/bench_triad.hpp"

namespace {

using namespace prt::bake;

// Figures kept for the summary line (the last measurement of each benchmark).
struct Figures {
  double triad_bytes_per_second[3] = {0, 0, 0};  // by thread count 1, 2
  double occluded1_rays_per_second = 0.0;
  double packet_rays_per_second = 0.0;
  int packet_width = 0;
  double renderer_rays_per_second = 0.0;
  std::string mesh_name;
} g_figures;

// --- Memory bandwidth ------------------------------------------------------------------------

void BM_StreamTriad(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  g_figures.triad_bytes_per_second[threads] = prt_bench::stream_triad(state, threads).wall;
}
BENCHMARK(BM_StreamTriad)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// --- The mesh and its rays -----------------------------------------------------------------

struct Workload {
  Scene scene;
  std::vector<glm::vec3> origins;     // one per group of kRaysPerPoint rays
  std::vector<glm::vec3> directions;  // cosine-distributed about the triangle's normal
};
constexpr int kRaysPerPoint = 16;
constexpr std::size_t kPoints = std::size_t(1) << 16;

const Workload& workload() {
  static const Workload w = [] {
    Workload w;
    const std::filesystem::path bunny =
        std::filesystem::path(PRT_SHARED_DIR) / "assets/meshes/stanford-bunny.obj";
    if (std::filesystem::exists(bunny)) {
      w.scene = import_scene(bunny.string(), Context{});
      g_figures.mesh_name = "stanford-bunny.obj";
    } else {
      w.scene = make_demo_scene();
      g_figures.mesh_name = "built-in demo scene (bunny not found)";
    }
    // Area-uniform points on the triangles, rays leaving the front side; the same offset policy
    // as the renderer (EmbreeScene::offset_origin).
    const EmbreeScene policy(w.scene, Context{});
    std::vector<double> area_cdf;
    std::vector<std::pair<std::size_t, std::size_t>> triangles;
    double total = 0.0;
    for (std::size_t m = 0; m < w.scene.meshes.size(); ++m) {
      const Mesh& mesh = w.scene.meshes[m];
      for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        if (is_degenerate_triangle(mesh, t)) continue;
        const glm::vec3 p0 = mesh.positions[mesh.indices[3 * t]];
        total += 0.5 * glm::length(glm::cross(mesh.positions[mesh.indices[3 * t + 1]] - p0,
                                              mesh.positions[mesh.indices[3 * t + 2]] - p0));
        area_cdf.push_back(total);
        triangles.emplace_back(m, t);
      }
    }
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (std::size_t i = 0; i < kPoints; ++i) {
      const double pick = uniform(rng) * total;
      const std::size_t k = std::min<std::size_t>(
          std::lower_bound(area_cdf.begin(), area_cdf.end(), pick) - area_cdf.begin(),
          triangles.size() - 1);
      const Mesh& mesh = w.scene.meshes[triangles[k].first];
      const std::size_t t = triangles[k].second;
      const glm::vec3 p0 = mesh.positions[mesh.indices[3 * t]],
                      p1 = mesh.positions[mesh.indices[3 * t + 1]],
                      p2 = mesh.positions[mesh.indices[3 * t + 2]];
      float a = static_cast<float>(uniform(rng)), b = static_cast<float>(uniform(rng));
      if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
      const glm::vec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
      w.origins.push_back(policy.offset_origin(p0 + a * (p1 - p0) + b * (p2 - p0), n));
      const Frame frame(n);
      for (int r = 0; r < kRaysPerPoint; ++r) {
        const glm::vec2 u(static_cast<float>(uniform(rng)), static_cast<float>(uniform(rng)));
        w.directions.push_back(frame.to_world(cosine_hemisphere(u)));
      }
    }
    return w;
  }();
  return w;
}

using prt_bench::RawEmbree;
using prt_bench::set_ftz_daz;

const RawEmbree& raw_embree() {
  static const RawEmbree raw(workload().scene);
  return raw;
}

void BM_EmbreeOccluded1(benchmark::State& state) {
  const Workload& w = workload();
  const RawEmbree& raw = raw_embree();
  set_ftz_daz();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  std::size_t next = 0, occluded = 0;
  std::int64_t rays = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    for (int batch = 0; batch < 4096; ++batch, next = (next + 1) % w.directions.size()) {
      const glm::vec3 o = w.origins[next / kRaysPerPoint], d = w.directions[next];
      RTCRay ray{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, 0.0f, INFINITY, 0xFFFFFFFFu, 0, 0};
      rtcOccluded1(raw.scene, &context, &ray);
      occluded += ray.tfar < 0.0f;
    }
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rays += 4096;
  }
  benchmark::DoNotOptimize(occluded);
  state.counters["rays/s"] =
      benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["occluded"] = static_cast<double>(occluded) / rays;
  g_figures.occluded1_rays_per_second = rays / seconds;
}
BENCHMARK(BM_EmbreeOccluded1)->Unit(benchmark::kMillisecond)->UseRealTime();

// Fills `width` rays of a packet from one surface point (kRaysPerPoint is a multiple of width).
template <typename Packet>
void fill_packet(const Workload& w, int width, std::size_t* next, Packet* packet) {
  for (int k = 0; k < width; ++k, *next = (*next + 1) % w.directions.size()) {
    const glm::vec3 o = w.origins[*next / kRaysPerPoint], d = w.directions[*next];
    packet->org_x[k] = o.x, packet->org_y[k] = o.y, packet->org_z[k] = o.z;
    packet->dir_x[k] = d.x, packet->dir_y[k] = d.y, packet->dir_z[k] = d.z;
    packet->tnear[k] = 0.0f, packet->tfar[k] = INFINITY, packet->time[k] = 0.0f;
    packet->mask[k] = 0xFFFFFFFFu, packet->id[k] = 0, packet->flags[k] = 0;
  }
}

int count_occluded(const float* tfar, int width) {
  int occluded = 0;
  for (int k = 0; k < width; ++k) occluded += tfar[k] < 0.0f;
  return occluded;
}

void BM_EmbreeOccludedPacket(benchmark::State& state) {
  const Workload& w = workload();
  const RawEmbree& raw = raw_embree();
  const int width = std::max(raw.widest_packet(), 4);
  set_ftz_daz();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) int valid[16];
  for (int& v : valid) v = -1;
  alignas(64) RTCRay16 packet16;
  alignas(64) RTCRay8 packet8;
  alignas(64) RTCRay4 packet4;
  std::size_t next = 0;
  std::int64_t rays = 0, occluded = 0;
  double seconds = 0.0;
  const int per_iteration = 4096;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    for (int p = 0; p < per_iteration / width; ++p) {
      if (width == 16) {
        fill_packet(w, 16, &next, &packet16);
        rtcOccluded16(valid, raw.scene, &context, &packet16);
        occluded += count_occluded(packet16.tfar, 16);
      } else if (width == 8) {
        fill_packet(w, 8, &next, &packet8);
        rtcOccluded8(valid, raw.scene, &context, &packet8);
        occluded += count_occluded(packet8.tfar, 8);
      } else {
        fill_packet(w, 4, &next, &packet4);
        rtcOccluded4(valid, raw.scene, &context, &packet4);
        occluded += count_occluded(packet4.tfar, 4);
      }
    }
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rays += per_iteration;
  }
  state.SetLabel("rtcOccluded" + std::to_string(width));
  state.counters["rays/s"] =
      benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["occluded"] = static_cast<double>(occluded) / static_cast<double>(rays);
  g_figures.packet_rays_per_second = rays / seconds;
  g_figures.packet_width = width;
}
BENCHMARK(BM_EmbreeOccludedPacket)->Unit(benchmark::kMillisecond)->UseRealTime();

// --- The reference renderer on the same mesh -----------------------------------------------

void BM_ReferenceRendererVertices(benchmark::State& state) {
  const Workload& w = workload();
  const std::filesystem::path sun =
      std::filesystem::path(PRT_SHARED_DIR) / "assets/envmaps/spiaggia_di_mondello_1k.hdr";
  const prt::io::EnvMap env = std::filesystem::exists(sun)
                                  ? prt::io::load_envmap(sun.string(), prt::io::EnvMapping::Auto)
                                  : make_demo_sky(512);
  ReferenceSettings settings;
  settings.bounces = static_cast<int>(state.range(0));
  settings.spp = 8;
  settings.override_albedo = true;
  settings.albedo = glm::vec3(0.8f);
  const ReferenceRenderer renderer(w.scene, env, settings, Context{});
  Context one_thread;
  one_thread.threads = 1;  // compared with single-threaded raw Embree
  std::uint64_t rays = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const VertexRadiance result = renderer.render_vertices(one_thread);
    rays += result.stats.rays;
    seconds += result.stats.seconds;
  }
  state.counters["rays/s"] =
      benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  if (settings.bounces == 0) g_figures.renderer_rays_per_second = rays / seconds;
}
BENCHMARK(BM_ReferenceRendererVertices)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("bounces")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

void print_summary() {
  const Figures& f = g_figures;
  std::printf("\nsummary (mesh: %s; ray figures on one thread)\n", f.mesh_name.c_str());
  if (f.triad_bytes_per_second[1] > 0.0) {
    std::printf("  memory bandwidth (triad): %.2f GB/s on 1 thread, %.2f GB/s on 2 threads\n",
                f.triad_bytes_per_second[1] * 1e-9, f.triad_bytes_per_second[2] * 1e-9);
  }
  if (f.occluded1_rays_per_second > 0.0) {
    std::printf("  raw Embree rtcOccluded1: %.2f Mrays/s\n", f.occluded1_rays_per_second * 1e-6);
  }
  if (f.packet_rays_per_second > 0.0) {
    std::printf("  raw Embree rtcOccluded%d: %.2f Mrays/s\n", f.packet_width,
                f.packet_rays_per_second * 1e-6);
  }
  if (f.renderer_rays_per_second > 0.0 && f.occluded1_rays_per_second > 0.0) {
    std::printf("  reference renderer (0 bounces): %.2f Mrays/s = %.0f %% of raw rtcOccluded1\n",
                f.renderer_rays_per_second * 1e-6,
                100.0 * f.renderer_rays_per_second / f.occluded1_rays_per_second);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary();
  return 0;
}
