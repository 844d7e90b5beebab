// SPDX-License-Identifier: MIT
// Technique `pose` benchmark; printed, never asserted:
//  - the memory-bandwidth roofline: STREAM triad on 1 and 2 threads, in the same run;
//  - evaluations per second: one evaluation is a full prt_pose_shade of every vertex from joint
//    rotations (features, pose coordinates, skeleton, the light folded, the learned part and,
//    for model 1, the exact part of each skinned normal), on the scalar backend, SIMD (AVX2),
//    and SIMD over a 2-thread prt_workers pool; for both models on a synthetic blob at the
//    paper's scale (11,534 vertices, J 19, p 8, q 22, order 6, 16 bits), and on every blob named
//    in PRT_POSE_BENCH_BLOBS (colon-separated paths, e.g. CesiumMan baked with --subdivide-to);
//  - the share of the roofline: the bytes an evaluation must move (basis values, the skin
//    records model 1 reads, the regression, the radiance written) times evaluations per second,
//    over the triad on as many threads. At paper scale those bytes (about 1 MB) can stay in a
//    large cache, so the share says how far the kernels are from streaming, not that memory
//    limits them.
// Every rate is given by each thread's CPU time and by wall clock (bench_triad.hpp).
//
//   [PRT_POSE_BENCH_BLOBS=a.prtk:b.prtk] prt_bench_pose [google benchmark flags]
#include <benchmark/benchmark.h>
#include <prt/prt.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "pose/pose_blob.hpp"
#include "support/bench_backends.hpp"
#include "support/bench_triad.hpp"

namespace {

using prt_bench::kBackends;

// The paper's character (James and Fatahalian 2003, paper 002): 11,534 vertices, 8 pose and
// 22 basis dimensions; CesiumMan's 19 joints; order 6 and 16 bits as `prt-bake bake pose`.
constexpr uint32_t kPaperVertices = 11534, kJoints = 19, kPoseDims = 8, kBasisDims = 22;
constexpr uint32_t kOrder = 6, kBits = 16;

// How a case is shaded: a backend of support/bench_backends.hpp, alone or over workers.
struct Runner {
  const char* name;
  int backend;  // index into kBackends
  uint32_t threads;
};
constexpr Runner kRunners[] = {{"cpu", 0, 1}, {"simd-avx2", 2, 1}, {"simd-avx2 x2 workers", 2, 2}};
constexpr int kRunnerCount = int(sizeof kRunners / sizeof kRunners[0]);

struct Case {
  std::string name;
  std::vector<uint8_t> bytes;
  prt_pose_info info{};
  double bytes_per_eval = 0.0;
  prt_bench::Rate rate[kRunnerCount];  // evaluations/s
  std::string skipped[kRunnerCount];
};

struct Figures {
  prt_bench::Rate triad[3];  // by thread count 1, 2
  std::vector<std::unique_ptr<Case>> cases;
  std::mutex mutex;
} g_figures;

// Bytes an evaluation must move: every basis value, model 1's skin records, the regression and
// basis parameters, and the radiance written (the triad counts its write too).
double bytes_per_eval(const prt_pose_info& i) {
  const double n2 = double(i.order) * i.order;
  double bytes = double(i.vertex_count) * i.basis_dims * (i.bits / 8);
  if (i.model == PRT_POSE_MODEL_RESIDUAL) bytes += double(i.vertex_count) * PRT_BLOB_PSTR_SKIN_SIZE;
  bytes += 4.0 * (i.pose_dims + 1.0) * i.basis_dims * n2 + 8.0 * i.basis_dims;
  return bytes + 12.0 * i.vertex_count;
}

std::vector<uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// An asset per (runner's backend, case), kept for the run.
class Assets {
 public:
  ~Assets() {
    for (prt_workers* w : workers_) prt_workers_destroy(w);
    for (prt_asset* a : assets_) prt_asset_destroy(a);
  }
  prt_asset* get(const Runner& runner, Case& c, prt_workers** workers, std::string* why) {
    prt_context* ctx = contexts_.usable(runner.backend, why);
    if (!ctx) return nullptr;
    const std::lock_guard<std::mutex> lock(mutex_);
    prt_asset* asset = nullptr;
    if (prt_asset_load_memory_borrowed(ctx, c.bytes.data(), c.bytes.size(), PRT_VALIDATE_FULL,
                                       &asset) != PRT_OK) {
      *why = std::string("load failed: ") + prt_context_last_message(ctx);
      return nullptr;
    }
    assets_.push_back(asset);
    *workers = nullptr;
    if (runner.threads > 1) {
      prt_workers_desc desc = prt::sized<prt_workers_desc>();
      desc.thread_count = runner.threads;
      if (prt_workers_create(ctx, &desc, workers) != PRT_OK) {
        *why = "no workers";
        return nullptr;
      }
      workers_.push_back(*workers);
    }
    return asset;
  }

 private:
  prt_bench::BackendContexts contexts_;
  std::mutex mutex_;
  std::vector<prt_asset*> assets_;
  std::vector<prt_workers*> workers_;
} g_assets;

void BM_StreamTriad(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  g_figures.triad[threads] = prt_bench::stream_triad(state, threads);
}
BENCHMARK(BM_StreamTriad)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void evaluate(benchmark::State& state, Case& c, int runner_index) {
  const Runner& runner = kRunners[runner_index];
  std::string why;
  prt_workers* workers = nullptr;
  prt_asset* asset = g_assets.get(runner, c, &workers, &why);
  if (!asset) {
    c.skipped[runner_index] = why;
    state.SkipWithError(why.c_str());
    return;
  }
  // A pose away from the bind pose: each joint's bind rotation turned a little.
  const uint32_t joints = c.info.joint_count;
  std::vector<float> rotations(4 * size_t(joints));
  prt_pose_bind_pose(asset, rotations.data(), nullptr, nullptr);
  for (uint32_t j = 0; j < joints; ++j) rotations[4 * j] += 0.1f * std::sin(float(j));
  prt_pose_input pose = prt::sized<prt_pose_input>();
  pose.joint_rotations = rotations.data();
  std::vector<float> light(size_t(c.info.order) * c.info.order * 3);
  for (size_t i = 0; i < light.size(); ++i) light[i] = std::cos(0.7f * float(i));
  prt_pose_light l = prt::sized<prt_pose_light>();
  l.light_rgb = light.data();
  std::vector<float> out(size_t(c.info.vertex_count) * 3);
  const prt_backend backend = kBackends[runner.backend].backend;
  const uint32_t n = c.info.vertex_count;
  const double process_start = prt_bench::process_cpu_seconds();
  const prt_bench::Timed timed = prt_bench::time_shading(
      state,
      [&] {
        return workers
                   ? prt_pose_shade_workers(workers, asset, backend, &pose, &l, 0, n, out.data())
                   : prt_pose_shade(asset, backend, &pose, &l, 0, n, out.data());
      },
      out.data());
  // Over workers the CPU time is the process's: every thread of the pool works.
  const double cpu = workers ? prt_bench::process_cpu_seconds() - process_start : timed.cpu_seconds;
  const double evals = double(state.iterations());
  state.counters["evals/s"] = benchmark::Counter(evals, benchmark::Counter::kIsRate);
  state.SetBytesProcessed(static_cast<int64_t>(evals * c.bytes_per_eval));
  const std::lock_guard<std::mutex> lock(g_figures.mutex);
  if (timed.seconds > 0.0 && cpu > 0.0)
    c.rate[runner_index] = {evals / timed.seconds, evals * runner.threads / cpu};
}

// The synthetic paper-scale section of pose/pose_blob.hpp for a model.
Case synthetic(uint32_t model) {
  Case c;
  c.name = std::string("synthetic ") + (model == PRT_POSE_MODEL_RESIDUAL ? "residual" : "direct");
  c.bytes = prt_test::pose_blob(prt_test::random_section(kOrder, kPaperVertices, kJoints, kPoseDims,
                                                         kBasisDims, kBits, model, 1));
  return c;
}

// Fills a case's info from its blob; false when it does not load as a pose asset.
bool describe(Case& c) {
  prt_context* ctx = nullptr;
  prt_context_desc desc = prt::sized<prt_context_desc>();
  if (prt_context_create(&desc, &ctx) != PRT_OK) return false;
  prt_asset* asset = nullptr;
  bool ok = prt_asset_load_memory_borrowed(ctx, c.bytes.data(), c.bytes.size(), PRT_VALIDATE_FULL,
                                           &asset) == PRT_OK;
  c.info = prt::sized<prt_pose_info>();
  ok = ok && prt_pose_get_info(asset, &c.info) == PRT_OK;
  prt_asset_destroy(asset);
  prt_context_destroy(ctx);
  c.bytes_per_eval = bytes_per_eval(c.info);
  return ok;
}

void register_cases() {
  std::vector<Case> cases{synthetic(PRT_POSE_MODEL_DIRECT), synthetic(PRT_POSE_MODEL_RESIDUAL)};
  if (const char* list = std::getenv("PRT_POSE_BENCH_BLOBS")) {
    std::string paths = list;
    for (size_t at = 0; at <= paths.size();) {
      const size_t end = std::min(paths.find(':', at), paths.size());
      const std::string path = paths.substr(at, end - at);
      at = end + 1;
      if (path.empty()) continue;
      Case c;
      c.name = path.substr(path.find_last_of('/') + 1);
      c.bytes = read_file(path);
      if (c.bytes.empty())
        std::fprintf(stderr, "PRT_POSE_BENCH_BLOBS: cannot read %s\n", path.c_str());
      if (!c.bytes.empty()) cases.push_back(std::move(c));
    }
  }
  for (Case& c : cases) {
    if (!describe(c)) {
      std::fprintf(stderr, "%s: not a pose asset, skipped\n", c.name.c_str());
      continue;
    }
    g_figures.cases.push_back(std::make_unique<Case>(std::move(c)));
    Case* stored = g_figures.cases.back().get();
    for (int r = 0; r < kRunnerCount; ++r) {
      const std::string name = "Shade/" + stored->name + "/" + kRunners[r].name;
      benchmark::RegisterBenchmark(
          name.c_str(), [stored, r](benchmark::State& state) { evaluate(state, *stored, r); })
          ->UseRealTime()
          ->MinTime(0.3)
          ->Unit(benchmark::kMicrosecond);
    }
  }
}

void print_summary() {
  const Figures& f = g_figures;
  std::printf(
      "\nsummary: pose evaluations (prt_pose_shade of every vertex from joint rotations)\n");
  std::printf(
      "  memory bandwidth (triad), by CPU time: %.2f GB/s on 1 thread, %.2f GB/s on 2; "
      "by wall clock: %.2f, %.2f\n",
      f.triad[1].cpu * 1e-9, f.triad[2].cpu * 1e-9, f.triad[1].wall * 1e-9, f.triad[2].wall * 1e-9);
  for (const bool by_cpu : {true, false}) {
    std::printf("\n  by %s: evaluations/s (ms each), %% of the triad on as many threads\n",
                by_cpu ? "CPU time (per core)" : "wall clock");
    for (const auto& c : f.cases) {
      const prt_pose_info& i = c->info;
      std::printf("  %-34s V %u, J %u, p %u, q %u, order %u, %u bits, %s, %.0f KB/eval\n",
                  c->name.c_str(), i.vertex_count, i.joint_count, i.pose_dims, i.basis_dims,
                  i.order, i.bits, i.model == PRT_POSE_MODEL_RESIDUAL ? "residual" : "direct",
                  c->bytes_per_eval / 1024.0);
      for (int r = 0; r < kRunnerCount; ++r) {
        const double evals = by_cpu ? c->rate[r].cpu : c->rate[r].wall;
        const double triad =
            by_cpu ? f.triad[kRunners[r].threads].cpu : f.triad[kRunners[r].threads].wall;
        if (evals <= 0.0) {
          std::printf("    %-22s -  %s\n", kRunners[r].name, c->skipped[r].c_str());
          continue;
        }
        std::printf("    %-22s %9.0f /s  (%7.3f ms)  %5.1f %% of the triad\n", kRunners[r].name,
                    evals, 1e3 / evals,
                    triad > 0.0 ? 100.0 * evals * c->bytes_per_eval / triad : 0.0);
      }
    }
  }
  std::printf(
      "\n  (by CPU time, a workers rate is evaluations per process CPU-second times the threads:\n"
      "   what the pool does with that many cores to itself)\n");
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_cases();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary();
  return 0;
}
