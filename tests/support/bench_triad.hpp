// SPDX-License-Identifier: MIT
// The memory-bandwidth roofline the benchmarks compare with: a STREAM triad measured in the same
// run as the figure, by wall clock and by each thread's CPU time (this machine may be shared).
#pragma once

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <ctime>
#include <thread>
#include <vector>

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

}  // namespace prt_bench
