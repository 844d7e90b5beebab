// SPDX-License-Identifier: MIT
// A `shadowfield` scene of synthetic objects for the runtime's tests: a context, the scene, and
// shading every instance into vectors.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "shadowfield/runtime/shadowfield_synthetic.hpp"

extern "C" {
#include "shadowfield_scene.h"
}

namespace prt::test {

struct TestScene {
  prt_context* context = nullptr;
  prt_shadowfield_scene* scene = nullptr;

  explicit TestScene(uint32_t max_instances) {
    EXPECT_EQ(prt_context_create(nullptr, &context), PRT_OK);
    EXPECT_EQ(prt_shadowfield_scene_create(context, max_instances, &scene), PRT_OK);
  }
  ~TestScene() {
    prt_shadowfield_scene_destroy(scene);
    prt_context_destroy(context);
  }
  TestScene(const TestScene&) = delete;
  TestScene& operator=(const TestScene&) = delete;

  uint32_t add_object(SyntheticObject& object) {
    uint32_t id = ~0u;
    EXPECT_EQ(prt_internal_sf_scene_add_object(scene, object.view(), &id), PRT_OK)
        << prt_context_last_message(context);
    return id;
  }

  uint32_t add_instance(uint32_t object, const prt_shadowfield_transform& transform) {
    uint32_t id = ~0u;
    EXPECT_EQ(prt_shadowfield_scene_add_instance(scene, object, &transform, &id), PRT_OK)
        << prt_context_last_message(context);
    return id;
  }

  // Every instance's outgoing radiance (V x 3 each), bounce light at probes `probe_spacing`
  // apart (0: per vertex).
  std::vector<std::vector<float>> shade(const std::vector<float>& light, const float eye[3],
                                        uint32_t bounces, float probe_spacing = 0.0f) {
    const uint32_t count = prt_shadowfield_scene_instance_count(scene);
    std::vector<std::vector<float>> out(count);
    std::vector<float*> pointers(count);
    for (uint32_t i = 0; i < count; ++i) {
      out[i].assign(size_t(prt_shadowfield_instance_vertex_count(scene, i)) * 3, -1.0f);
      pointers[i] = out[i].data();
    }
    prt_shadowfield_settings settings{};
    settings.struct_size = sizeof settings;
    settings.bounces = bounces;
    settings.bounce_probe_spacing = probe_spacing;
    EXPECT_EQ(prt_shadowfield_shade(scene, light.data(), eye, &settings, pointers.data()), PRT_OK)
        << prt_context_last_message(context);
    return out;
  }

  // The radiance after `through_pass` passes of the frame shade() last prepared.
  std::vector<float> pass_output(uint32_t instance, uint32_t through_pass) {
    const uint32_t vertices = prt_shadowfield_instance_vertex_count(scene, instance);
    std::vector<float> out(size_t(vertices) * 3);
    EXPECT_EQ(prt_shadowfield_output(scene, instance, through_pass, 0, vertices, out.data()),
              PRT_OK);
    return out;
  }
};

// A light of order n with every coefficient set, mostly a bright constant (RGB).
inline std::vector<float> test_light(uint32_t order, float phase = 0.0f) {
  std::vector<float> light(order * order * 3);
  for (uint32_t i = 0; i < order * order; ++i)
    for (uint32_t c = 0; c < 3; ++c)
      light[3 * i + c] =
          i == 0 ? 3.0f + float(c) : 0.6f * std::sin(1.3f * float(i) + float(c) + phase);
  return light;
}

inline double max_abs(const std::vector<float>& values) {
  double worst = 0.0;
  for (const float v : values) worst = std::max(worst, double(std::fabs(v)));
  return worst;
}

inline double max_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0.0;
  for (size_t e = 0; e < a.size(); ++e) worst = std::max(worst, double(std::fabs(a[e] - b[e])));
  return worst;
}

// Checks that every field point a cell of `source`'s SRF grid reads holds what casting the whole
// field (`whole`, all three planes) gives; the values compared.
inline uint64_t expect_cell_points_cast(const prt_sf_instance& source, const prt_sf_object* object,
                                        const std::vector<float>& whole, const prt_sf_cell& cell,
                                        uint32_t n2) {
  const uint64_t points = prt_sf_point_count(&object->srf_shells);
  prt_sf_lookup lookup{};
  prt_sf_cell_lookup(&object->srf_shells, &cell, &lookup);
  uint64_t checked = 0;
  for (uint32_t e = 0; e < lookup.count; ++e)
    for (uint32_t c = 0; c < 3; ++c)
      for (uint32_t k = 0; k < n2; ++k) {
        const size_t at = (c * points + lookup.index[e]) * n2 + k;
        EXPECT_EQ(source.field[at], whole[at]) << "point " << lookup.index[e];
        ++checked;
      }
  return checked;
}

}  // namespace prt::test
