// SPDX-License-Identifier: MIT
// What the CPU shading benchmarks of every technique share: the backends they compare (scalar,
// SIMD forced to SSE4.1, to AVX2 and to AVX-512), one context per backend that says why a backend
// cannot run here, a benchmark thread's share of the vertices, and the timed shading loop that
// measures by wall clock and by the thread's own CPU time (bench_triad.hpp).
#pragma once

#include <benchmark/benchmark.h>
#include <prt/prt.hpp>

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

#include "support/bench_triad.hpp"

namespace prt_bench {

struct Backend {
  const char* name;
  prt_backend backend;
  prt_simd_isa isa_limit;
};
constexpr Backend kBackends[] = {{"cpu", PRT_BACKEND_CPU, PRT_SIMD_ISA_AUTO},
                                 {"simd-sse4.1", PRT_BACKEND_SIMD, PRT_SIMD_ISA_SSE41},
                                 {"simd-avx2", PRT_BACKEND_SIMD, PRT_SIMD_ISA_AVX2},
                                 {"simd-avx512", PRT_BACKEND_SIMD, PRT_SIMD_ISA_AVX512}};
constexpr int kBackendCount = int(sizeof kBackends / sizeof kBackends[0]);

// A context per backend, limited to its instruction set, made on first use and shared by the
// benchmark threads.
class BackendContexts {
 public:
  ~BackendContexts() {
    for (prt_context* context : contexts_) prt_context_destroy(context);
  }
  // The context of kBackends[index], or null with `why` set when that backend cannot run here.
  prt_context* usable(int index, std::string* why) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const Backend& backend = kBackends[index];
    prt_context*& context = contexts_[index];
    if (!context) {
      prt_context_desc desc = prt::sized<prt_context_desc>();
      desc.simd_isa_limit = backend.isa_limit;
      if (prt_context_create(&desc, &context) != PRT_OK) {
        *why = std::string(backend.name) + ": no context";
        return nullptr;
      }
    }
    prt_backend_info info = prt::sized<prt_backend_info>();
    prt_backend_get_info(context, backend.backend, &info);
    if (!info.usable || (backend.backend == PRT_BACKEND_SIMD && info.isa != backend.isa_limit)) {
      *why = std::string(backend.name) + " not usable here: " + info.note;
      return nullptr;
    }
    return context;
  }

 private:
  std::mutex mutex_;
  prt_context* contexts_[kBackendCount] = {};
};

// The vertices [first, first + count) of `vertices` that this benchmark thread shades.
struct VertexRange {
  uint32_t first = 0, count = 0;
};
inline VertexRange thread_share(const benchmark::State& state, uint32_t vertices) {
  const uint64_t threads = uint64_t(state.threads()), index = uint64_t(state.thread_index());
  const uint32_t first = uint32_t(vertices * index / threads);
  return {first, uint32_t(vertices * (index + 1) / threads) - first};
}

// Runs `shade_once` (returning a prt_result) once per iteration into `out`, timed by wall clock
// and by this thread's CPU time; a failure ends the benchmark with its name.
struct Timed {
  double seconds = 0.0, cpu_seconds = 0.0;
};
template <typename ShadeOnce, typename Output>
Timed time_shading(benchmark::State& state, ShadeOnce&& shade_once, Output* out) {
  Timed timed;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = thread_cpu_seconds();
    const prt_result r = shade_once();
    timed.cpu_seconds += thread_cpu_seconds() - cpu_start;
    timed.seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (r != PRT_OK) {
      state.SkipWithError(prt_result_string(r));
      break;
    }
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  return timed;
}

}  // namespace prt_bench
