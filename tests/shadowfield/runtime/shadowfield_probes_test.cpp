// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s bounce probes (prt_shadowfield_settings::bounce_probe_spacing,
// docs/shadowfield/design.md, "Bounce probes") on synthetic objects: a vertex on the probes' grid
// gets the light the per-vertex gather gives it, one between corners their trilinear mean (every
// vertex of a patch has the same transfer, so the mean of the lights is the mean of the
// incident values), above a source and interpenetrating it; the staged calls, a pool and a frame
// without the probes' first stage give the one call's bits; 50 instances stay finite and near the
// per-vertex frame; the settings' checks and the grids at extreme spacings.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "shadowfield/runtime/shadowfield_test_scene.hpp"

namespace prt::test {
namespace {

const float kEye[3] = {1.5f, 2.5f, 2.0f};

// A patch of `terms` glossy terms, each the cosine transfer scaled down by term.
void make_glossy(SyntheticObject& o, uint32_t terms) {
  o.glossy = 1;
  o.terms = terms;
  o.brdf_grid = 4;
  o.g_table.clear();
  for (uint32_t k = 0; k < terms; ++k)
    for (uint32_t cell = 0; cell < 16; ++cell)
      o.g_table.push_back(1.0f + 0.3f * std::sin(float(cell + 5 * k)));
  const std::vector<float> cosine = o.transfer;
  o.transfer.clear();
  for (uint32_t v = 0; v < o.vertex_count; ++v)
    for (uint32_t k = 0; k < terms; ++k)
      for (uint32_t i = 0; i < 16; ++i)
        o.transfer.push_back((1.0f - 0.2f * k) * cosine[16 * v + i]);
}

// A diffuse 9 x 9 floor (vertices 1/8 apart in its frame, scaled by 3) and a glossy 9 x 9 patch
// of 3 terms tilted above it, each lighting the other through fields that change from point to
// point. At spacing 0.25 each has a 5 x 5 grid of probes: every other vertex is a corner.
struct ProbeScene {
  SyntheticObject floor = make_patch(4, 9), source = make_patch(4, 9);
  TestScene scene{2};

  // interpenetrating: the source at the floor's centre, unturned and unscaled, so both share
  // every position and each one's probes and vertices lie inside the other's inner shell, one at
  // its very centre.
  explicit ProbeScene(bool interpenetrating = false) {
    make_glossy(source, 3);
    auto field = [](uint32_t i, uint32_t k, uint64_t p, uint32_t c) {
      return c == 0 ? 0.3f + 0.05f * float(i + k) : 0.04f * std::sin(float(p + 3 * c + i));
    };
    floor.set_basis(2, field);
    source.set_basis(2, field);
    const uint32_t floor_id = scene.add_object(floor), source_id = scene.add_object(source);
    scene.add_instance(floor_id, make_transform(identity_rotation(), 0.0f, 0.0f, 0.0f, 3.0f));
    const float axis[3] = {0.36f, 0.8f, 0.48f};
    float tilt[9];
    axis_rotation(axis, 2.6f, tilt);
    if (interpenetrating)
      scene.add_instance(source_id, make_transform(identity_rotation(), 0.0f, 0.0f, 0.0f, 3.0f));
    else
      scene.add_instance(source_id, make_transform(tilt, 0.3f, 0.7f, 0.2f, 0.8f));
  }

  prt_shadowfield_settings settings(float spacing, uint32_t bounces) const {
    prt_shadowfield_settings s{};
    s.struct_size = sizeof s;
    s.bounces = bounces;
    s.backend = PRT_BACKEND_CPU;
    s.bounce_probe_spacing = spacing;
    return s;
  }

  std::vector<std::vector<float>> shade(float spacing, uint32_t bounces) {
    std::vector<std::vector<float>> out(2);
    std::vector<float*> pointers(2);
    for (uint32_t i = 0; i < 2; ++i) {
      out[i].assign(size_t(prt_shadowfield_instance_vertex_count(scene.scene, i)) * 3, -1.0f);
      pointers[i] = out[i].data();
    }
    const prt_shadowfield_settings s = settings(spacing, bounces);
    EXPECT_EQ(prt_shadowfield_shade(scene.scene, test_light(4).data(), kEye, &s, pointers.data()),
              PRT_OK)
        << prt_context_last_message(scene.context);
    return out;
  }

  // L_k,c of instance i's vertices in `pass` of the last frame ([(v K + k) 3 + c]).
  std::vector<float> incident(uint32_t i, uint32_t pass) const {
    const prt_sf_instance& instance = scene.scene->instances[i];
    const prt_sf_object* object = scene.scene->objects[instance.object];
    const size_t floats = size_t(object->vertex_count) * object->terms * 3;
    const float* at = instance.incident + pass * floats;
    return std::vector<float>(at, at + floats);
  }
};

// Vertex (i, j) of a 9 x 9 patch on a grid of every other vertex: the mean of its cell's corners'
// values, each `width` floats in `per_vertex`.
std::vector<float> corner_means(const std::vector<float>& per_vertex, size_t width) {
  std::vector<float> out(per_vertex.size());
  for (uint32_t j = 0; j < 9; ++j)
    for (uint32_t i = 0; i < 9; ++i) {
      const uint32_t i0 = i / 2 * 2, j0 = j / 2 * 2;
      const uint32_t i1 = i % 2 ? i0 + 2 : i0, j1 = j % 2 ? j0 + 2 : j0;
      for (size_t e = 0; e < width; ++e) {
        double sum = 0.0;
        for (const uint32_t a : {i0, i1})
          for (const uint32_t b : {j0, j1}) sum += per_vertex[(b * 9 + a) * width + e];
        out[(j * 9 + i) * width + e] = float(sum / 4.0);
      }
    }
  return out;
}

class ShadowfieldProbesPlaced : public ::testing::TestWithParam<bool> {};

TEST_P(ShadowfieldProbesPlaced, VerticesOnTheGridKeepTheirLightAndOthersTakeTheirCornersMean) {
  ProbeScene s(GetParam());
  s.shade(0.0f, 1);
  const std::vector<float> floor_exact = s.incident(0, 1), source_exact = s.incident(1, 1);
  const std::vector<float> floor_direct = s.incident(0, 0);
  s.shade(0.25f, 1);
  ASSERT_EQ(prt_shadowfield_instance_probe_count(s.scene.scene, 0), 25u);
  ASSERT_EQ(prt_shadowfield_instance_probe_count(s.scene.scene, 1), 25u);
  // The direct light is never interpolated: the same bits.
  EXPECT_EQ(s.incident(0, 0), floor_direct);
  // The floor's diffuse term (read with its transfer) and the source's 3 glossy terms (the light
  // read whole, then dotted with each term).
  const std::vector<float> expected[2] = {corner_means(floor_exact, 3),
                                          corner_means(source_exact, 9)};
  for (uint32_t i = 0; i < 2; ++i) {
    const std::vector<float> probed = s.incident(i, 1);
    const double difference = max_difference(probed, expected[i]);
    std::printf("instance %u: max difference %.2e of %.3f\n", i, difference, max_abs(expected[i]));
    EXPECT_GT(max_abs(expected[i]), 0.01);  // lit
    EXPECT_LT(difference, 4e-7 * max_abs(expected[i])) << "instance " << i;
  }
  // And the corners' lights differ: the means are not of one value.
  EXPECT_GT(max_difference(floor_exact, corner_means(floor_exact, 3)), 1e-3 * max_abs(floor_exact));
}

// Above the floor, and interpenetrating it (receivers inside the source's inner shell).
INSTANTIATE_TEST_SUITE_P(Placements, ShadowfieldProbesPlaced, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? "Interpenetrating" : "Above";
                         });

TEST(ShadowfieldProbes, FiftyInstancesStayFiniteAndNearThePerVertexFrame) {
  SyntheticObject patch = make_patch(4, 9);
  patch.set_basis(2, [](uint32_t i, uint32_t, uint64_t p, uint32_t c) {
    return c == 0 ? 0.05f + 0.01f * float(i) : 0.005f * std::sin(float(p + c));
  });
  TestScene s(50);
  const uint32_t object = s.add_object(patch);
  for (uint32_t i = 0; i < 50; ++i) {
    float rotation[9];
    const float axis[3] = {0.6f, 0.0f, 0.8f};
    axis_rotation(axis, 0.3f * float(i), rotation);
    s.add_instance(object, make_transform(rotation, float(i % 7) * 0.9f, float(i / 7) * 0.3f,
                                          float(i % 3) * 0.5f));
  }
  const std::vector<float> light = test_light(4);
  std::vector<std::vector<float>> frames[2];
  for (const float spacing : {0.0f, 0.25f}) {
    std::vector<std::vector<float>>& out = frames[spacing > 0.0f];
    out.assign(50, std::vector<float>(size_t(patch.vertex_count) * 3));
    std::vector<float*> pointers;
    for (auto& o : out) pointers.push_back(o.data());
    prt_shadowfield_settings settings{};
    settings.struct_size = sizeof settings;
    settings.bounces = 3;
    settings.bounce_probe_spacing = spacing;
    ASSERT_EQ(prt_shadowfield_shade(s.scene, light.data(), kEye, &settings, pointers.data()),
              PRT_OK);
  }
  double largest = 0.0, apart = 0.0;
  for (uint32_t i = 0; i < 50; ++i) {
    for (const float v : frames[1][i]) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
    largest = std::max(largest, max_abs(frames[0][i]));
    apart = std::max(apart, max_difference(frames[1][i], frames[0][i]));
  }
  std::printf("50 instances, 3 bounces: probes apart from per vertex by %.3g of %.3g\n", apart,
              largest);
  EXPECT_GT(apart, 0.0);
  EXPECT_LT(apart, 0.025 * largest);  // measured 0.013
}

TEST(ShadowfieldProbes, TheStagesGiveTheOneCallsResult) {
  for (const bool probe_stage_at_pass_0 : {true, false}) {
    ProbeScene s;
    const auto expected = s.shade(0.25f, 2);
    prt_shadowfield_scene* scene = s.scene.scene;
    const prt_shadowfield_settings settings = s.settings(0.25f, 2);
    const std::vector<float> light = test_light(4);
    ASSERT_EQ(prt_shadowfield_prepare(scene, light.data(), kEye, &settings), PRT_OK);
    for (uint32_t pass = 0; pass <= 2; ++pass) {
      // Ranges of 4 probes and 5 vertices in reverse order, as a job system might run them;
      // without pass 0's probe stage the bounces locate their probes themselves.
      for (uint32_t i = 2; i-- > 0;) {
        const uint32_t probes = prt_shadowfield_instance_probe_count(scene, i);
        for (uint32_t first = 0; first < probes && (pass > 0 || probe_stage_at_pass_0);
             first += 4) {
          ASSERT_EQ(
              prt_shadowfield_gather_probes(scene, pass, i, first, std::min(4u, probes - first)),
              PRT_OK);
        }
      }
      for (uint32_t i = 2; i-- > 0;) {
        const uint32_t vertices = prt_shadowfield_instance_vertex_count(scene, i);
        for (uint32_t first = 0; first < vertices; first += 5) {
          ASSERT_EQ(prt_shadowfield_gather(scene, pass, i, first, std::min(5u, vertices - first)),
                    PRT_OK);
        }
      }
      if (pass < 2) {
        ASSERT_EQ(prt_shadowfield_project(scene, pass, 0, 2), PRT_OK);
      }
    }
    for (uint32_t i = 0; i < 2; ++i) {
      std::vector<float> out(expected[i].size());
      ASSERT_EQ(prt_shadowfield_output(scene, i, 2, 0, uint32_t(out.size() / 3), out.data()),
                PRT_OK);
      EXPECT_EQ(out, expected[i]) << "instance " << i << ", stage at pass 0 "
                                  << probe_stage_at_pass_0;
    }
  }
}

TEST(ShadowfieldProbes, AWorkerPoolGivesTheOneThreadResult) {
  ProbeScene s;
  const auto expected = s.shade(0.25f, 3);
  prt_workers_desc desc{};
  desc.struct_size = sizeof desc;
  desc.thread_count = 3;
  prt_workers* workers = nullptr;
  ASSERT_EQ(prt_workers_create(s.scene.context, &desc, &workers), PRT_OK);
  std::vector<std::vector<float>> out = {std::vector<float>(expected[0].size()),
                                         std::vector<float>(expected[1].size())};
  float* pointers[2] = {out[0].data(), out[1].data()};
  const prt_shadowfield_settings settings = s.settings(0.25f, 3);
  EXPECT_EQ(prt_shadowfield_shade_workers(workers, s.scene.scene, test_light(4).data(), kEye,
                                          &settings, pointers),
            PRT_OK);
  EXPECT_EQ(out[0], expected[0]);
  EXPECT_EQ(out[1], expected[1]);
  prt_workers_destroy(workers);
}

// A source's field is cast only where cells read it: after a frame with probes, every point a
// probe's cell reads holds bitwise what casting the whole field gives.
TEST(ShadowfieldProbes, EveryFieldPointAProbeReadsIsCast) {
  ProbeScene s;
  s.shade(0.25f, 2);
  const prt_shadowfield_scene* scene = s.scene.scene;
  const uint32_t n2 = scene->order * scene->order;
  uint64_t checked = 0;
  for (uint32_t r = 0; r < 2; ++r) {
    const prt_sf_instance& receiver = scene->instances[r];
    ASSERT_GT(receiver.probe_count, 0u);
    for (uint32_t q = 0; q < receiver.pair_count; ++q) {
      const prt_sf_pair& pair = scene->pairs[receiver.pair_first + q];
      const prt_sf_instance& source = scene->instances[pair.other];
      const prt_sf_object* object = scene->objects[source.object];
      const uint64_t points = prt_sf_point_count(&object->srf_shells);
      std::vector<float> whole(points * n2 * 3);
      scene->kernels->cast_field(object, source.weights, whole.data(), 0, points);
      for (uint32_t p = 0; p < receiver.probe_count; ++p) {
        ASSERT_EQ(receiver.probe_located[p], scene->frame);
        const prt_sf_cell& cell =
            scene->probe_cells[receiver.probe_cell_first + size_t(p) * receiver.pair_count + q];
        checked += expect_cell_points_cast(source, object, whole, cell, n2);
      }
    }
  }
  EXPECT_GT(checked, 0u);
}

TEST(ShadowfieldProbes, ProbesOnlyWhereTheyAreFewerThanVerticesAndBouncesReadThem) {
  ProbeScene s;
  EXPECT_EQ(prt_shadowfield_instance_probe_count(s.scene.scene, 0), 0u);  // not prepared
  const std::vector<float> light = test_light(4);
  const struct {
    float spacing;
    uint32_t bounces, probes;
  } cases[] = {
      {0.25f, 3, 25},  // a 5 x 5 grid, in the patch's plane only (the corners above weigh 0)
      {0.0f, 3, 0},    // off
      {0.25f, 0, 0},   // no bounce to gather
      {0.125f, 3, 0},  // a corner per vertex: per vertex
      {1e-30f, 3, 0},  // a grid too fine to number: per vertex
      {1e3f, 3, 4},    // one cell: its 4 corners in the plane
      {1e30f, 3, 3},   // the same, but the far corner's weight (below 1e-60) is 0 in floats
      {0.3f, 3, 25},   // 0.3 does not divide 1: the last cells reach past the patch
  };
  for (const auto& c : cases) {
    const prt_shadowfield_settings settings = s.settings(c.spacing, c.bounces);
    ASSERT_EQ(prt_shadowfield_prepare(s.scene.scene, light.data(), kEye, &settings), PRT_OK);
    EXPECT_EQ(prt_shadowfield_instance_probe_count(s.scene.scene, 0), c.probes) << c.spacing;
    const auto out = s.shade(c.spacing, c.bounces);
    for (const auto& o : out)
      for (const float v : o) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << c.spacing;
  }
}

// A game may free an asset before the scene that read it: destroying the scene then frees the
// probes' layouts without reading the object (under ASan, a read would fail here).
TEST(ShadowfieldProbes, DestroyingASceneAfterItsObjectsReadsNoObject) {
  auto patch = std::make_unique<SyntheticObject>(make_patch(4, 9));
  patch->set_basis(1,
                   [](uint32_t, uint32_t, uint64_t, uint32_t c) { return c == 0 ? 0.2f : 0.0f; });
  prt_context* context = nullptr;
  ASSERT_EQ(prt_context_create(nullptr, &context), PRT_OK);
  prt_shadowfield_scene* scene = nullptr;
  ASSERT_EQ(prt_shadowfield_scene_create(context, 2, &scene), PRT_OK);
  uint32_t object = 0, instance = 0;
  ASSERT_EQ(prt_internal_sf_scene_add_object(scene, patch->view(), &object), PRT_OK);
  for (const float x : {0.0f, 0.6f}) {
    const prt_shadowfield_transform t = make_transform(identity_rotation(), x, 0.2f, 0.0f);
    ASSERT_EQ(prt_shadowfield_scene_add_instance(scene, object, &t, &instance), PRT_OK);
  }
  prt_shadowfield_settings settings{};
  settings.struct_size = sizeof settings;
  settings.bounces = 1;
  settings.bounce_probe_spacing = 0.25f;
  ASSERT_EQ(prt_shadowfield_prepare(scene, test_light(4).data(), kEye, &settings), PRT_OK);
  ASSERT_EQ(prt_shadowfield_instance_probe_count(scene, 0), 25u);
  patch.reset();
  prt_shadowfield_scene_destroy(scene);
  prt_context_destroy(context);
}

TEST(ShadowfieldProbes, BadSpacingsAreRefusedAndA10SettingsStructHasNone) {
  ProbeScene s;
  const std::vector<float> light = test_light(4);
  for (const float bad :
       {-0.25f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    const prt_shadowfield_settings settings = s.settings(bad, 1);
    EXPECT_EQ(prt_shadowfield_prepare(s.scene.scene, light.data(), kEye, &settings),
              PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(prt_context_last_message(s.scene.context)).find("bounce_probe_spacing"),
              std::string::npos);
  }
  // A caller built against 1.0's struct: its struct_size ends before the spacing, whatever
  // lies beyond it.
  prt_shadowfield_settings old = s.settings(0.25f, 1);
  old.struct_size = offsetof(prt_shadowfield_settings, bounce_probe_spacing);
  ASSERT_EQ(prt_shadowfield_prepare(s.scene.scene, light.data(), kEye, &old), PRT_OK);
  EXPECT_EQ(prt_shadowfield_instance_probe_count(s.scene.scene, 0), 0u);
  old.struct_size -= 1;
  EXPECT_EQ(prt_shadowfield_prepare(s.scene.scene, light.data(), kEye, &old),
            PRT_ERROR_INVALID_ARGUMENT);
}

TEST(ShadowfieldProbes, TheProbeStageRefusesBadArguments) {
  ProbeScene s;
  EXPECT_EQ(prt_shadowfield_gather_probes(nullptr, 0, 0, 0, 0), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_gather_probes(s.scene.scene, 0, 0, 0, 1), PRT_ERROR_INVALID_OPERATION);
  const prt_shadowfield_settings settings = s.settings(0.25f, 2);
  ASSERT_EQ(prt_shadowfield_prepare(s.scene.scene, test_light(4).data(), kEye, &settings), PRT_OK);
  EXPECT_EQ(prt_shadowfield_gather_probes(s.scene.scene, 3, 0, 0, 1), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_gather_probes(s.scene.scene, 0, 2, 0, 1), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_gather_probes(s.scene.scene, 0, 0, 20, 6), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_gather_probes(s.scene.scene, 0, 0, 26, 0), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_gather_probes(s.scene.scene, 0, 0, 20, 5), PRT_OK);
  EXPECT_EQ(prt_shadowfield_gather_probes(s.scene.scene, 0, 0, 25, 0), PRT_OK);
}

}  // namespace
}  // namespace prt::test
