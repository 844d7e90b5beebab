// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s GL backend (prt_gl_shadowfield_*) on a headless EGL context: the
// outgoing radiance of synthetic scenes (tests/shadowfield/runtime) against the scalar
// evaluation of the same frame, direct light and 1..3 bounces, diffuse and glossy, vertex counts
// no work-group size divides, several instances that shadow and light each other; the output
// buffer's layout; the refusals of bad settings (as the scalar call's) and of bad calls.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
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
      for (uint32_t i = 0; i < n2; ++i)
        o.transfer.push_back((1.0f - 0.4f * k) * cosine[n2 * v + i]);
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
                                         uint32_t bounces, float probe_spacing = 0.0f) {
  prt_shadowfield_settings settings = settings_for(bounces);
  settings.bounce_probe_spacing = probe_spacing;
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
    EXPECT_EQ(gl[i].size(), cpu[i].size());
    if (scale == 0.0) {  // a glossy instance seen from behind: black on both
      EXPECT_EQ(max_difference(gl[i], cpu[i]), 0.0);
      continue;
    }
    worst = std::max(worst, max_difference(gl[i], cpu[i]) / scale);
  }
  return worst;
}

// What GL and the scalar evaluation may differ by, relative to an instance's largest radiance:
// both round every step to float, in different orders (dot products, blocked sums, fused or not)
// and GL's log (the shell) and atan (the g table's map) are not correctly rounded, so they part
// by a few float ulps of the values summed. Measured at most 15 u (u = 2^-24) over these scenes,
// orders 2..6 and 0..3 bounces; held to 32 u.
const double kTolerance = 32.0 * std::ldexp(1.0, -24);

// The GL shade of the scene against the scalar one, every bounce count 0..3 (each a frame of its
// own); returns the worst relative difference. `lit_by_bounces`: the bounces must change the
// result (else they were not tested). probe_spacing: both gather bounce light at probes.
double agreement(TestScene& scene, headless_gl* gl, const std::vector<float>& light,
                 const float eye[3], bool lit_by_bounces = true, float probe_spacing = 0.0f) {
  GlShadowfieldPtr shader = create(scene.scene, gl);
  if (!shader) return 1.0;
  double worst = 0.0;
  std::vector<std::vector<float>> direct;
  for (uint32_t bounces = 0; bounces <= 3; ++bounces) {
    const auto cpu = scene.shade(light, eye, bounces, probe_spacing);
    const auto on_gl = shade_gl(shader.get(), scene.scene, light, eye, bounces, probe_spacing);
    const double difference = relative_difference(on_gl, cpu);
    std::printf("%u bounces: GL - scalar %.2e of the largest radiance\n", bounces, difference);
    worst = std::max(worst, difference);
    if (bounces == 0) direct = cpu;
    if (bounces > 0 && lit_by_bounces) {
      EXPECT_GT(relative_difference(cpu, direct), 1e-3);
    }
  }
  return worst;
}

TEST(ShadowfieldGl, OneInstanceAgreesWithScalar) {
  PRT_REQUIRE_GL(context);
  SyntheticObject patch = make_patch(4, 9);
  TestScene scene(1);
  scene.add_instance(scene.add_object(patch),
                     make_transform(identity_rotation(), 0.0f, 0.0f, 0.0f));
  EXPECT_LT(agreement(scene, context.gl, test_light(4), kNearEye, false), kTolerance);
}

TEST(ShadowfieldGl, DiffuseBlockersAndBouncesAgreeWithScalar) {
  PRT_REQUIRE_GL(context);
  GlScene busy(4, false);
  EXPECT_LT(agreement(busy.scene, context.gl, test_light(4), kNearEye), kTolerance);
}

// Bounce probes (a 3 x 3 grid on the floor and on each box, fewer than their 81 and 25
// vertices), diffuse and glossy boxes; then the per-vertex frame again after them.
TEST(ShadowfieldGl, BounceProbesAgreeWithScalar) {
  PRT_REQUIRE_GL(context);
  for (const bool glossy : {false, true}) {
    GlScene busy(4, glossy);
    EXPECT_LT(agreement(busy.scene, context.gl, test_light(4), kNearEye, true, 0.5f), kTolerance)
        << "glossy " << glossy;
    busy.scene.shade(test_light(4), kNearEye, 3, 0.5f);  // a GL frame leaves none prepared
    EXPECT_EQ(prt_shadowfield_instance_probe_count(busy.scene.scene, 0), 9u);
    EXPECT_EQ(prt_shadowfield_instance_probe_count(busy.scene.scene, 1), 9u);
    EXPECT_LT(agreement(busy.scene, context.gl, test_light(4), kNearEye), kTolerance);
  }
}

TEST(ShadowfieldGl, GlossyBlockersAndBouncesAgreeWithScalar) {
  PRT_REQUIRE_GL(context);
  GlScene busy(4, true);
  EXPECT_LT(agreement(busy.scene, context.gl, test_light(4), kNearEye), kTolerance);
}

TEST(ShadowfieldGl, TheSmallestAndLargestOrdersAgreeWithScalar) {
  PRT_REQUIRE_GL(context);
  for (const uint32_t order : {2u, 6u}) {
    GlScene busy(order, true, 7, 3);
    EXPECT_LT(agreement(busy.scene, context.gl, test_light(order), kNearEye), kTolerance)
        << "order " << order;
  }
}

// The eye at a vertex (its view direction falls back to the normal) and far away.
TEST(ShadowfieldGl, AnEyeAtAVertexOrFarAwayAgreesWithScalar) {
  PRT_REQUIRE_GL(context);
  SyntheticObject patch = make_patch(4, 5);
  make_glossy(patch);
  TestScene scene(1);
  scene.add_instance(scene.add_object(patch),
                     make_transform(identity_rotation(), 0.0f, 0.0f, 0.0f));
  GlShadowfieldPtr shader = create(scene.scene, context.gl);
  ASSERT_TRUE(shader);
  const auto light = test_light(4);
  const float far_eye[3] = {3e4f, 1e5f, -2e4f};
  const float* vertex_7 = &patch.positions[3 * 7];
  for (const float* eye : {vertex_7, far_eye}) {
    const auto cpu = scene.shade(light, eye, 0);
    const auto on_gl = shade_gl(shader.get(), scene.scene, light, eye, 0);
    EXPECT_LT(relative_difference(on_gl, cpu), kTolerance);
  }
}

// A glossy patch whose normals lean about the z axis, n = (sin a, cos a, z_sign * 0): the tangent
// frame that maps the view direction onto the g table (Duff et al., as the baker builds it) takes
// its sign from n.z's sign bit, so -0 and +0 give two different frames. A generated sphere's
// seam has normals with z = -0 (the room's GGX sphere).
SyntheticObject leaning_glossy_patch(float z_sign) {
  SyntheticObject patch = make_patch(4, 5);
  make_glossy(patch);
  for (uint32_t v = 0; v < patch.vertex_count; ++v) {
    const float a = 0.2f + 0.05f * float(v);
    patch.normals[3 * v] = std::sin(a);
    patch.normals[3 * v + 1] = std::cos(a);
    patch.normals[3 * v + 2] = std::copysign(0.0f, z_sign);
  }
  return patch;
}

TEST(ShadowfieldGl, NormalsWithANegativeZeroZAgreeWithScalar) {
  PRT_REQUIRE_GL(context);
  const auto light = test_light(4);
  std::vector<float> by_sign[2];
  for (const float z_sign : {-1.0f, 1.0f}) {
    SyntheticObject patch = leaning_glossy_patch(z_sign);
    TestScene scene(1);
    scene.add_instance(scene.add_object(patch),
                       make_transform(identity_rotation(), 0.0f, 0.0f, 0.0f));
    GlShadowfieldPtr shader = create(scene.scene, context.gl);
    ASSERT_TRUE(shader);
    const auto cpu = scene.shade(light, kNearEye, 0);
    const auto on_gl = shade_gl(shader.get(), scene.scene, light, kNearEye, 0);
    const double difference = relative_difference(on_gl, cpu);
    std::printf("z %c0: GL - scalar %.2e of the largest radiance\n", z_sign < 0.0f ? '-' : '+',
                difference);
    EXPECT_LT(difference, kTolerance) << "z sign " << z_sign;
    by_sign[z_sign > 0.0f ? 1 : 0] = cpu[0];
  }
  // The two frames read the table at different places: the case is reached.
  const double apart = max_difference(by_sign[0], by_sign[1]) / max_abs(by_sign[1]);
  std::printf("-0 and +0 apart by %.2f of the largest radiance\n", apart);
  EXPECT_GT(apart, 0.1);
}

// Instances that interpenetrate: receivers inside the other's innermost shell read that shell.
TEST(ShadowfieldGl, InterpenetratingInstancesAgreeWithScalar) {
  PRT_REQUIRE_GL(context);
  GlScene busy(4, true);
  float tilt[9];
  axis_rotation(kAxis, 1.1f, tilt);
  const prt_shadowfield_transform inside = make_transform(tilt, 0.05f, 0.02f, -0.03f, 1.0f);
  ASSERT_EQ(prt_shadowfield_scene_set_transform(busy.scene.scene, 2, &inside), PRT_OK);
  EXPECT_LT(agreement(busy.scene, context.gl, test_light(4, 0.3f), kNearEye), kTolerance);
}

// More vertices than one dispatch takes (the backend splits an instance into chunks).
TEST(ShadowfieldGl, AnInstanceLargerThanADispatchAgreesWithScalar) {
  PRT_REQUIRE_GL(context);
  GlScene busy(2, false, 131, 3);
  GlShadowfieldPtr shader = create(busy.scene.scene, context.gl);
  ASSERT_TRUE(shader);
  const auto light = test_light(2);
  const auto cpu = busy.scene.shade(light, kNearEye, 1);
  const auto on_gl = shade_gl(shader.get(), busy.scene.scene, light, kNearEye, 1);
  EXPECT_LT(relative_difference(on_gl, cpu), kTolerance);
}

TEST(ShadowfieldGl, MovedInstancesAgreeWithScalarFrameAfterFrame) {
  PRT_REQUIRE_GL(context);
  GlScene busy(4, true);
  GlShadowfieldPtr shader = create(busy.scene.scene, context.gl);
  ASSERT_TRUE(shader);
  for (int frame = 0; frame < 3; ++frame) {
    float turn[9];
    axis_rotation(kAxis, 0.7f * float(frame), turn);
    const prt_shadowfield_transform moved =
        make_transform(turn, 0.2f * float(frame), 0.7f, -0.1f * float(frame), 0.9f);
    ASSERT_EQ(prt_shadowfield_scene_set_transform(busy.scene.scene, 1, &moved), PRT_OK);
    const auto light = test_light(4, 0.5f * float(frame));
    const auto cpu = busy.scene.shade(light, kNearEye, 2);
    const auto on_gl = shade_gl(shader.get(), busy.scene.scene, light, kNearEye, 2);
    EXPECT_LT(relative_difference(on_gl, cpu), kTolerance) << "frame " << frame;
  }
}

TEST(ShadowfieldGl, NullSettingsGiveTheDefaultBouncesAsScalar) {
  PRT_REQUIRE_GL(context);
  GlScene busy(4, false);
  GlShadowfieldPtr shader = create(busy.scene.scene, context.gl);
  ASSERT_TRUE(shader);
  const auto light = test_light(4);
  ASSERT_EQ(prt_gl_shadowfield_shade(shader.get(), light.data(), kNearEye, nullptr), PRT_OK);
  const auto cpu = busy.scene.shade(light, kNearEye, PRT_SHADOWFIELD_DEFAULT_BOUNCES);
  for (uint32_t i = 0; i < 3; ++i) {
    std::vector<float> on_gl(cpu[i].size());
    ASSERT_EQ(
        prt_gl_shadowfield_read(shader.get(), i, 0, uint32_t(cpu[i].size() / 3), on_gl.data()),
        PRT_OK);
    EXPECT_LT(max_difference(on_gl, cpu[i]), kTolerance * max_abs(cpu[i])) << "instance " << i;
  }
}

// The output buffer holds the instances one after another, vertex-major RGB; read gives its
// ranges.
TEST(ShadowfieldGl, TheOutputBufferHoldsEveryInstanceInOrder) {
  PRT_REQUIRE_GL(context);
  GlScene busy(4, true);
  GlShadowfieldPtr shader = create(busy.scene.scene, context.gl);
  ASSERT_TRUE(shader);
  const auto light = test_light(4);
  prt_test::leave_gl_error_pending();  // an application's earlier mistake changes nothing
  (void)prt_test::take_gl_error();
  // With probes, so that every binding (the probes' too) is used.
  const auto on_gl = shade_gl(shader.get(), busy.scene.scene, light, kNearEye, 1, 0.5f);
  prt_test::expect_gl_state_restored("prt_gl_shadowfield_shade and read");
  for (unsigned binding = 4; binding < 8; ++binding) {
    int value = -1;
    prt_test::gl_function<prt_test::gl_names::GetIntegeriVFn>("glGetIntegeri_v")(
        prt_test::gl_names::kGlShaderStorageBufferBinding, binding, &value);
    EXPECT_EQ(value, 0) << "indexed SSBO binding " << binding;
  }
  const uint32_t buffer = prt_gl_shadowfield_output_buffer(shader.get());
  ASSERT_NE(buffer, 0u);
  EXPECT_EQ(prt_gl_shadowfield_output_first(shader.get(), 0), 0u);
  EXPECT_EQ(prt_gl_shadowfield_output_first(shader.get(), 1), 81u);
  EXPECT_EQ(prt_gl_shadowfield_output_first(shader.get(), 2), 81u + 25u);
  EXPECT_EQ(prt_gl_shadowfield_output_first(shader.get(), 3), 0u);  // unknown
  std::vector<float> whole(3 * (81 + 25 + 25));
  using prt_test::gl_function;
  gl_function<prt_test::gl_names::BindBufferFn>("glBindBuffer")(0x90D2u, buffer);
  gl_function<prt_test::gl_names::GetBufferSubDataFn>("glGetBufferSubData")(
      0x90D2u, 0, std::ptrdiff_t(whole.size() * sizeof(float)), whole.data());
  gl_function<prt_test::gl_names::BindBufferFn>("glBindBuffer")(0x90D2u, 0u);
  for (uint32_t i = 0; i < 3; ++i) {
    const size_t first = 3 * size_t(prt_gl_shadowfield_output_first(shader.get(), i));
    EXPECT_TRUE(std::equal(on_gl[i].begin(), on_gl[i].end(), whole.begin() + first))
        << "instance " << i;
  }
  std::vector<float> part(3 * 4);
  ASSERT_EQ(prt_gl_shadowfield_read(shader.get(), 1, 21, 4, part.data()), PRT_OK);
  EXPECT_TRUE(std::equal(part.begin(), part.end(), on_gl[1].begin() + 3 * 21));
}

// ---- refusals ----------------------------------------------------------------------------

// Bad settings, light and eye: the GL call refuses what the scalar call refuses, with its result.
TEST(ShadowfieldGl, BadSettingsAreRefusedAsByScalar) {
  PRT_REQUIRE_GL(context);
  GlScene busy(4, false);
  GlShadowfieldPtr shader = create(busy.scene.scene, context.gl);
  ASSERT_TRUE(shader);
  prt_shadowfield_scene* scene = busy.scene.scene;
  const auto light = test_light(4);
  std::vector<float> nan_light = light;
  nan_light[5] = std::nanf("");
  const float nan_eye[3] = {0.0f, std::numeric_limits<float>::infinity(), 0.0f};
  std::vector<std::vector<float>> out(3);
  std::vector<float*> pointers(3);
  for (uint32_t i = 0; i < 3; ++i) {
    out[i].resize(3 * size_t(prt_shadowfield_instance_vertex_count(scene, i)));
    pointers[i] = out[i].data();
  }
  struct Case {
    const char* what;
    prt_shadowfield_settings settings;
    const float* light;
    const float* eye;
  };
  prt_shadowfield_settings too_many = settings_for(PRT_SHADOWFIELD_MAX_BOUNCES + 1);
  prt_shadowfield_settings old = settings_for(1);
  old.struct_size = sizeof(size_t);
  // A backend value no enumerator has, as a C caller could pass it; C++ may not form such an
  // enum value, so it is written and read as the int it is.
  static_assert(sizeof(prt_backend) == sizeof(int), "prt_backend is stored as an int");
  prt_shadowfield_settings unknown = settings_for(1);
  const int bogus_backend = 77;
  std::memcpy(&unknown.backend, &bogus_backend, sizeof bogus_backend);
  prt_shadowfield_settings negative_spacing = settings_for(1);
  negative_spacing.bounce_probe_spacing = -0.5f;
  const Case cases[] = {{"too many bounces", too_many, light.data(), kNearEye},
                        {"a negative probe spacing", negative_spacing, light.data(), kNearEye},
                        {"struct_size too small", old, light.data(), kNearEye},
                        {"unknown backend", unknown, light.data(), kNearEye},
                        {"NULL light", settings_for(1), nullptr, kNearEye},
                        {"NULL eye", settings_for(1), light.data(), nullptr},
                        {"NaN light", settings_for(1), nan_light.data(), kNearEye},
                        {"infinite eye", settings_for(1), light.data(), nan_eye}};
  for (const Case& c : cases) {
    prt_shadowfield_settings cpu_settings = c.settings;
    int backend = 0;
    std::memcpy(&backend, &cpu_settings.backend, sizeof backend);
    if (backend == PRT_BACKEND_GL) cpu_settings.backend = PRT_BACKEND_CPU;
    const prt_result scalar =
        prt_shadowfield_shade(scene, c.light, c.eye, &cpu_settings, pointers.data());
    EXPECT_NE(scalar, PRT_OK) << c.what;
    EXPECT_EQ(prt_gl_shadowfield_shade(shader.get(), c.light, c.eye, &c.settings), scalar)
        << c.what;
  }
  // The GL entry point runs GL: a CPU backend asked of it is refused.
  for (const prt_backend cpu : {PRT_BACKEND_CPU, PRT_BACKEND_SIMD}) {
    const prt_shadowfield_settings settings = settings_for(1, cpu);
    EXPECT_EQ(prt_gl_shadowfield_shade(shader.get(), light.data(), kNearEye, &settings),
              PRT_ERROR_UNSUPPORTED_BACKEND);
  }
  // A caller built against 1.0's struct (ending before the spacing) asking for GL gets GL.
  prt_shadowfield_settings first = settings_for(1, PRT_BACKEND_GL);
  first.struct_size = offsetof(prt_shadowfield_settings, bounce_probe_spacing);
  first.bounce_probe_spacing = 0.25f;  // beyond its struct_size: never read
  EXPECT_EQ(prt_gl_shadowfield_shade(shader.get(), light.data(), kNearEye, &first), PRT_OK)
      << prt_context_last_message(busy.scene.context);
  // AUTO is GL here.
  const prt_shadowfield_settings automatic = settings_for(1, PRT_BACKEND_AUTO);
  EXPECT_EQ(prt_gl_shadowfield_shade(shader.get(), light.data(), kNearEye, &automatic), PRT_OK);
  EXPECT_EQ(prt_gl_shadowfield_shade(nullptr, light.data(), kNearEye, &automatic),
            PRT_ERROR_INVALID_ARGUMENT);
}

TEST(ShadowfieldGl, BadReadsAreRefused) {
  PRT_REQUIRE_GL(context);
  GlScene busy(4, false);
  GlShadowfieldPtr shader = create(busy.scene.scene, context.gl);
  ASSERT_TRUE(shader);
  const auto light = test_light(4);
  const prt_shadowfield_settings settings = settings_for(0);
  ASSERT_EQ(prt_gl_shadowfield_shade(shader.get(), light.data(), kNearEye, &settings), PRT_OK);
  std::vector<float> out(3 * 81);
  EXPECT_EQ(prt_gl_shadowfield_read(shader.get(), 3, 0, 1, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_shadowfield_read(shader.get(), 0, 80, 2, out.data()),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_shadowfield_read(shader.get(), 0, 82, 0, out.data()),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_shadowfield_read(shader.get(), 0, 0, 1, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_shadowfield_read(nullptr, 0, 0, 1, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_shadowfield_read(shader.get(), 0, 81, 0, nullptr), PRT_OK);
  EXPECT_EQ(prt_gl_shadowfield_read(shader.get(), 1, 0, 25, out.data()), PRT_OK);
  // The CPU stages do not hold the GL frame: they ask for prepare again.
  EXPECT_EQ(prt_shadowfield_output(busy.scene.scene, 0, 0, 0, 1, out.data()),
            PRT_ERROR_INVALID_OPERATION);
}

TEST(ShadowfieldGl, BadCreatesAreRefused) {
  PRT_REQUIRE_GL(context);
  prt_gl_shadowfield* shader = reinterpret_cast<prt_gl_shadowfield*>(&shader);
  EXPECT_EQ(prt_gl_shadowfield_create(nullptr, headless_gl_get_proc, context.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(shader, nullptr);
  TestScene empty(2);
  EXPECT_EQ(prt_gl_shadowfield_create(empty.scene, headless_gl_get_proc, context.gl, &shader),
            PRT_ERROR_INVALID_OPERATION);
  GlScene busy(4, false);
  EXPECT_EQ(prt_gl_shadowfield_create(busy.scene.scene, nullptr, context.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_shadowfield_create(busy.scene.scene, headless_gl_get_proc, context.gl, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  // An old GL, and a loader without an entry point.
  EXPECT_EQ(prt_gl_shadowfield_create(busy.scene.scene, prt_test::lying_loader,
                                      const_cast<char*>("version"), &shader),
            PRT_ERROR_UNSUPPORTED_BACKEND);
  prt_test::LoaderOverride hiding{context.gl, "glDispatchCompute"};
  EXPECT_EQ(
      prt_gl_shadowfield_create(busy.scene.scene, prt_test::LoaderOverride::get, &hiding, &shader),
      PRT_ERROR_UNSUPPORTED_BACKEND);
  EXPECT_EQ(shader, nullptr);
  // A context limited to the CPU.
  prt::ContextPtr cpu_only = prt_test::limited_context(PRT_BACKEND_CPU);
  prt_shadowfield_scene* limited = nullptr;
  ASSERT_EQ(prt_shadowfield_scene_create(cpu_only.get(), 1, &limited), PRT_OK);
  uint32_t object = 0, instance = 0;
  ASSERT_EQ(prt_internal_sf_scene_add_object(limited, busy.box.view(), &object), PRT_OK);
  const prt_shadowfield_transform here = make_transform(identity_rotation(), 0, 0, 0);
  ASSERT_EQ(prt_shadowfield_scene_add_instance(limited, object, &here, &instance), PRT_OK);
  EXPECT_EQ(prt_gl_shadowfield_create(limited, headless_gl_get_proc, context.gl, &shader),
            PRT_ERROR_UNSUPPORTED_BACKEND);
  prt_shadowfield_scene_destroy(limited);
  prt_gl_shadowfield_destroy(nullptr);
}

// The log-space product: GL sums the logs and takes the exponential at the same directions,
// with GLSL's exp (not correctly rounded) where the CPU has its polynomial.
TEST(ShadowfieldGl, TheLogProductAgreesWithScalar) {
  PRT_REQUIRE_GL(context);
  for (const uint32_t order : {2u, 4u, 6u})
    for (const bool glossy : {false, true}) {
      GlScene busy(order, glossy);
      ASSERT_EQ(prt_shadowfield_scene_set_product(busy.scene.scene, PRT_SHADOWFIELD_PRODUCT_LOG),
                PRT_OK);
      EXPECT_LT(agreement(busy.scene, context.gl, test_light(order), kNearEye), kTolerance)
          << order << (glossy ? " glossy" : " diffuse");
    }
}

TEST(ShadowfieldGl, AProductChangedAfterCreateIsRefused) {
  PRT_REQUIRE_GL(context);
  GlScene busy(4, false);
  GlShadowfieldPtr shader = create(busy.scene.scene, context.gl);
  ASSERT_TRUE(shader);
  ASSERT_EQ(prt_shadowfield_scene_set_product(busy.scene.scene, PRT_SHADOWFIELD_PRODUCT_LOG),
            PRT_OK);
  const auto light = test_light(4);
  const prt_shadowfield_settings settings = settings_for(1);
  EXPECT_EQ(prt_gl_shadowfield_shade(shader.get(), light.data(), kNearEye, &settings),
            PRT_ERROR_INVALID_OPERATION);
  EXPECT_NE(std::strstr(prt_context_last_message(busy.scene.context), "product changed"), nullptr);
}

TEST(ShadowfieldGl, InstancesAddedAfterCreateAreRefused) {
  PRT_REQUIRE_GL(context);
  GlScene busy(4, false);
  TestScene& scene = busy.scene;
  prt_shadowfield_scene_destroy(scene.scene);
  ASSERT_EQ(prt_shadowfield_scene_create(scene.context, 4, &scene.scene), PRT_OK);
  const uint32_t floor = scene.add_object(busy.floor);
  scene.add_instance(floor, make_transform(identity_rotation(), 0, 0, 0));
  GlShadowfieldPtr shader = create(scene.scene, context.gl);
  ASSERT_TRUE(shader);
  scene.add_instance(floor, make_transform(identity_rotation(), 0, 1, 0));
  const auto light = test_light(4);
  const prt_shadowfield_settings settings = settings_for(1);
  EXPECT_EQ(prt_gl_shadowfield_shade(shader.get(), light.data(), kNearEye, &settings),
            PRT_ERROR_INVALID_OPERATION);
}

}  // namespace
}  // namespace prt::test
