// SPDX-License-Identifier: MIT
// The GL backend of `wavelet` (prt_wavelet_asset.h) on a headless EGL context: results against the
// exact double sum of the stored pairs and scales (wvlt_reference_shade, from blobs built byte by
// byte per formats/SPEC.md §7.2), rows of every shape, vertex ranges, the output buffer's layout
// and GL state, corrupt rows at quick validation, and every error path.
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

using prt_test::Bytes;
using prt_test::ContextPtr;
using prt_test::CountingAllocator;
using prt_test::LoadedAsset;
using prt_test::WaveletShaderPtr;
using prt_test::WvltTransfer;

constexpr prt_wavelet_param kCube = PRT_WAVELET_PARAM_CUBE,
                            kParaboloid = PRT_WAVELET_PARAM_DUAL_PARABOLOID;

// A `wavelet` asset in its own context.
struct GlAsset {
  WvltTransfer transfer;
  ContextPtr context;
  std::unique_ptr<LoadedAsset> loaded;
  GlAsset(const WvltTransfer& t, prt_backend limit = PRT_BACKEND_AUTO, bool zstd = false,
          const prt_allocator* allocator = nullptr, prt_validation validation = PRT_VALIDATE_FULL)
      : GlAsset(t, prt_test::wvlt_make_blob(prt_test::wvlt_encode(t), t.vertices, zstd), limit,
                allocator, validation) {}
  GlAsset(const WvltTransfer& t, const Bytes& blob, prt_backend limit,
          const prt_allocator* allocator, prt_validation validation)
      : transfer(t) {
    context = prt_test::limited_context(limit, PRT_SIMD_ISA_AUTO, allocator);
    prt_context* ctx = context.get();
    loaded = std::make_unique<LoadedAsset>(ctx, blob, validation);
    EXPECT_EQ(loaded->result, PRT_OK) << prt_context_last_message(ctx);
  }
  const prt_asset* asset() const { return loaded->asset; }
  std::string message() const { return prt_context_last_message(context.get()); }
};

WaveletShaderPtr create_shader(const GlAsset& a, headless_gl* gl) {
  prt_gl_wavelet_shader* shader = nullptr;
  EXPECT_EQ(prt_gl_wavelet_create(a.context.get(), a.asset(), headless_gl_get_proc, gl, &shader),
            PRT_OK)
      << a.message();
  return WaveletShaderPtr(shader);
}

// Creation of the asset's shader, for the shared refusal checks (gl_create_checks.hpp).
prt_test::TryCreateShader try_create(const GlAsset& a) {
  return [&a](prt_context* context, prt_gl_loader_fn loader, void* user, bool* shader_null) {
    prt_gl_wavelet_shader* shader = nullptr;
    const prt_result r = prt_gl_wavelet_create(context, a.asset(), loader, user, &shader);
    *shader_null = shader == nullptr;
    prt_gl_wavelet_destroy(shader);
    return r;
  };
}

std::vector<float> read_all(prt_gl_wavelet_shader* shader, uint32_t vertices) {
  std::vector<float> rgb(3 * size_t(vertices), -12345.0f);
  EXPECT_EQ(prt_gl_wavelet_read(shader, 0, vertices, rgb.data()), PRT_OK);
  return rgb;
}

// Shades all vertices under `light` (unprepared; prepared here independently of the runtime).
std::vector<float> shade_all(const GlAsset& a, prt_gl_wavelet_shader* shader,
                             const std::vector<float>& light) {
  const std::vector<float> prepared = prt_test::wavelet_prepared(a.transfer, light);
  EXPECT_EQ(prt_gl_wavelet_shade(shader, prepared.data(), 0, a.transfer.vertices), PRT_OK);
  return read_all(shader, a.transfer.vertices);
}

// Expects rgb[3 i + c] (i < count) to be vertex first + i under light, within the tolerance.
void expect_matches(const WvltTransfer& t, const std::vector<float>& light, const float* rgb,
                    uint32_t first, uint32_t count) {
  int failures = 0;
  for (uint32_t i = 0; i < count && failures < 10; ++i) {
    double value[3], magnitude[3];
    prt_test::wvlt_reference_shade(t, light, first + i, value, magnitude);
    for (uint32_t c = 0; c < 3; ++c) {
      const double tol = prt_test::wavelet_tolerance(t.rows[first + i].size(), magnitude[c]);
      const double got = rgb[3 * size_t(i) + c];
      if (std::fabs(got - value[c]) > tol) {
        ADD_FAILURE() << "vertex " << first + i << " channel " << c << ": " << got << " vs "
                      << value[c] << " (tolerance " << tol << ")";
        ++failures;
      }
    }
  }
}

TEST(GlWavelet, ShadesLikeTheExactSumForEveryShape) {
  PRT_REQUIRE_GL(gl);
  // 131 vertices: three work groups of 64, the last one partial.
  for (prt_wavelet_param param : {kCube, kParaboloid})
    for (uint32_t size : {16u, 64u})
      for (uint32_t nonzeros : {0u, 1u, 37u, 600u}) {
        SCOPED_TRACE("param " + std::to_string(param) + ", size " + std::to_string(size) +
                     ", non-zeros " + std::to_string(nonzeros));
        const GlAsset a(prt_test::wvlt_random(param, size, 131, nonzeros, size + nonzeros));
        const std::vector<float> light =
            prt_test::wvlt_random_light(a.transfer.coefficients(), param + 7);
        WaveletShaderPtr shader = create_shader(a, gl.gl);
        ASSERT_TRUE(shader);
        expect_matches(a.transfer, light, shade_all(a, shader.get(), light).data(), 0, 131);
      }
}

// Rows of the extreme shapes §7.2 allows: empty; one pair at the first and at the last
// coefficient; a block with all 256 non-zeros (and the blocks around it empty); a dense row (every
// coefficient stored); values ±127 and ±1; a vertex with scale 0.
TEST(GlWavelet, ExtremeRowsShadeExactly) {
  PRT_REQUIRE_GL(gl);
  const uint32_t size = 16, coefficients = 6 * size * size;
  std::vector<std::vector<int8_t>> dense(7, std::vector<int8_t>(coefficients, 0));
  dense[1][0] = 127;
  dense[2][coefficients - 1] = -127;
  for (uint32_t i = 0; i < 256; ++i) dense[3][256 * 2 + i] = int8_t(i % 2 ? -1 - int(i % 127) : 1);
  for (uint32_t j = 0; j < coefficients; ++j) dense[4][j] = int8_t(j % 2 ? 127 : -128 + 1 + j % 5);
  for (uint32_t j = 0; j < coefficients; j += 3) dense[5][j] = int8_t(1 + j % 100);
  dense[6] = dense[4];
  std::vector<float> band_scale(6 * 5);
  for (size_t b = 0; b < band_scale.size(); ++b) band_scale[b] = 0.25f + 0.01f * float(b);
  std::vector<float> vertex_scale(3 * 7, 1.5f);
  vertex_scale[3 * 6 + 0] = vertex_scale[3 * 6 + 1] = vertex_scale[3 * 6 + 2] = 0.0f;
  const GlAsset a(prt_test::wvlt_from_dense(kCube, size, dense, band_scale, vertex_scale));
  ASSERT_EQ(a.transfer.rows[3].size(), 256u);
  ASSERT_EQ(a.transfer.rows[4].size(), coefficients);
  const std::vector<float> light = prt_test::wvlt_random_light(coefficients, 3);
  WaveletShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const std::vector<float> rgb = shade_all(a, shader.get(), light);
  expect_matches(a.transfer, light, rgb.data(), 0, 7);
  for (uint32_t c = 0; c < 3; ++c) {
    EXPECT_EQ(rgb[c], 0.0f) << "an empty row is exactly 0";
    EXPECT_EQ(rgb[3 * 6 + c], 0.0f) << "a vertex scale of 0 gives exactly 0";
  }
  // One pair, two float products: q * prepared, then * vs, each rounded once (2u relative).
  const double one_pair = 127.0 * double(prt_test::wavelet_prepared(a.transfer, light)[0]) * 1.5;
  EXPECT_NEAR(rgb[3], one_pair, std::fabs(one_pair) * 4e-7);
}

TEST(GlWavelet, ZstdCompressedSectionShadesTheSame) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::wvlt_random(kCube, 32, 200, 300, 99), PRT_BACKEND_AUTO, true);
  const std::vector<float> light = prt_test::wvlt_random_light(a.transfer.coefficients(), 5);
  WaveletShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  expect_matches(a.transfer, light, shade_all(a, shader.get(), light).data(), 0, 200);
}

TEST(GlWavelet, RangesShadeOnlyTheirVertices) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 300;
  const GlAsset a(prt_test::wvlt_random(kParaboloid, 32, n, 120, 11));
  const std::vector<float> light_a = prt_test::wvlt_random_light(a.transfer.coefficients(), 1);
  const std::vector<float> light_b = prt_test::wvlt_random_light(a.transfer.coefficients(), 2);
  const std::vector<float> prepared_a = prt_test::wavelet_prepared(a.transfer, light_a);
  const std::vector<float> prepared_b = prt_test::wavelet_prepared(a.transfer, light_b);
  WaveletShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  ASSERT_EQ(prt_gl_wavelet_shade(shader.get(), prepared_a.data(), 0, n), PRT_OK);
  ASSERT_EQ(prt_gl_wavelet_shade(shader.get(), prepared_b.data(), 70, 100), PRT_OK);
  ASSERT_EQ(prt_gl_wavelet_shade(shader.get(), prepared_b.data(), n, 0), PRT_OK)
      << "empty range at end";
  std::vector<float> rgb = read_all(shader.get(), n);
  expect_matches(a.transfer, light_a, rgb.data(), 0, 70);
  expect_matches(a.transfer, light_b, rgb.data() + 3 * 70, 70, 100);
  expect_matches(a.transfer, light_a, rgb.data() + 3 * 170, 170, n - 170);

  // A partial read returns exactly that slice.
  std::vector<float> slice(3 * 33);
  ASSERT_EQ(prt_gl_wavelet_read(shader.get(), 150, 33, slice.data()), PRT_OK);
  EXPECT_TRUE(std::equal(slice.begin(), slice.end(), rgb.begin() + 3 * 150));

  // Two halves shaded separately (as a job system would split them) cover the whole asset.
  ASSERT_EQ(prt_gl_wavelet_shade(shader.get(), prepared_b.data(), 0, 123), PRT_OK);
  ASSERT_EQ(prt_gl_wavelet_shade(shader.get(), prepared_b.data(), 123, n - 123), PRT_OK);
  expect_matches(a.transfer, light_b, read_all(shader.get(), n).data(), 0, n);
}

TEST(GlWavelet, OutputBufferIsTightlyPackedRgbAndStateIsLeftUnbound) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 77;
  const GlAsset a(prt_test::wvlt_random(kCube, 16, n, 50, 3));
  const std::vector<float> light = prt_test::wvlt_random_light(a.transfer.coefficients(), 3);
  WaveletShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const std::vector<float> via_read = shade_all(a, shader.get(), light);
  const uint32_t buffer = prt_gl_wavelet_output_buffer(shader.get());
  ASSERT_NE(buffer, 0u);

  // The program and the buffer bindings the backend uses are back to 0.
  ASSERT_EQ(prt_gl_wavelet_shade(shader.get(), prt_test::wavelet_prepared(a.transfer, light).data(),
                                 0, n),
            PRT_OK);
  prt_test::expect_gl_bindings_cleared();

  // Read the whole buffer through GL itself: 12 bytes per vertex, RGB floats, nothing else.
  int size = 0;
  const std::vector<float> rgb = prt_test::read_gl_buffer_floats(buffer, &size);
  ASSERT_EQ(size, int(12 * n));
  expect_matches(a.transfer, light, rgb.data(), 0, n);
  EXPECT_EQ(via_read, rgb) << "prt_gl_wavelet_read returns the buffer's bytes";
}

TEST(GlWavelet, ErrorsTheApplicationLeftPendingDoNotFailCreation) {
  PRT_REQUIRE_GL(gl);
  prt_test::leave_gl_error_pending();
  const GlAsset a(prt_test::wvlt_random(kCube, 16, 10, 5, 6));
  EXPECT_TRUE(create_shader(a, gl.gl));
  EXPECT_EQ(prt_test::take_gl_error(), 0u) << "create cleared the pending error and raised none";
}

TEST(GlWavelet, ManyVerticesSpanSeveralDispatches) {
  PRT_REQUIRE_GL(gl);
  // The shader runs one work group per vertex, and GL guarantees 65535 groups per dispatch, so
  // this needs three dispatches; the vertices checked one by one sit at their seams.
  const uint32_t n = 2u * 65535u + 1000u;
  const GlAsset a(prt_test::wvlt_random(kParaboloid, 16, n, 1, 5));
  const std::vector<float> light = prt_test::wvlt_random_light(a.transfer.coefficients(), 9);
  WaveletShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const std::vector<float> rgb = shade_all(a, shader.get(), light);
  for (uint32_t v : {0u, 65534u, 65535u, 2u * 65535u - 1u, 2u * 65535u, n - 1u})
    expect_matches(a.transfer, light, rgb.data() + 3 * size_t(v), v, 1);
  expect_matches(a.transfer, light, rgb.data(), 0, n);
}

TEST(GlWavelet, AssetWithoutVerticesShadesNothing) {
  PRT_REQUIRE_GL(gl);
  WvltTransfer t = prt_test::wvlt_random(kCube, 16, 0, 10, 1);
  const Bytes wvlt = prt_test::wvlt_encode(t);
  prt::format::BlobWriter w;
  prt::format::SectionOptions required;
  required.required = true;
  w.add_section(prt_test::kWvltVPOS, nullptr, 0, 0, required);
  w.add_section(prt_test::kWvltWVLT, wvlt.data(), wvlt.size(), 0, required);
  const prt::ContextPtr ctx = prt_test::limited_context();
  LoadedAsset loaded(ctx.get(), w.finish());
  ASSERT_EQ(loaded.result, PRT_OK) << prt_context_last_message(ctx.get());
  prt_gl_wavelet_shader* raw = nullptr;
  ASSERT_EQ(prt_gl_wavelet_create(ctx.get(), loaded.asset, headless_gl_get_proc, gl.gl, &raw),
            PRT_OK)
      << prt_context_last_message(ctx.get());
  WaveletShaderPtr shader(raw);
  const std::vector<float> light = prt_test::wvlt_random_light(t.coefficients(), 1);
  EXPECT_EQ(prt_gl_wavelet_shade(raw, light.data(), 0, 0), PRT_OK);
  EXPECT_EQ(prt_gl_wavelet_read(raw, 0, 0, nullptr), PRT_OK);
  EXPECT_EQ(prt_gl_wavelet_shade(raw, light.data(), 0, 1), PRT_ERROR_INVALID_ARGUMENT);
}

TEST(GlWavelet, NoWvltSectionIsNotFound) {
  PRT_REQUIRE_GL(gl);
  const prt::ContextPtr ctx = prt_test::limited_context();
  LoadedAsset loaded(ctx.get(), prt_test::mesh_only_blob());
  ASSERT_EQ(loaded.result, PRT_OK);
  prt_gl_wavelet_shader* shader = reinterpret_cast<prt_gl_wavelet_shader*>(&loaded);
  EXPECT_EQ(prt_gl_wavelet_create(ctx.get(), loaded.asset, headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(shader, nullptr);
  EXPECT_NE(std::string(prt_context_last_message(ctx.get())).find("WVLT"), std::string::npos);
}

// Rows whose block counts and row starts lie (loaded at quick validation, which does not look at
// the rows): the shader clamps every read to its array, so shading completes with finite values
// and never reads outside the buffers (which llvmpipe would turn into a crash or garbage).
TEST(GlWavelet, CorruptRowsAtQuickValidationStayInBounds) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 40;
  const WvltTransfer t = prt_test::wvlt_random(kCube, 16, n, 20, 8);
  Bytes wvlt = prt_test::wvlt_encode(t);
  const prt_test::WvltOffsets o = prt_test::wvlt_offsets(t);
  for (uint32_t v = 0; v < n; v += 3)  // counts far above 256 and above the row's pairs
    prt_le_store_u16(wvlt.data() + o.counts + 2 * (size_t(v) * t.blocks() + v % t.blocks()),
                     uint16_t(v % 2 ? 65535 : 300));
  prt_le_store_u32(wvlt.data() + o.row_start + 4 * 5, 0xFFFFFFF0u);  // row 5 starts past P
  prt_le_store_u32(wvlt.data() + o.row_start + 4 * 9, 7u);           // rows 8, 9 overlap
  const Bytes blob = prt_test::wvlt_make_blob(wvlt, n);
  const GlAsset a(t, blob, PRT_BACKEND_AUTO, nullptr, PRT_VALIDATE_QUICK);
  ASSERT_EQ(a.loaded->result, PRT_OK) << "quick validation does not check the rows";
  WaveletShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const std::vector<float> light = prt_test::wvlt_random_light(t.coefficients(), 4);
  const std::vector<float> rgb = shade_all(a, shader.get(), light);
  for (float x : rgb) EXPECT_TRUE(std::isfinite(x));
  // Rows untouched by the corruption still shade exactly.
  expect_matches(t, light, rgb.data() + 3 * 1, 1, 2);
  // Full validation rejects the same bytes.
  const prt::ContextPtr ctx = prt_test::limited_context();
  LoadedAsset full(ctx.get(), blob, PRT_VALIDATE_FULL);
  EXPECT_NE(full.result, PRT_OK);
}

TEST(GlWavelet, MissingEntryPointIsUnsupportedAndNamed) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::wvlt_random(kCube, 16, 8, 4, 1));
  prt_test::expect_refused_without_entry_points(
      try_create(a), a.context.get(), gl.gl,
      {"glDispatchCompute", "glMemoryBarrier", "glGetBufferSubData", "glProgramUniform1ui",
       "glBufferSubData", "glGetError"});
}

TEST(GlWavelet, ContextOlderThan43IsUnsupported) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::wvlt_random(kCube, 16, 8, 4, 1));
  prt_test::expect_refused_below_gl_43(try_create(a), a.context.get());
}

TEST(GlWavelet, AssetLargerThanTheSsboLimitIsUnsupported) {
  PRT_REQUIRE_GL(gl);
  // The light alone is 16 * 1536 bytes > 1024.
  const GlAsset a(prt_test::wvlt_random(kCube, 16, 4, 4, 1));
  prt_test::expect_refused_above_ssbo_limit(try_create(a), a.context.get());
}

TEST(GlWavelet, BackendLimitBelowGlIsUnsupported) {
  PRT_REQUIRE_GL(gl);
  for (prt_backend limit : {PRT_BACKEND_CPU, PRT_BACKEND_SIMD}) {
    const GlAsset a(prt_test::wvlt_random(kCube, 16, 8, 4, 1), limit);
    prt_gl_wavelet_shader* shader = nullptr;
    EXPECT_EQ(
        prt_gl_wavelet_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
        PRT_ERROR_UNSUPPORTED_BACKEND);
    EXPECT_EQ(shader, nullptr);
  }
  const GlAsset a(prt_test::wvlt_random(kCube, 16, 8, 4, 1), PRT_BACKEND_GL);
  EXPECT_TRUE(create_shader(a, gl.gl));
}

TEST(GlWavelet, BadRangesAreInvalidArguments) {
  PRT_REQUIRE_GL(gl);
  const uint32_t n = 50;
  const GlAsset a(prt_test::wvlt_random(kCube, 16, n, 9, 2));
  const std::vector<float> light = prt_test::wvlt_random_light(a.transfer.coefficients(), 1);
  WaveletShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  std::vector<float> rgb(3 * size_t(n) + 3);
  const uint32_t bad[][2] = {{n + 1, 0}, {0, n + 1}, {n - 1, 2}, {1, UINT32_MAX}, {UINT32_MAX, 1}};
  for (const auto& range : bad) {
    EXPECT_EQ(prt_gl_wavelet_shade(shader.get(), light.data(), range[0], range[1]),
              PRT_ERROR_INVALID_ARGUMENT)
        << range[0] << " + " << range[1];
    EXPECT_EQ(prt_gl_wavelet_read(shader.get(), range[0], range[1], rgb.data()),
              PRT_ERROR_INVALID_ARGUMENT)
        << range[0] << " + " << range[1];
  }
  EXPECT_EQ(prt_gl_wavelet_shade(shader.get(), nullptr, 0, n), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_wavelet_read(shader.get(), 0, n, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_wavelet_read(shader.get(), n, 0, nullptr), PRT_OK) << "empty read";
  // Per-frame calls report through their result only: no context was written.
  EXPECT_EQ(prt_context_last_result(a.context.get()), PRT_OK) << a.message();
}

TEST(GlWavelet, NullArguments) {
  PRT_REQUIRE_GL(gl);
  const GlAsset a(prt_test::wvlt_random(kCube, 16, 8, 4, 1));
  prt_gl_wavelet_shader* shader = nullptr;
  EXPECT_EQ(prt_gl_wavelet_create(nullptr, a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_wavelet_create(a.context.get(), nullptr, headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_wavelet_create(a.context.get(), a.asset(), nullptr, gl.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_wavelet_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(shader, nullptr);
  const std::vector<float> light(4 * 1536);
  float rgb[3];
  EXPECT_EQ(prt_gl_wavelet_shade(nullptr, light.data(), 0, 1), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_wavelet_read(nullptr, 0, 1, rgb), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_wavelet_output_buffer(nullptr), 0u);
  prt_gl_wavelet_destroy(nullptr);  // ignored
}

TEST(GlWavelet, ShaderComesFromTheAssetsAllocator) {
  PRT_REQUIRE_GL(gl);
  CountingAllocator counter;
  const prt_allocator allocator = counter.api();
  const GlAsset a(prt_test::wvlt_random(kCube, 16, 40, 30, 4), PRT_BACKEND_AUTO, false, &allocator);
  const int before = counter.live;
  prt_gl_wavelet_shader* shader = nullptr;
  ASSERT_EQ(prt_gl_wavelet_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_OK);
  EXPECT_GT(counter.live, before);
  prt_gl_wavelet_destroy(shader);
  EXPECT_EQ(counter.live, before);

  counter.fail = true;
  EXPECT_EQ(prt_gl_wavelet_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(shader, nullptr);
  counter.fail = false;
  EXPECT_EQ(counter.live, before);
}

}  // namespace
