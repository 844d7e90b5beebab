// SPDX-License-Identifier: MIT
// The ray-throughput roofline the benchmarks compare with: a raw Embree scene with no prtkit code
// in the way.
#pragma once

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "prt/baker/embree_scene.hpp"
#include "prt/baker/sampling.hpp"
#include "prt/baker/scene.hpp"
#include "support/bench_triad.hpp"

namespace prt_bench {

// A raw Embree device and scene over a Scene's non-degenerate triangles.
struct RawEmbree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  // flags: none for the fastest raw call; RTC_SCENE_FLAG_ROBUST for the bake's own scene flags.
  explicit RawEmbree(const prt::bake::Scene& s, RTCSceneFlags flags = RTC_SCENE_FLAG_NONE) {
    device = rtcNewDevice(nullptr);
    scene = rtcNewScene(device);
    rtcSetSceneFlags(scene, flags);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    for (const prt::bake::Mesh& mesh : s.meshes) {
      std::vector<std::uint32_t> kept;
      for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        if (prt::bake::is_degenerate_triangle(mesh, t)) continue;
        kept.insert(kept.end(), mesh.indices.begin() + 3 * t, mesh.indices.begin() + 3 * t + 3);
      }
      if (kept.empty()) continue;
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, mesh.positions.size()));
      std::memcpy(v, mesh.positions.data(), mesh.positions.size() * 12);
      auto* i = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, kept.size() / 3));
      std::memcpy(i, kept.data(), kept.size() * 4);
      rtcCommitGeometry(g);
      rtcAttachGeometry(scene, g);
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(scene);
  }
  ~RawEmbree() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  int widest_packet() const {
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) return 16;
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) return 8;
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED)) return 4;
    return 1;
  }
  RawEmbree(const RawEmbree&) = delete;
  RawEmbree& operator=(const RawEmbree&) = delete;
};

inline void set_ftz_daz() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

// Rays like a bake's: `per_vertex` directions from every vertex with a usable normal, leaving
// it by the bake's offset policy, cosine-distributed about the normal.
struct VertexRays {
  std::uint32_t per_vertex = 0;
  std::vector<glm::vec3> origins, directions;  // one origin per `per_vertex` directions
};

inline VertexRays cosine_vertex_rays(const prt::bake::Scene& scene, std::uint32_t per_vertex) {
  VertexRays r;
  r.per_vertex = per_vertex;
  const prt::bake::EmbreeScene policy(scene, prt::bake::Context{});
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (const prt::bake::Mesh& mesh : scene.meshes)
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const glm::vec3 n = mesh.normals[v];
      if (!(glm::dot(n, n) > 0.5f)) continue;
      r.origins.push_back(policy.offset_origin(mesh.positions[v], n));
      const prt::bake::Frame frame(n);
      for (std::uint32_t k = 0; k < per_vertex; ++k)
        r.directions.push_back(
            frame.to_world(prt::bake::cosine_hemisphere({uniform(rng), uniform(rng)})));
    }
  return r;
}

// The ray roofline: rtcOccluded1 over `rays` on one thread in the benchmark's loop, with
// nothing else in the way; rays/s by wall clock and by the thread's CPU time.
inline Rate raw_occluded_rate(benchmark::State& state, const RawEmbree& raw,
                              const VertexRays& rays) {
  set_ftz_daz();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  std::size_t next = 0, occluded = 0;
  std::int64_t traced = 0;
  double seconds = 0.0, cpu_seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = thread_cpu_seconds();
    for (int i = 0; i < 4096; ++i, next = (next + 1) % rays.directions.size()) {
      const glm::vec3 o = rays.origins[next / rays.per_vertex], d = rays.directions[next];
      RTCRay ray{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, 0.0f, INFINITY, 0xFFFFFFFFu, 0, 0};
      rtcOccluded1(raw.scene, &context, &ray);
      occluded += ray.tfar < 0.0f;
    }
    cpu_seconds += thread_cpu_seconds() - cpu_start;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    traced += 4096;
  }
  benchmark::DoNotOptimize(occluded);
  state.counters["rays/s"] = benchmark::Counter(double(traced), benchmark::Counter::kIsRate);
  state.counters["occluded"] = double(occluded) / double(traced);
  return {double(traced) / seconds, double(traced) / cpu_seconds};
}

// The same rays through rtcOccluded4/8/16: consecutive rays of one vertex (per_vertex is a
// multiple of the width) in one packet, every lane valid. Packet and Ray are RTCRayN, RTCRayN's
// call the matching rtcOccludedN.
template <int Width, typename Packet, typename Call>
Rate raw_occluded_packet_rate(benchmark::State& state, const RawEmbree& raw, const VertexRays& rays,
                              Call call) {
  set_ftz_daz();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(64) int valid[Width];
  for (int k = 0; k < Width; ++k) valid[k] = -1;
  std::size_t next = 0, occluded = 0;
  std::int64_t traced = 0;
  double seconds = 0.0, cpu_seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = thread_cpu_seconds();
    for (int i = 0; i < 4096; i += Width) {
      alignas(64) Packet packet;
      for (int k = 0; k < Width; ++k, next = (next + 1) % rays.directions.size()) {
        const glm::vec3 o = rays.origins[next / rays.per_vertex], d = rays.directions[next];
        packet.org_x[k] = o.x;
        packet.org_y[k] = o.y;
        packet.org_z[k] = o.z;
        packet.tnear[k] = 0.0f;
        packet.dir_x[k] = d.x;
        packet.dir_y[k] = d.y;
        packet.dir_z[k] = d.z;
        packet.time[k] = 0.0f;
        packet.tfar[k] = INFINITY;
        packet.mask[k] = 0xFFFFFFFFu;
        packet.id[k] = 0;
        packet.flags[k] = 0;
      }
      call(valid, raw.scene, &context, &packet);
      for (int k = 0; k < Width; ++k) occluded += packet.tfar[k] < 0.0f;
    }
    cpu_seconds += thread_cpu_seconds() - cpu_start;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    traced += 4096;
  }
  benchmark::DoNotOptimize(occluded);
  state.counters["rays/s"] = benchmark::Counter(double(traced), benchmark::Counter::kIsRate);
  state.counters["occluded"] = double(occluded) / double(traced);
  return {double(traced) / seconds, double(traced) / cpu_seconds};
}

// Raw rtcOccludedN for N = 1, 4, 8 or 16 over the bake-like rays.
inline Rate raw_occluded_rate_width(benchmark::State& state, const RawEmbree& raw,
                                    const VertexRays& rays, int width) {
  switch (width) {
    case 4:
      return raw_occluded_packet_rate<4, RTCRay4>(state, raw, rays, rtcOccluded4);
    case 8:
      return raw_occluded_packet_rate<8, RTCRay8>(state, raw, rays, rtcOccluded8);
    case 16:
      return raw_occluded_packet_rate<16, RTCRay16>(state, raw, rays, rtcOccluded16);
    default:
      return raw_occluded_rate(state, raw, rays);
  }
}

// Registers `run` as BM_RawEmbreeOccluded/N for the widths raw_occluded_rate_width knows; `run`
// reads N from state.range(0). Call it from a namespace-scope initialiser so it keeps its place
// among the BENCHMARK registrations.
inline benchmark::internal::Benchmark* register_raw_occluded(void (*run)(benchmark::State&)) {
  return benchmark::RegisterBenchmark("BM_RawEmbreeOccluded", run)
      ->Arg(1)
      ->Arg(4)
      ->Arg(8)
      ->Arg(16)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->MinTime(0.5);
}

// Registers `run` as BM_RawEmbreeOccludedRobust/16: rtcOccluded16 on a scene built with the
// bake's flags (RTC_SCENE_FLAG_ROBUST), which shows how much of a bake's gap to the fastest raw
// call is the flag rather than the work around the rays.
inline benchmark::internal::Benchmark* register_raw_occluded_robust(
    void (*run)(benchmark::State&)) {
  return benchmark::RegisterBenchmark("BM_RawEmbreeOccludedRobust", run)
      ->Arg(16)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->MinTime(0.5);
}

// The bake's share of the raw call with its own scene flags, when both were measured.
inline void print_robust_share(const Rate& bake, const Rate& robust) {
  if (!(bake.cpu > 0.0 && robust.cpu > 0.0)) return;
  std::printf(
      "    against rtcOccluded16 on a scene with the bake's flags (RTC_SCENE_FLAG_ROBUST), by CPU "
      "time: %.2f vs %.2f Mrays/s = %.0f %%\n",
      bake.cpu * 1e-6, robust.cpu * 1e-6, 100.0 * bake.cpu / robust.cpu);
}

// The best of the raw calls measured so far (by CPU time, and by wall clock), and its width.
struct BestRaw {
  Rate rate{0.0, 0.0};
  int width = 0;
  void offer(const Rate& r, int w) {
    if (r.cpu > rate.cpu) {
      rate = r;
      width = w;
    }
  }
};

}  // namespace prt_bench
