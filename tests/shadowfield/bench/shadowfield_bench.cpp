// SPDX-License-Identifier: MIT
// prt_bench_shadowfield: the cost of technique `shadowfield`'s scene on the backend AUTO picks
// (SIMD where usable), one thread, on synthetic objects with the default field sizes (OOF 16
// shells of 6 x 16 x 16 points, SRF 8 shells of 6 x 8 x 8, N = 16, SH order 4):
//   Direct/b/product: pass 0 of a 32 x 32 receiver under b blockers, blockers combined by
//              triple products (0) or the log-space product (1); the counter is the time per
//              receiver vertex per blocker: where the log product's line falls below the triple
//              product's is the blocker count from which it pays;
//   Bounce/k:  pass 1 of that receiver lit by one source of k BRDF terms; the time per vertex
//              per source (the source's field read at the vertex, rotated, dotted with T);
//   Project/k: one source's basis weights and field (its cost does not depend on receivers);
//   Frame:     a 64 x 64 floor and a 2,025-vertex glossy object (K = 4), 3 bounces, the whole
//              frame on 1 thread and on a pool of 2 (wall clock): the teapot-on-floor
//              budget is 16 ms on 2 cores.
// Printed, never asserted.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "shadowfield/runtime/shadowfield_test_scene.hpp"

namespace prt::test {
namespace {

prt_sf_shells grid(float radius, uint32_t shells, uint32_t face) {
  prt_sf_shells g = default_shells(radius);
  g.shells = shells;
  g.face_size = face;
  return g;
}

// A side x side patch with the default field sizes, K terms, fields from formulas.
SyntheticObject make_object(uint32_t side, uint32_t terms) {
  SyntheticObject o = make_patch(4, side);
  if (terms > 1) {
    o.glossy = 1;
    o.terms = terms;
    o.brdf_grid = 32;
    o.g_table.assign(size_t(terms) * 32 * 32, 0.5f);
    const std::vector<float> cosine = o.transfer;
    o.transfer.clear();
    for (uint32_t v = 0; v < o.vertex_count; ++v)
      for (uint32_t k = 0; k < terms; ++k)
        o.transfer.insert(o.transfer.end(), cosine.begin() + 16 * v, cosine.begin() + 16 * (v + 1));
  }
  o.oof_shells = grid(0.75f, 16, 16);
  o.srf_shells = grid(0.75f, 8, 8);
  const uint64_t points = prt_sf_point_count(&o.oof_shells);
  o.oof.resize(points * 16);
  for (size_t e = 0; e < o.oof.size(); ++e) o.oof[e] = 0.1f * std::sin(0.01f * float(e));
  for (uint64_t p = 0; p < points; ++p) o.oof[p * 16] = 2.0f;
  o.set_basis(2, [](uint32_t, uint32_t, uint64_t p, uint32_t c) {
    return c == 0 ? 0.3f : 0.01f * std::sin(float(p + c));
  });
  // N = 16: the closed-form inverse above is for N <= 2; the bench needs sizes, not accuracy.
  o.basis_size = 16;
  o.basis.assign(size_t(16) * o.vertex_count, 0.1f);
  o.basis_inverse.assign(16 * 16, 0.0f);
  for (int i = 0; i < 16; ++i) o.basis_inverse[i * 17] = 1.0f;
  o.srf.assign(size_t(16) * terms * prt_sf_point_count(&o.srf_shells) * 16, 0.01f);
  return o;
}

const float kEye[3] = {1.0f, 5.0f, 2.0f};

void prepare(TestScene& s, uint32_t bounces) {
  const std::vector<float> light = test_light(4);
  prt_shadowfield_settings settings{};
  settings.struct_size = sizeof settings;
  settings.bounces = bounces;
  prt_shadowfield_prepare(s.scene, light.data(), kEye, &settings);
}

void BM_Direct(benchmark::State& state) {
  const uint32_t blockers = uint32_t(state.range(0));
  SyntheticObject receiver = make_object(32, 1), blocker = make_object(4, 1);
  TestScene s(blockers + 1);
  prt_shadowfield_scene_set_product(s.scene, prt_shadowfield_product(state.range(1)));
  s.add_instance(s.add_object(receiver), make_transform(identity_rotation(), 0, 0, 0));
  const uint32_t blocker_id = s.add_object(blocker);
  for (uint32_t b = 0; b < blockers; ++b)
    s.add_instance(blocker_id, make_transform(identity_rotation(), 0.2f * b, 1.0f, 0.1f * b));
  prepare(s, 0);
  for (auto _ : state) prt_shadowfield_gather(s.scene, 0, 0, 0, receiver.vertex_count);
  state.counters["s_per_vertex_blocker"] = benchmark::Counter(
      double(receiver.vertex_count) * blockers,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_Direct)
    ->ArgNames({"blockers", "product"})
    ->ArgsProduct({{1, 2, 4, 8, 16, 32},
                   {PRT_SHADOWFIELD_PRODUCT_TRIPLE, PRT_SHADOWFIELD_PRODUCT_LOG}})
    ->Unit(benchmark::kMicrosecond);

// A receiver and one source of `terms` terms, prepared for one bounce, the source projected.
struct BounceScene {
  SyntheticObject receiver = make_object(32, 1), source;
  TestScene scene{2};
  explicit BounceScene(uint32_t terms) : source(make_object(4, terms)) {
    scene.add_instance(scene.add_object(receiver), make_transform(identity_rotation(), 0, 0, 0));
    scene.add_instance(scene.add_object(source), make_transform(identity_rotation(), 0, 1, 0));
    prepare(scene, 1);
    prt_shadowfield_gather(scene.scene, 0, 1, 0, source.vertex_count);
    prt_shadowfield_project(scene.scene, 0, 1, 1);
  }
};

void BM_Bounce(benchmark::State& state) {
  BounceScene b(uint32_t(state.range(0)));
  for (auto _ : state) prt_shadowfield_gather(b.scene.scene, 1, 0, 0, b.receiver.vertex_count);
  state.counters["s_per_vertex_source"] = benchmark::Counter(
      double(b.receiver.vertex_count),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_Bounce)->Arg(1)->Arg(4)->Unit(benchmark::kMicrosecond);

void BM_Project(benchmark::State& state) {
  BounceScene b(uint32_t(state.range(0)));
  for (auto _ : state) prt_shadowfield_project(b.scene.scene, 0, 1, 1);
}
BENCHMARK(BM_Project)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

void BM_Frame(benchmark::State& state) {
  SyntheticObject floor = make_object(64, 1), object = make_object(45, 4);
  TestScene s(2);
  const uint32_t floor_id = s.add_object(floor), object_id = s.add_object(object);
  s.add_instance(floor_id, make_transform(identity_rotation(), 0, 0, 0, 4.0f));
  s.add_instance(object_id, make_transform(identity_rotation(), 0, 0.8f, 0));
  const std::vector<float> light = test_light(4);
  std::vector<float> a(size_t(floor.vertex_count) * 3), b(size_t(object.vertex_count) * 3);
  float* out[2] = {a.data(), b.data()};
  prt_shadowfield_settings settings{};
  settings.struct_size = sizeof settings;
  settings.bounces = 3;
  const uint32_t threads = uint32_t(state.range(0));
  prt_workers* workers = nullptr;
  if (threads > 1) {
    prt_workers_desc desc{};
    desc.struct_size = sizeof desc;
    desc.thread_count = threads;
    prt_workers_create(s.context, &desc, &workers);
  }
  for (auto _ : state) {
    if (workers)
      prt_shadowfield_shade_workers(workers, s.scene, light.data(), kEye, &settings, out);
    else
      prt_shadowfield_shade(s.scene, light.data(), kEye, &settings, out);
  }
  prt_workers_destroy(workers);
}
BENCHMARK(BM_Frame)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace prt::test

BENCHMARK_MAIN();
