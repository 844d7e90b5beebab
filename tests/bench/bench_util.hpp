// SPDX-License-Identifier: MIT
// Pieces the benchmarks share: the STREAM triad (the memory-bandwidth roofline of this machine,
// measured in the same run as the figure compared with it) and a raw Embree scene with no prtkit
// code in the way (the ray-throughput roofline). Taken from bench_foundation.cpp.
#pragma once

#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <thread>
#include <vector>

#include "prt/baker/embree_scene.hpp"
#include "prt/baker/scene.hpp"

namespace prt_bench {

// CPU time of the calling thread. This machine may be shared: a figure per CPU-second of each
// thread is not diluted by time the thread spent descheduled, where a wall-clock one is.
inline double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// CPU time of the whole process (for work that runs on threads of its own).
inline double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// A throughput measured both ways: total work per wall-clock second, and the sum over threads of
// each thread's work per second of its own CPU time.
struct Rate {
  double wall = 0.0, cpu = 0.0;
};

// STREAM-style triad a = b + s c over three arrays of 64 MiB (far beyond the caches) on
// `threads` threads, in bytes per second by STREAM's convention (3 x 8 bytes per element: two
// reads, one write; write-allocate ignored).
inline Rate stream_triad(benchmark::State& state, int threads) {
  constexpr std::size_t kElements = std::size_t(1) << 23;
  std::vector<double> a(kElements, 0.0), b(kElements, 1.0), c(kElements, 2.0);
  std::vector<double> cpu_seconds(threads, 0.0);
  const double scalar = 3.0;
  auto triad = [&](int t, std::size_t begin, std::size_t end) {
    const double start = thread_cpu_seconds();
    for (std::size_t i = begin; i < end; ++i) a[i] = b[i] + scalar * c[i];
    cpu_seconds[t] += thread_cpu_seconds() - start;
  };
  const std::size_t chunk = kElements / threads;
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back(triad, t, t * chunk, t + 1 == threads ? kElements : (t + 1) * chunk);
    for (auto& thread : pool) thread.join();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  const double bytes = 24.0 * kElements * state.iterations();
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
  Rate rate;
  rate.wall = bytes / seconds;
  for (int t = 0; t < threads; ++t)
    rate.cpu += 24.0 * (t + 1 == threads ? kElements - t * chunk : chunk) * state.iterations() /
                cpu_seconds[t];
  return rate;
}

// A raw Embree device and scene over a Scene's non-degenerate triangles.
struct RawEmbree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  explicit RawEmbree(const prt::bake::Scene& s) {
    device = rtcNewDevice(nullptr);
    scene = rtcNewScene(device);
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
  RawEmbree(const RawEmbree&) = delete;
  RawEmbree& operator=(const RawEmbree&) = delete;
};

inline void set_ftz_daz() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

}  // namespace prt_bench
