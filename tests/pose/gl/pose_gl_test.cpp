// SPDX-License-Identifier: MIT
// The GL backend of `pose` (prt_pose_asset.h) on a headless EGL context: both models against the
// scalar reference within pose_bound() (pose/gl/pose_gl_util.hpp), the caller's normals, vertex
// ranges, the output buffer's layout and GL state, and every error path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "pose/gl/pose_gl_util.hpp"
#include "support/gl_create_checks.hpp"
#include "support/gl_test_util.hpp"

namespace {

using prt_test::LoadedAsset;
using prt_test::PoseSection;

struct GlPoseDeleter {
  void operator()(prt_gl_pose_shader* shader) const noexcept { prt_gl_pose_destroy(shader); }
};
using ShaderPtr = std::unique_ptr<prt_gl_pose_shader, GlPoseDeleter>;

// A `pose` asset in its own context.
struct GlAsset {
  PoseSection section;
  prt::ContextPtr context;
  std::unique_ptr<LoadedAsset> loaded;
  explicit GlAsset(const PoseSection& s, prt_backend limit = PRT_BACKEND_AUTO,
                   const prt_allocator* allocator = nullptr)
      : section(s) {
    context = prt_test::limited_context(limit, PRT_SIMD_ISA_AUTO, allocator);
    loaded = std::make_unique<LoadedAsset>(context.get(), prt_test::pose_blob(s));
    EXPECT_EQ(loaded->result, PRT_OK) << prt_context_last_message(context.get());
  }
  const prt_asset* asset() const { return loaded->asset; }
  std::string message() const { return prt_context_last_message(context.get()); }
};

ShaderPtr create_shader(const GlAsset& a, headless_gl* gl) {
  prt_gl_pose_shader* shader = nullptr;
  EXPECT_EQ(prt_gl_pose_create(a.context.get(), a.asset(), headless_gl_get_proc, gl, &shader),
            PRT_OK)
      << a.message();
  return ShaderPtr(shader);
}

prt_test::TryCreateShader try_create(const GlAsset& a) {
  return [&a](prt_context* context, prt_gl_loader_fn loader, void* user, bool* shader_null) {
    prt_gl_pose_shader* shader = nullptr;
    const prt_result r = prt_gl_pose_create(context, a.asset(), loader, user, &shader);
    *shader_null = shader == nullptr;
    prt_gl_pose_destroy(shader);
    return r;
  };
}

prt_pose_light light_of(const std::vector<float>& rgb, const float* world = nullptr,
                        const float* normals = nullptr) {
  prt_pose_light l{};
  l.struct_size = sizeof l;
  l.light_rgb = rgb.data();
  l.world_from_character = world;
  l.normals = normals;
  return l;
}

std::vector<float> read_all(prt_gl_pose_shader* shader, uint32_t vertices) {
  std::vector<float> rgb(3 * size_t(vertices), -12345.0f);
  EXPECT_EQ(prt_gl_pose_read(shader, 0, vertices, rgb.data()), PRT_OK);
  return rgb;
}

// The scalar reference of vertices [first, first + count) and GL's (already in `got`) within
// pose_bound; returns the largest |error| / tolerance.
double expect_matches_scalar(const GlAsset& a, const std::vector<float>& r,
                             const prt_pose_light& light, const float* got, uint32_t first,
                             uint32_t count, bool given_normals = false) {
  const PoseSection& s = a.section;
  const prt_pose_input pose = prt_test::pose_of(r);
  std::vector<float> reference(3 * size_t(s.vertices), 0.0f);
  prt_pose_light l = light;
  EXPECT_EQ(prt_pose_shade(a.asset(), PRT_BACKEND_CPU, &pose, &l, first, count,
                           reference.data() + 3 * size_t(first)),
            PRT_OK);
  const std::vector<double> ref(reference.begin(), reference.end());
  const std::vector<float> light_rgb(light.light_rgb, light.light_rgb + 3 * s.coefficients());
  const prt_test::PoseBound bound =
      prt_test::pose_bound(s, r, light_rgb, light.world_from_character, ref, given_normals);
  return prt_test::compare_to_reference("gl", ref, bound, got, first, count);
}

TEST(GlPose, BothModelsShadeLikeTheScalarReference) {
  PRT_REQUIRE_GL(gl);
  // 131 vertices: three work groups of 64, the last one partial.
  for (uint32_t model : {0u, 1u})
    for (uint32_t order : {1u, 4u, 8u})
      for (uint32_t bits : {8u, 16u}) {
        SCOPED_TRACE("model " + std::to_string(model) + ", order " + std::to_string(order) +
                     ", bits " + std::to_string(bits));
        const uint32_t q = order * 3 + bits / 8;  // odd and even, off any group of 4
        const GlAsset a(prt_test::random_section(order, 131, 5, 4, q, bits, model, order + bits));
        ShaderPtr shader = create_shader(a, gl.gl);
        ASSERT_TRUE(shader);
        const std::vector<float> r = prt_test::random_rotations(5, order);
        const prt_pose_input pose = prt_test::pose_of(r);
        const std::vector<float> light = prt_test::realistic_light(order, order + model);
        const std::vector<float> world = prt_test::axis_rotation(1, 0.3, -0.2, 0.7);
        const prt_pose_light l = light_of(light, world.data());
        ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pose, &l, 0, 131), PRT_OK);
        const double worst =
            expect_matches_scalar(a, r, l, read_all(shader.get(), 131).data(), 0, 131);
        std::printf("model %u order %u %u-bit q %u: max err/tol %.3g\n", model, order, bits, q,
                    worst);
      }
}

// A mirrored joint (negative scale: det K < 0 for the vertices it moves alone) keeps the skinned
// normal's orientation through the cofactors' sign, as on the CPU.
TEST(GlPose, MirroredJointsSkinNormalsLikeTheScalarReference) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 97;
  PoseSection s = prt_test::random_section(4, n, 4, 3, 6, 16, 1, 51);
  s.joints[2].scale[0] = -s.joints[2].scale[0];
  for (uint32_t v = 0; v < n; v += 2) s.skin[v].joints = {2, 2, 2, 2};  // det < 0 alone
  const GlAsset a(s);
  ShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const std::vector<float> r = prt_test::random_rotations(4, 52);
  const prt_pose_input pose = prt_test::pose_of(r);
  const std::vector<float> light = prt_test::realistic_light(4, 53);
  const prt_pose_light l = light_of(light);
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pose, &l, 0, n), PRT_OK);
  expect_matches_scalar(a, r, l, read_all(shader.get(), n).data(), 0, n);
}

// Model 1 with the caller's normals: those are what the exact part reads, on GL as on the CPU.
TEST(GlPose, CallersNormalsReplaceTheSkinnedOnes) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 200;
  const GlAsset a(prt_test::random_section(5, n, 4, 3, 7, 16, 1, 21));
  ShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const std::vector<float> r = prt_test::random_rotations(4, 22);
  const prt_pose_input pose = prt_test::pose_of(r);
  const std::vector<float> light = prt_test::realistic_light(5, 23);
  // Normals of vertices [30, 150): unnormalised on purpose, and one zero (no exact part).
  std::vector<float> normals(3 * 120);
  for (uint32_t i = 0; i < 120; ++i) {
    normals[3 * i] = 0.5f + 0.01f * i, normals[3 * i + 1] = -2.0f, normals[3 * i + 2] = 0.3f;
  }
  normals[3 * 7] = normals[3 * 7 + 1] = normals[3 * 7 + 2] = 0.0f;
  const prt_pose_light skinned = light_of(light), given = light_of(light, nullptr, normals.data());
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pose, &skinned, 0, n), PRT_OK);
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pose, &given, 30, 120), PRT_OK);
  const std::vector<float> rgb = read_all(shader.get(), n);
  expect_matches_scalar(a, r, skinned, rgb.data(), 0, 30);
  expect_matches_scalar(a, r, given, rgb.data() + 3 * 30, 30, 120, true);
  expect_matches_scalar(a, r, skinned, rgb.data() + 3 * 150, 150, n - 150);
  // And they differ from the skinned ones' shading (the normals were used).
  std::vector<float> cpu_skinned(3 * 120);
  ASSERT_EQ(
      prt_pose_shade(a.asset(), PRT_BACKEND_CPU, &pose, &skinned, 30, 120, cpu_skinned.data()),
      PRT_OK);
  double largest_change = 0;
  for (size_t i = 0; i < cpu_skinned.size(); ++i)
    largest_change = std::max(largest_change, double(std::fabs(cpu_skinned[i] - rgb[3 * 30 + i])));
  EXPECT_GT(largest_change, 1e-3);
  // The next call without normals skins again.
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pose, &skinned, 0, n), PRT_OK);
  expect_matches_scalar(a, r, skinned, read_all(shader.get(), n).data(), 0, n);
}

TEST(GlPose, RangesShadeOnlyTheirVertices) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 300;
  const GlAsset a(prt_test::random_section(3, n, 4, 3, 6, 8, 1, 31));
  ShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const std::vector<float> ra = prt_test::random_rotations(4, 32);
  const std::vector<float> rb = prt_test::random_rotations(4, 33);
  const prt_pose_input pa = prt_test::pose_of(ra), pb = prt_test::pose_of(rb);
  const std::vector<float> light = prt_test::realistic_light(3, 34);
  const prt_pose_light l = light_of(light);
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pa, &l, 0, n), PRT_OK);
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pb, &l, 70, 100), PRT_OK);
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pb, &l, n, 0), PRT_OK) << "empty range at end";
  const std::vector<float> rgb = read_all(shader.get(), n);
  expect_matches_scalar(a, ra, l, rgb.data(), 0, 70);
  expect_matches_scalar(a, rb, l, rgb.data() + 3 * 70, 70, 100);
  expect_matches_scalar(a, ra, l, rgb.data() + 3 * 170, 170, n - 170);

  // A partial read returns exactly that slice.
  std::vector<float> slice(3 * 33);
  ASSERT_EQ(prt_gl_pose_read(shader.get(), 150, 33, slice.data()), PRT_OK);
  EXPECT_TRUE(std::equal(slice.begin(), slice.end(), rgb.begin() + 3 * 150));

  // Two halves shaded separately give the bits of one call (a vertex's arithmetic does not
  // depend on the range).
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pb, &l, 0, n), PRT_OK);
  const std::vector<float> whole = read_all(shader.get(), n);
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pa, &l, 0, n), PRT_OK);
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pb, &l, 0, 123), PRT_OK);
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pb, &l, 123, n - 123), PRT_OK);
  EXPECT_EQ(std::memcmp(read_all(shader.get(), n).data(), whole.data(), 4 * whole.size()), 0);
}

TEST(GlPose, OutputBufferIsTightlyPackedRgbAndStateIsLeftUnbound) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 77;
  for (uint32_t model : {0u, 1u}) {
    const GlAsset a(prt_test::random_section(2, n, 3, 2, 5, 8, model, 41));
    ShaderPtr shader = create_shader(a, gl.gl);
    ASSERT_TRUE(shader);
    const std::vector<float> r = prt_test::random_rotations(3, 42);
    const prt_pose_input pose = prt_test::pose_of(r);
    const std::vector<float> light = prt_test::realistic_light(2, 43);
    const prt_pose_light l = light_of(light);
    ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pose, &l, 0, n), PRT_OK);
    const uint32_t buffer = prt_gl_pose_output_buffer(shader.get());
    ASSERT_NE(buffer, 0u);
    prt_test::expect_gl_state_restored("prt_gl_pose_shade");
    // Binding 4 (the caller's normals) too, which the shared check does not cover.
    using namespace prt_test::gl_names;
    int value = -1;
    prt_test::gl_function<GetIntegeriVFn>("glGetIntegeri_v")(kGlShaderStorageBufferBinding, 4,
                                                             &value);
    EXPECT_EQ(value, 0) << "indexed SSBO binding 4";
    int size = 0;
    const std::vector<float> rgb = prt_test::read_gl_buffer_floats(buffer, &size);
    ASSERT_EQ(size, int(12 * n));
    expect_matches_scalar(a, r, l, rgb.data(), 0, n);
    EXPECT_EQ(read_all(shader.get(), n), rgb) << "prt_gl_pose_read returns the buffer's bytes";
  }
}

// A joint index >= J (only loadable at quick validation) weighs 0 on GL as on the CPU: alone it
// leaves the identity, beside a valid joint it gives that joint the whole weight.
TEST(GlPose, JointIndicesPastJWeighNothingAtQuickValidation) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 9;
  PoseSection s = prt_test::random_section(3, n, 3, 2, 4, 8, 1, 61);
  s.skin[0].joints = {200, 0, 0, 0};
  s.skin[0].weights = {65535, 0, 0, 0};
  s.skin[1].joints = {200, 1, 3, 2};
  s.skin[1].weights = {30000, 20000, 15000, 0};
  const prt::ContextPtr ctx = prt_test::limited_context();
  LoadedAsset quick(ctx.get(), prt_test::pose_blob(s), PRT_VALIDATE_QUICK);
  ASSERT_EQ(quick.result, PRT_OK) << prt_context_last_message(ctx.get());
  prt_gl_pose_shader* raw = nullptr;
  ASSERT_EQ(prt_gl_pose_create(ctx.get(), quick.asset, headless_gl_get_proc, gl.gl, &raw), PRT_OK)
      << prt_context_last_message(ctx.get());
  ShaderPtr shader(raw);
  const std::vector<float> r = prt_test::random_rotations(3, 62);
  const prt_pose_input pose = prt_test::pose_of(r);
  const std::vector<float> light = prt_test::realistic_light(3, 63);
  const prt_pose_light l = light_of(light);
  ASSERT_EQ(prt_gl_pose_shade(raw, &pose, &l, 0, n), PRT_OK);
  std::vector<float> got = read_all(raw, n), reference(3 * n);
  ASSERT_EQ(prt_pose_shade(quick.asset, PRT_BACKEND_CPU, &pose, &l, 0, n, reference.data()),
            PRT_OK);
  const std::vector<double> ref(reference.begin(), reference.end());
  const prt_test::PoseBound bound = prt_test::pose_bound(s, r, light, nullptr, ref);
  prt_test::compare_to_reference("gl", ref, bound, got.data(), 0, n);
}

TEST(GlPose, ManyVerticesSpanSeveralDispatches) {
  PRT_REQUIRE_GL(gl);
  // More than 65535 work groups of 64 (the dispatch limit GL guarantees) needs two dispatches.
  const uint32_t n = 65535u * 64u + 1000u;
  const GlAsset a(prt_test::random_section(1, n, 1, 0, 1, 8, 0, 5));
  ShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const std::vector<float> r = {0, 0, 0, 1};
  const prt_pose_input pose = prt_test::pose_of(r);
  const std::vector<float> light = {2.0f, 3.0f, 5.0f};
  const prt_pose_light l = light_of(light);
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pose, &l, 0, n), PRT_OK);
  const std::vector<float> rgb = read_all(shader.get(), n);
  expect_matches_scalar(a, r, l, rgb.data(), 0, n);
}

TEST(GlPose, ErrorsTheApplicationLeftPendingDoNotFailCreation) {
  PRT_REQUIRE_GL(gl);
  prt_test::leave_gl_error_pending();
  const GlAsset a(prt_test::random_section(2, 10, 2, 1, 3, 8, 1, 6));
  EXPECT_TRUE(create_shader(a, gl.gl));
  EXPECT_EQ(prt_test::take_gl_error(), 0u) << "create cleared the pending error and raised none";
}

TEST(GlPose, NoPstrSectionIsNotFound) {
  PRT_REQUIRE_GL(gl);
  const prt::ContextPtr ctx = prt_test::limited_context();
  LoadedAsset loaded(ctx.get(), prt_test::mesh_only_blob());
  ASSERT_EQ(loaded.result, PRT_OK);
  prt_gl_pose_shader* shader = reinterpret_cast<prt_gl_pose_shader*>(&loaded);
  EXPECT_EQ(prt_gl_pose_create(ctx.get(), loaded.asset, headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(shader, nullptr);
  EXPECT_NE(std::string(prt_context_last_message(ctx.get())).find("PSTR"), std::string::npos);
}

TEST(GlPose, MissingEntryPointIsUnsupportedAndNamed) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::random_section(2, 8, 2, 1, 3, 8, 1, 1));
  prt_test::expect_refused_without_entry_points(
      try_create(a), a.context.get(), gl.gl,
      {"glDispatchCompute", "glMemoryBarrier", "glGetBufferSubData", "glProgramUniform1ui",
       "glGetError"});
}

TEST(GlPose, ContextOlderThan43IsUnsupported) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::random_section(2, 8, 2, 1, 3, 8, 1, 1));
  prt_test::expect_refused_below_gl_43(try_create(a), a.context.get());
}

TEST(GlPose, AssetLargerThanTheSsboLimitIsUnsupported) {
  PRT_REQUIRE_GL(gl);
  // 100 vertices * 36 bytes of skin records > 1024 bytes.
  const GlAsset a(prt_test::random_section(1, 100, 2, 1, 1, 8, 1, 1));
  prt_test::expect_refused_above_ssbo_limit(try_create(a), a.context.get());
}

TEST(GlPose, BackendLimitBelowGlIsUnsupported) {
  PRT_REQUIRE_GL(gl);
  for (prt_backend limit : {PRT_BACKEND_CPU, PRT_BACKEND_SIMD}) {
    const GlAsset a(prt_test::random_section(2, 8, 2, 1, 3, 8, 0, 1), limit);
    prt_gl_pose_shader* shader = nullptr;
    EXPECT_EQ(prt_gl_pose_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
              PRT_ERROR_UNSUPPORTED_BACKEND);
    EXPECT_EQ(shader, nullptr);
  }
  const GlAsset a(prt_test::random_section(2, 8, 2, 1, 3, 8, 0, 1), PRT_BACKEND_GL);
  EXPECT_TRUE(create_shader(a, gl.gl));
}

TEST(GlPose, BadArgumentsAreInvalidAndWriteNoContext) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 50;
  const GlAsset a(prt_test::random_section(2, n, 3, 2, 3, 16, 1, 2));
  ShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const std::vector<float> r = prt_test::random_rotations(3, 3);
  const prt_pose_input pose = prt_test::pose_of(r);
  const std::vector<float> light = prt_test::realistic_light(2, 4);
  const prt_pose_light l = light_of(light);
  std::vector<float> rgb(3 * size_t(n) + 3);
  const uint32_t bad[][2] = {{n + 1, 0}, {0, n + 1}, {n - 1, 2}, {1, UINT32_MAX}, {UINT32_MAX, 1}};
  for (const auto& range : bad) {
    EXPECT_EQ(prt_gl_pose_shade(shader.get(), &pose, &l, range[0], range[1]),
              PRT_ERROR_INVALID_ARGUMENT)
        << range[0] << " + " << range[1];
    EXPECT_EQ(prt_gl_pose_read(shader.get(), range[0], range[1], rgb.data()),
              PRT_ERROR_INVALID_ARGUMENT)
        << range[0] << " + " << range[1];
  }
  EXPECT_EQ(prt_gl_pose_shade(shader.get(), nullptr, &l, 0, n), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_pose_shade(shader.get(), &pose, nullptr, 0, n), PRT_ERROR_INVALID_ARGUMENT);
  prt_pose_light bad_light = l;
  bad_light.struct_size = 8;
  EXPECT_EQ(prt_gl_pose_shade(shader.get(), &pose, &bad_light, 0, n), PRT_ERROR_INVALID_ARGUMENT);
  bad_light = l;
  bad_light.light_rgb = nullptr;
  EXPECT_EQ(prt_gl_pose_shade(shader.get(), &pose, &bad_light, 0, n), PRT_ERROR_INVALID_ARGUMENT);
  const float scaled[9] = {2, 0, 0, 0, 2, 0, 0, 0, 2}, mirror[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (const float* world : {scaled, mirror}) {
    bad_light = l;
    bad_light.world_from_character = world;
    EXPECT_EQ(prt_gl_pose_shade(shader.get(), &pose, &bad_light, 0, n), PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(prt_gl_pose_shade(shader.get(), &pose, &bad_light, 0, 0), PRT_ERROR_INVALID_ARGUMENT)
        << "checked whatever the range, as prt_pose_shade";
  }
  std::vector<float> zero = r;
  zero[4] = zero[5] = zero[6] = zero[7] = 0.0f;
  const prt_pose_input zero_pose = prt_test::pose_of(zero);
  EXPECT_EQ(prt_gl_pose_shade(shader.get(), &zero_pose, &l, 0, n), PRT_ERROR_INVALID_ARGUMENT);
  prt_pose_input small = pose;
  small.struct_size = 4;
  EXPECT_EQ(prt_gl_pose_shade(shader.get(), &small, &l, 0, n), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_pose_read(shader.get(), 0, n, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_pose_read(shader.get(), n, 0, nullptr), PRT_OK) << "empty read";
  EXPECT_EQ(prt_gl_pose_shade(shader.get(), &pose, &l, n, 0), PRT_OK) << "empty shade";
  // Per-frame calls report through their result only: no context was written.
  EXPECT_EQ(prt_context_last_result(a.context.get()), PRT_OK) << a.message();
  // Nothing was issued for the refused calls: the last good shade's values stand.
  ASSERT_EQ(prt_gl_pose_shade(shader.get(), &pose, &l, 0, n), PRT_OK);
  const std::vector<float> before = read_all(shader.get(), n);
  EXPECT_EQ(prt_gl_pose_shade(shader.get(), &zero_pose, &l, 0, n), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(read_all(shader.get(), n), before);
}

// The shader reports to the context it is created with, which need not be the asset's.
TEST(GlPose, CreateReportsToTheCallersContext) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::random_section(2, 8, 2, 1, 3, 8, 1, 1));
  const prt::ContextPtr limited = prt_test::limited_context(PRT_BACKEND_SIMD);
  prt_gl_pose_shader* shader = nullptr;
  EXPECT_EQ(prt_gl_pose_create(limited.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_UNSUPPORTED_BACKEND);
  EXPECT_EQ(shader, nullptr);
  EXPECT_NE(std::string(prt_context_last_message(limited.get())).find("prt_gl_pose_create"),
            std::string::npos);
  EXPECT_EQ(prt_context_last_result(a.context.get()), PRT_OK) << a.message();
  const prt::ContextPtr render = prt_test::limited_context();
  ASSERT_EQ(prt_gl_pose_create(render.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_OK)
      << prt_context_last_message(render.get());
  ShaderPtr owned(shader);
  const std::vector<float> r = prt_test::random_rotations(2, 5);
  const prt_pose_input pose = prt_test::pose_of(r);
  const std::vector<float> light = prt_test::realistic_light(2, 3);
  const prt_pose_light l = light_of(light);
  ASSERT_EQ(prt_gl_pose_shade(shader, &pose, &l, 0, 8), PRT_OK);
  expect_matches_scalar(a, r, l, read_all(shader, 8).data(), 0, 8);
}

TEST(GlPose, NullArguments) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::random_section(2, 8, 2, 1, 3, 8, 0, 1));
  prt_gl_pose_shader* shader = nullptr;
  EXPECT_EQ(prt_gl_pose_create(nullptr, a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_pose_create(a.context.get(), nullptr, headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_pose_create(a.context.get(), a.asset(), nullptr, gl.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_pose_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(shader, nullptr);
  const std::vector<float> r = {0, 0, 0, 1, 0, 0, 0, 1};
  const prt_pose_input pose = prt_test::pose_of(r);
  const std::vector<float> light(12, 0.0f);
  const prt_pose_light l = light_of(light);
  float rgb[3];
  EXPECT_EQ(prt_gl_pose_shade(nullptr, &pose, &l, 0, 1), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_pose_read(nullptr, 0, 1, rgb), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_pose_output_buffer(nullptr), 0u);
  prt_gl_pose_destroy(nullptr);  // ignored
}

TEST(GlPose, ShaderComesFromTheAssetsAllocator) {
  PRT_REQUIRE_GL(gl);
  prt_test::CountingAllocator counter;
  const prt_allocator allocator = counter.api();
  const GlAsset a(prt_test::random_section(3, 40, 3, 2, 5, 8, 1, 4), PRT_BACKEND_AUTO, &allocator);
  const int before = counter.live;
  prt_gl_pose_shader* shader = nullptr;
  ASSERT_EQ(prt_gl_pose_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_OK);
  EXPECT_GT(counter.live, before);
  prt_gl_pose_destroy(shader);
  EXPECT_EQ(counter.live, before);

  counter.fail = true;
  EXPECT_EQ(prt_gl_pose_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(shader, nullptr);
  counter.fail = false;
  EXPECT_EQ(counter.live, before);
}

}  // namespace
