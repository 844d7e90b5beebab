// prt_workers (prt_workers.h): the speed-up of the split `sh` shade call over the one-range call
// on the same thread, for pools of 1 and 2 threads, on a bunny-sized random transfer (the
// bunny's vertex count, order 6, RGB, 8 bits). Printed as ratios, never asserted.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <random>
#include <vector>

#include "sh/sh_blob_test_util.hpp"
#include "support/blob_test_util.hpp"
#include "support/mesh_blob.hpp"

#include <prt/prt.h>

namespace {

using namespace prt_test;

constexpr uint32_t kBunnyVertices = 35947;
constexpr uint32_t kOrder = 6;

struct Setup {
  Context c;
  Transfer t = random_transfer(kOrder, kBunnyVertices, 3, 8, 1);
  LoadedAsset a{c.ctx, make_blob(encode(t), kBunnyVertices)};
  std::vector<float> light;
  std::vector<float> out = std::vector<float>(size_t(kBunnyVertices) * 3);
  Setup() {
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (uint32_t i = 0; i < kOrder * kOrder * 3; ++i) light.push_back(unit(rng));
  }
};

Setup& setup() {
  static Setup s;
  return s;
}

std::map<int, double> g_vertices_per_second;  // 0: one-range call, n: a pool of n threads

void BM_ShOneRange(benchmark::State& state) {
  Setup& s = setup();
  for (auto _ : state)
    benchmark::DoNotOptimize(
        prt_sh_shade(s.a.asset, PRT_BACKEND_AUTO, s.light.data(), 0, kBunnyVertices, s.out.data()));
  state.SetItemsProcessed(int64_t(state.iterations()) * kBunnyVertices);
}

void BM_ShWorkers(benchmark::State& state) {
  Setup& s = setup();
  prt_workers_desc desc{};
  desc.struct_size = sizeof desc;
  desc.thread_count = uint32_t(state.range(0));
  prt_workers* workers = nullptr;
  if (prt_workers_create(s.c.ctx, &desc, &workers) != PRT_OK) {
    state.SkipWithError("prt_workers_create failed");
    return;
  }
  for (auto _ : state)
    benchmark::DoNotOptimize(prt_sh_shade_workers(workers, s.a.asset, PRT_BACKEND_AUTO,
                                                  s.light.data(), 0, kBunnyVertices, s.out.data()));
  state.SetItemsProcessed(int64_t(state.iterations()) * kBunnyVertices);
  prt_workers_destroy(workers);
}

BENCHMARK(BM_ShOneRange)->UseRealTime();
BENCHMARK(BM_ShWorkers)->Arg(1)->Arg(2)->UseRealTime();

// Keeps each case's vertices per second for the ratio table.
class Recorder : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      // Iterations over their accumulated wall time (seconds): one shade per iteration.
      const double rate =
          double(kBunnyVertices) * double(run.iterations) / run.real_accumulated_time;
      const std::string name = run.benchmark_name();
      if (name.rfind("BM_ShOneRange", 0) == 0) g_vertices_per_second[0] = rate;
      if (name.rfind("BM_ShWorkers/1", 0) == 0) g_vertices_per_second[1] = rate;
      if (name.rfind("BM_ShWorkers/2", 0) == 0) g_vertices_per_second[2] = rate;
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  Recorder recorder;
  benchmark::RunSpecifiedBenchmarks(&recorder);
  if (g_vertices_per_second.count(0)) {
    std::printf("\n  sh shading, %u vertices, order %u: speed-up over the one-range call\n",
                kBunnyVertices, kOrder);
    for (int threads : {1, 2})
      if (g_vertices_per_second.count(threads))
        std::printf("  %d thread%s: %.2fx\n", threads, threads > 1 ? "s" : "",
                    g_vertices_per_second[threads] / g_vertices_per_second[0]);
  }
  benchmark::Shutdown();
  return 0;
}
