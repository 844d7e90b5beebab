// SPDX-License-Identifier: MIT
// The GL backend of `sh` (prt_sh_asset.h) on a headless EGL context: results against the exact
// double sum of the stored q/offset/scale, vertex ranges, the output buffer's layout and GL state,
// and every error path.
#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "support/gl_create_checks.hpp"
#include "support/gl_test_util.hpp"

namespace {

using prt_test::ContextPtr;
using prt_test::LoadedAsset;
using prt_test::ShaderPtr;
using prt_test::Transfer;

using prt_test::CountingAllocator;

// An `sh` asset in its own context.
struct GlAsset {
  Transfer transfer;
  ContextPtr context;
  std::unique_ptr<LoadedAsset> loaded;
  GlAsset(const Transfer& t, prt_backend limit = PRT_BACKEND_AUTO, bool zstd = false,
          const prt_allocator* allocator = nullptr)
      : transfer(t) {
    context = prt_test::limited_context(limit, PRT_SIMD_ISA_AUTO, allocator);
    prt_context* ctx = context.get();
    loaded = std::make_unique<LoadedAsset>(
        ctx, prt_test::make_blob(prt_test::encode(t), t.vertices, zstd));
    EXPECT_EQ(loaded->result, PRT_OK) << prt_context_last_message(ctx);
  }
  const prt_asset* asset() const { return loaded->asset; }
  std::string message() const { return prt_context_last_message(context.get()); }
};

ShaderPtr create_shader(const GlAsset& a, headless_gl* gl) {
  prt_gl_sh_shader* shader = nullptr;
  EXPECT_EQ(prt_gl_sh_create(a.context.get(), a.asset(), headless_gl_get_proc, gl, &shader), PRT_OK)
      << a.message();
  return ShaderPtr(shader);
}

// Creation of the asset's shader, for the shared refusal checks (gl_create_checks.hpp).
prt_test::TryCreateShader try_create(const GlAsset& a) {
  return [&a](prt_context* context, prt_gl_loader_fn loader, void* user, bool* shader_null) {
    prt_gl_sh_shader* shader = nullptr;
    const prt_result r = prt_gl_sh_create(context, a.asset(), loader, user, &shader);
    *shader_null = shader == nullptr;
    prt_gl_sh_destroy(shader);
    return r;
  };
}

std::vector<float> read_all(prt_gl_sh_shader* shader, uint32_t vertices) {
  std::vector<float> rgb(3 * size_t(vertices), -12345.0f);
  EXPECT_EQ(prt_gl_sh_read(shader, 0, vertices, rgb.data()), PRT_OK);
  return rgb;
}

// Expects rgb[3 i + c] (i < count) to be vertex first + i under light, within the tolerance.
void expect_matches(const Transfer& t, const std::vector<float>& light, const float* rgb,
                    uint32_t first, uint32_t count) {
  int failures = 0;
  for (uint32_t i = 0; i < count && failures < 10; ++i)
    for (uint32_t c = 0; c < 3; ++c) {
      const prt_test::Expected e = prt_test::expected_radiance(t, light, first + i, c);
      const double got = rgb[3 * size_t(i) + c];
      if (std::fabs(got - e.value) > prt_test::tolerance(t.order, e.magnitude)) {
        ADD_FAILURE() << "vertex " << first + i << " channel " << c << ": " << got << " vs "
                      << e.value << " (tolerance " << prt_test::tolerance(t.order, e.magnitude)
                      << ")";
        ++failures;
      }
    }
}

TEST(GlSh, ShadesLikeTheExactSumForEveryLayout) {
  PRT_REQUIRE_GL(gl);
  // 131 vertices: three work groups of 64, the last one partial.
  for (uint32_t order : {1u, 2u, 6u, 8u, 16u})
    for (uint32_t channels : {1u, 3u})
      for (uint32_t bits : {8u, 16u}) {
        SCOPED_TRACE("order " + std::to_string(order) + ", channels " + std::to_string(channels) +
                     ", bits " + std::to_string(bits));
        const GlAsset a(prt_test::random_transfer(order, 131, channels, bits, order * 7 + bits));
        const std::vector<float> light = prt_test::realistic_light(order, order + channels);
        ShaderPtr shader = create_shader(a, gl.gl);
        ASSERT_TRUE(shader);
        ASSERT_EQ(prt_gl_sh_shade(shader.get(), light.data(), 0, 131), PRT_OK);
        const std::vector<float> rgb = read_all(shader.get(), 131);
        expect_matches(a.transfer, light, rgb.data(), 0, 131);
      }
}

TEST(GlSh, ZstdCompressedSectionShadesTheSame) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::random_transfer(4, 200, 3, 16, 99), PRT_BACKEND_AUTO, true);
  const std::vector<float> light = prt_test::realistic_light(4, 5);
  ShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  ASSERT_EQ(prt_gl_sh_shade(shader.get(), light.data(), 0, 200), PRT_OK);
  expect_matches(a.transfer, light, read_all(shader.get(), 200).data(), 0, 200);
}

TEST(GlSh, RangesShadeOnlyTheirVertices) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 300;
  const GlAsset a(prt_test::random_transfer(3, n, 3, 16, 11));
  const std::vector<float> light_a = prt_test::realistic_light(3, 1);
  std::vector<float> light_b = prt_test::realistic_light(3, 2);
  for (float& l : light_b) l = -0.5f * l;
  ShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  ASSERT_EQ(prt_gl_sh_shade(shader.get(), light_a.data(), 0, n), PRT_OK);
  ASSERT_EQ(prt_gl_sh_shade(shader.get(), light_b.data(), 70, 100), PRT_OK);
  ASSERT_EQ(prt_gl_sh_shade(shader.get(), light_b.data(), n, 0), PRT_OK) << "empty range at end";
  std::vector<float> rgb = read_all(shader.get(), n);
  expect_matches(a.transfer, light_a, rgb.data(), 0, 70);
  expect_matches(a.transfer, light_b, rgb.data() + 3 * 70, 70, 100);
  expect_matches(a.transfer, light_a, rgb.data() + 3 * 170, 170, n - 170);

  // A partial read returns exactly that slice.
  std::vector<float> slice(3 * 33);
  ASSERT_EQ(prt_gl_sh_read(shader.get(), 150, 33, slice.data()), PRT_OK);
  EXPECT_TRUE(std::equal(slice.begin(), slice.end(), rgb.begin() + 3 * 150));

  // Two halves shaded separately (as a job system would split them) cover the whole asset.
  ASSERT_EQ(prt_gl_sh_shade(shader.get(), light_b.data(), 0, 123), PRT_OK);
  ASSERT_EQ(prt_gl_sh_shade(shader.get(), light_b.data(), 123, n - 123), PRT_OK);
  expect_matches(a.transfer, light_b, read_all(shader.get(), n).data(), 0, n);
}

TEST(GlSh, OutputBufferIsTightlyPackedRgbAndStateIsLeftUnbound) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 77;
  const GlAsset a(prt_test::random_transfer(2, n, 1, 8, 3));
  const std::vector<float> light = prt_test::realistic_light(2, 3);
  ShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  ASSERT_EQ(prt_gl_sh_shade(shader.get(), light.data(), 0, n), PRT_OK);
  const uint32_t buffer = prt_gl_sh_output_buffer(shader.get());
  ASSERT_NE(buffer, 0u);

  // The program and the buffer bindings the backend uses are back to 0.
  prt_test::expect_gl_bindings_cleared();

  // Read the whole buffer through GL itself: 12 bytes per vertex, RGB floats, nothing else.
  int size = 0;
  const std::vector<float> rgb = prt_test::read_gl_buffer_floats(buffer, &size);
  ASSERT_EQ(size, int(12 * n));
  expect_matches(a.transfer, light, rgb.data(), 0, n);
  EXPECT_EQ(read_all(shader.get(), n), rgb) << "prt_gl_sh_read returns the buffer's bytes";
}

TEST(GlSh, ErrorsTheApplicationLeftPendingDoNotFailCreation) {
  PRT_REQUIRE_GL(gl);
  prt_test::leave_gl_error_pending();
  const GlAsset a(prt_test::random_transfer(2, 10, 1, 8, 6));
  EXPECT_TRUE(create_shader(a, gl.gl));
  EXPECT_EQ(prt_test::take_gl_error(), 0u) << "create cleared the pending error and raised none";
}

TEST(GlSh, ManyVerticesSpanSeveralDispatches) {
  PRT_REQUIRE_GL(gl);
  // More than 65535 work groups of 64 (the dispatch limit GL guarantees) needs two dispatches.
  const uint32_t n = 65535u * 64u + 1000u;
  const GlAsset a(prt_test::random_transfer(1, n, 1, 8, 5));
  const std::vector<float> light = {2.0f, 3.0f, 5.0f};
  ShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  ASSERT_EQ(prt_gl_sh_shade(shader.get(), light.data(), 0, n), PRT_OK);
  const std::vector<float> rgb = read_all(shader.get(), n);
  for (uint32_t v : {0u, 65535u * 64u - 1u, 65535u * 64u, n - 1u})
    expect_matches(a.transfer, light, rgb.data() + 3 * size_t(v), v, 1);
  expect_matches(a.transfer, light, rgb.data(), 0, n);
}

TEST(GlSh, AssetWithoutVerticesShadesNothing) {
  PRT_REQUIRE_GL(gl);
  const Transfer t = prt_test::random_transfer(3, 0, 3, 8, 1);
  prt::format::BlobWriter w;
  prt::format::SectionOptions required;
  required.required = true;
  const prt_test::Bytes shtr = prt_test::encode(t);
  w.add_section(prt_test::kVPOS, nullptr, 0, 0, required);
  w.add_section(prt_test::kSHTR, shtr.data(), shtr.size(), 0, required);
  const prt::ContextPtr ctx = prt_test::limited_context();
  LoadedAsset loaded(ctx.get(), w.finish());
  ASSERT_EQ(loaded.result, PRT_OK) << prt_context_last_message(ctx.get());
  prt_gl_sh_shader* raw = nullptr;
  ASSERT_EQ(prt_gl_sh_create(ctx.get(), loaded.asset, headless_gl_get_proc, gl.gl, &raw), PRT_OK)
      << prt_context_last_message(ctx.get());
  ShaderPtr shader(raw);
  const std::vector<float> light = prt_test::realistic_light(3, 1);
  EXPECT_EQ(prt_gl_sh_shade(raw, light.data(), 0, 0), PRT_OK);
  EXPECT_EQ(prt_gl_sh_read(raw, 0, 0, nullptr), PRT_OK);
  EXPECT_EQ(prt_gl_sh_shade(raw, light.data(), 0, 1), PRT_ERROR_INVALID_ARGUMENT);
}

TEST(GlSh, NoShtrSectionIsNotFound) {
  PRT_REQUIRE_GL(gl);
  const prt::ContextPtr ctx = prt_test::limited_context();
  LoadedAsset loaded(ctx.get(), prt_test::mesh_only_blob());
  ASSERT_EQ(loaded.result, PRT_OK);
  prt_gl_sh_shader* shader = reinterpret_cast<prt_gl_sh_shader*>(&loaded);
  EXPECT_EQ(prt_gl_sh_create(ctx.get(), loaded.asset, headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(shader, nullptr);
  EXPECT_NE(std::string(prt_context_last_message(ctx.get())).find("SHTR"), std::string::npos);
}

TEST(GlSh, MissingEntryPointIsUnsupportedAndNamed) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::random_transfer(2, 8, 3, 8, 1));
  prt_test::expect_refused_without_entry_points(
      try_create(a), a.context.get(), gl.gl,
      {"glDispatchCompute", "glMemoryBarrier", "glGetBufferSubData", "glProgramUniform1ui",
       "glGetError"});
}

TEST(GlSh, ContextOlderThan43IsUnsupported) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::random_transfer(2, 8, 3, 8, 1));
  prt_test::expect_refused_below_gl_43(try_create(a), a.context.get());
}

TEST(GlSh, AssetLargerThanTheSsboLimitIsUnsupported) {
  PRT_REQUIRE_GL(gl);
  // 100 vertices * 12 bytes of output > 1024 bytes.
  const GlAsset a(prt_test::random_transfer(1, 100, 1, 8, 1));
  prt_test::expect_refused_above_ssbo_limit(try_create(a), a.context.get());
}

TEST(GlSh, BackendLimitBelowGlIsUnsupported) {
  PRT_REQUIRE_GL(gl);
  for (prt_backend limit : {PRT_BACKEND_CPU, PRT_BACKEND_SIMD}) {
    const GlAsset a(prt_test::random_transfer(2, 8, 3, 8, 1), limit);
    prt_gl_sh_shader* shader = nullptr;
    EXPECT_EQ(prt_gl_sh_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
              PRT_ERROR_UNSUPPORTED_BACKEND);
    EXPECT_EQ(shader, nullptr);
    prt_backend_info info = prt::sized<prt_backend_info>();
    ASSERT_EQ(prt_backend_get_info(a.context.get(), PRT_BACKEND_GL, &info), PRT_OK);
    EXPECT_EQ(info.usable, 0u);
  }
  const GlAsset a(prt_test::random_transfer(2, 8, 3, 8, 1), PRT_BACKEND_GL);
  EXPECT_TRUE(create_shader(a, gl.gl));
  prt_backend_info info = prt::sized<prt_backend_info>();
  ASSERT_EQ(prt_backend_get_info(a.context.get(), PRT_BACKEND_GL, &info), PRT_OK);
  EXPECT_EQ(info.compiled, 1u);
  EXPECT_EQ(info.usable, 1u);
}

TEST(GlSh, BadRangesAreInvalidArguments) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 50;
  const GlAsset a(prt_test::random_transfer(2, n, 1, 16, 2));
  const std::vector<float> light = prt_test::realistic_light(2, 1);
  ShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  std::vector<float> rgb(3 * size_t(n) + 3);
  const uint32_t bad[][2] = {{n + 1, 0}, {0, n + 1}, {n - 1, 2}, {1, UINT32_MAX}, {UINT32_MAX, 1}};
  for (const auto& range : bad) {
    EXPECT_EQ(prt_gl_sh_shade(shader.get(), light.data(), range[0], range[1]),
              PRT_ERROR_INVALID_ARGUMENT)
        << range[0] << " + " << range[1];
    EXPECT_EQ(prt_gl_sh_read(shader.get(), range[0], range[1], rgb.data()),
              PRT_ERROR_INVALID_ARGUMENT)
        << range[0] << " + " << range[1];
  }
  EXPECT_EQ(prt_gl_sh_shade(shader.get(), nullptr, 0, n), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_sh_read(shader.get(), 0, n, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_sh_read(shader.get(), n, 0, nullptr), PRT_OK) << "empty read";
  // Per-frame calls report through their result only: no context was written.
  EXPECT_EQ(prt_context_last_result(a.context.get()), PRT_OK) << a.message();
}

// The shader reports to the context it is created with, which need not be the asset's: the
// asset's context sees nothing, and the creating context's backend limit decides.
TEST(GlSh, CreateReportsToTheCallersContext) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::random_transfer(2, 8, 3, 8, 1));
  const prt::ContextPtr limited = prt_test::limited_context(PRT_BACKEND_SIMD);
  prt_gl_sh_shader* shader = nullptr;
  EXPECT_EQ(prt_gl_sh_create(limited.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_UNSUPPORTED_BACKEND);
  EXPECT_EQ(shader, nullptr);
  EXPECT_EQ(prt_context_last_result(limited.get()), PRT_ERROR_UNSUPPORTED_BACKEND);
  EXPECT_NE(std::string(prt_context_last_message(limited.get())).find("prt_gl_sh_create"),
            std::string::npos);
  EXPECT_EQ(prt_context_last_result(a.context.get()), PRT_OK) << a.message();
  const prt::ContextPtr render = prt_test::limited_context();
  ASSERT_EQ(prt_gl_sh_create(render.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader), PRT_OK)
      << prt_context_last_message(render.get());
  ShaderPtr owned(shader);
  const std::vector<float> light = prt_test::realistic_light(2, 3);
  ASSERT_EQ(prt_gl_sh_shade(shader, light.data(), 0, 8), PRT_OK);
  expect_matches(a.transfer, light, read_all(shader, 8).data(), 0, 8);
}

TEST(GlSh, NullArguments) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::random_transfer(2, 8, 3, 8, 1));
  prt_gl_sh_shader* shader = nullptr;
  EXPECT_EQ(prt_gl_sh_create(nullptr, a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_sh_create(a.context.get(), nullptr, headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_sh_create(a.context.get(), a.asset(), nullptr, gl.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_sh_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(shader, nullptr);
  const float light[12] = {};
  float rgb[3];
  EXPECT_EQ(prt_gl_sh_shade(nullptr, light, 0, 1), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_sh_read(nullptr, 0, 1, rgb), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_sh_output_buffer(nullptr), 0u);
  prt_gl_sh_destroy(nullptr);  // ignored
}

TEST(GlSh, ShaderComesFromTheAssetsAllocator) {
  PRT_REQUIRE_GL(gl);
  CountingAllocator counter;
  const prt_allocator allocator = counter.api();
  const GlAsset a(prt_test::random_transfer(3, 40, 3, 8, 4), PRT_BACKEND_AUTO, false, &allocator);
  const int before = counter.live;
  prt_gl_sh_shader* shader = nullptr;
  ASSERT_EQ(prt_gl_sh_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_OK);
  EXPECT_GT(counter.live, before);
  prt_gl_sh_destroy(shader);
  EXPECT_EQ(counter.live, before);

  counter.fail = true;
  EXPECT_EQ(prt_gl_sh_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(shader, nullptr);
  counter.fail = false;
  EXPECT_EQ(counter.live, before);
}

TEST(GlSh, ReportsTheRenderer) {
  PRT_REQUIRE_GL(gl);
  EXPECT_STRNE(headless_gl_renderer(gl.gl), "");
  EXPECT_STREQ(headless_gl_renderer(nullptr), "");
  std::printf("GL renderer: %s\n", headless_gl_renderer(gl.gl));
}

}  // namespace
