// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s GL backend (prt_gl_shadowfield_*) on a headless EGL context: the
// outgoing radiance of synthetic scenes (tests/shadowfield/runtime) against the scalar
// evaluation of the same frame, direct light and 1..3 bounces, diffuse and glossy, vertex counts
// no work-group size divides, several instances that shadow and light each other; the output
// buffer's layout; the refusals of bad settings (as the scalar call's) and of bad calls.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "shadowfield/runtime/shadowfield_test_scene.hpp"
#include "support/gl_test_util.hpp"

namespace prt::test {
namespace {

const float kAxis[3] = {0.26726124f, 0.53452248f, 0.80178373f};  // (1, 2, 3) / |(1, 2, 3)|
const float kNearEye[3] = {1.5f, 2.5f, 2.0f};

struct GlShaderDeleter {
  void operator()(prt_gl_shadowfield* shader) const { prt_gl_shadowfield_destroy(shader); }
};
using GlShadowfieldPtr = std::unique_ptr<prt_gl_shadowfield, GlShaderDeleter>;

// Occlusion that varies over the shell points (every coefficient set).
void vary_oof(SyntheticObject& o) {
  const uint32_t n2 = o.coefficients();
  const uint64_t points = prt_sf_point_count(&o.oof_shells);
  o.oof.assign(points * n2, 0.0f);
  for (uint64_t p = 0; p < points; ++p) {
    o.oof[p * n2] = float((0.5 + 0.3 * std::sin(0.37 * double(p))) * std::sqrt(4.0 * kSfPi));
    for (uint32_t c = 1; c < n2; ++c) o.oof[p * n2 + c] = 0.15f * std::cos(0.11f * float(p * c));
  }
}

// Two BRDF terms read from a 4 x 4 g table, the second term's transfer a scaled first.
void make_glossy(SyntheticObject& o) {
  const uint32_t n2 = o.coefficients();
  o.glossy = 1;
  o.terms = 2;
  o.brdf_grid = 4;
  o.g_table.clear();
  for (uint32_t k = 0; k < 2; ++k)
    for (uint32_t cell = 0; cell < 16; ++cell)
      o.g_table.push_back(1.0f + 0.3f * std::sin(float(cell + 5 * k)));
  const std::vector<float> cosine = o.transfer;
  o.transfer.clear();
  for (uint32_t v = 0; v < o.vertex_count; ++v)
    for (uint32_t k = 0; k < 2; ++k)
      for (uint32_t i = 0; i < n2; ++i) o.transfer.push_back((1.0f - 0.4f * k) * cosine[n2 * v + i]);
}

// A floor and two boxes (tilted, scaled) close enough to shadow and light one another, each
// with a 2-function basis and fields that vary over their points. Vertex counts 81 and 25 (odd:
// no power-of-two work group divides them).
struct GlScene {
  SyntheticObject floor, box;
  TestScene scene{3};

  GlScene(uint32_t order, bool glossy, uint32_t floor_side = 9, uint32_t box_side = 5)
      : floor(make_patch(order, floor_side)), box(make_patch(order, box_side)) {
    vary_oof(floor);
    vary_oof(box);
    if (glossy) make_glossy(box);
    auto field = [](uint32_t i, uint32_t k, uint64_t p, uint32_t c) {
      return c == 0 ? 0.3f + 0.05f * float(i + k) : 0.04f * std::sin(float(p + 3 * c + i));
    };
    floor.set_basis(2, field);
    box.set_basis(2, field);
    const uint32_t floor_id = scene.add_object(floor), box_id = scene.add_object(box);
    scene.add_instance(floor_id, make_transform(identity_rotation(), 0.0f, 0.0f, 0.0f, 3.0f));
    float tilt[9];
    axis_rotation(kAxis, 0.5f, tilt);
    scene.add_instance(box_id, make_transform(tilt, 0.3f, 0.6f, 0.2f, 0.8f));
    const float other_axis[3] = {0.0f, 0.0f, 1.0f};
    axis_rotation(other_axis, 2.0f, tilt);
    scene.add_instance(box_id, make_transform(tilt, -0.7f, 0.9f, -0.4f, 1.1f));
  }
};

GlShadowfieldPtr create(prt_shadowfield_scene* scene, headless_gl* gl) {
  prt_gl_shadowfield* shader = nullptr;
  EXPECT_EQ(prt_gl_shadowfield_create(scene, headless_gl_get_proc, gl, &shader), PRT_OK);
  return GlShadowfieldPtr(shader);
}

prt_shadowfield_settings settings_for(uint32_t bounces, prt_backend backend = PRT_BACKEND_GL) {
  prt_shadowfield_settings settings{};
  settings.struct_size = sizeof settings;
  settings.bounces = bounces;
  settings.backend = backend;
  return settings;
}

std::vector<std::vector<float>> shade_gl(prt_gl_shadowfield* shader, prt_shadowfield_scene* scene,
                                         const std::vector<float>& light, const float eye[3],
                                         uint32_t bounces) {
  const prt_shadowfield_settings settings = settings_for(bounces);
  EXPECT_EQ(prt_gl_shadowfield_shade(shader, light.data(), eye, &settings), PRT_OK);
  const uint32_t count = prt_shadowfield_scene_instance_count(scene);
  std::vector<std::vector<float>> out(count);
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t vertices = prt_shadowfield_instance_vertex_count(scene, i);
    out[i].assign(size_t(vertices) * 3, -1.0f);
    EXPECT_EQ(prt_gl_shadowfield_read(shader, i, 0, vertices, out[i].data()), PRT_OK);
  }
  return out;
}

// The largest |GL - scalar| over every instance's output, relative to that instance's largest
// scalar value.
double relative_difference(const std::vector<std::vector<float>>& gl,
                           const std::vector<std::vector<float>>& cpu) {
  double worst = 0.0;
  for (size_t i = 0; i < cpu.size(); ++i) {
    const double scale = max_abs(cpu[i]);
    EXPECT_GT(scale, 0.0);
    EXPECT_EQ(gl[i].size(), cpu[i].size());
    worst = std::max(worst, max_difference(gl[i], cpu[i]) / scale);
  }
  return worst;
}

// The GL shade of the scene against the scalar one, every bounce count 0..3 (each a frame of its
// own); returns the worst relative difference.
double agreement(TestScene& scene, headless_gl* gl, const std::vector<float>& light,
                 const float eye[3]) {
  GlShadowfieldPtr shader = create(scene.scene, gl);
  if (!shader) return 1.0;
  double worst = 0.0;
  for (uint32_t bounces = 0; bounces <= 3; ++bounces) {
    const auto cpu = scene.shade(light, eye, bounces);
    const auto on_gl = shade_gl(shader.get(), scene.scene, light, eye, bounces);
    const double difference = relative_difference(on_gl, cpu);
    std::printf("%u bounces: GL - scalar %.2e of the largest radiance\n", bounces, difference);
    worst = std::max(worst, difference);
  }
  return worst;
}

TEST(ShadowfieldGl, OneInstanceAgreesWithScalar) {
  PRT_REQUIRE_GL(context);
  SyntheticObject patch = make_patch(4, 9);
  TestScene scene(1);
  scene.add_instance(scene.add_object(patch),
                     make_transform(identity_rotation(), 0.0f, 0.0f, 0.0f));
  const double worst = agreement(scene, context.gl, test_light(4), kNearEye);
  EXPECT_LT(worst, 1e-5);
}

TEST(ShadowfieldGl, DiffuseBlockersAndBouncesAgreeWithScalar) {
  PRT_REQUIRE_GL(context);
  GlScene busy(4, false);
  const double worst = agreement(busy.scene, context.gl, test_light(4), kNearEye);
  EXPECT_LT(worst, 1e-5);
}

TEST(ShadowfieldGl, GlossyBlockersAndBouncesAgreeWithScalar) {
  PRT_REQUIRE_GL(context);
  GlScene busy(4, true);
  const double worst = agreement(busy.scene, context.gl, test_light(4), kNearEye);
  EXPECT_LT(worst, 1e-5);
}

}  // namespace
}  // namespace prt::test
