// SPDX-License-Identifier: MIT
// Backend conformance of `cloth` (tests/gl/conformance.hpp): the golden cloth blob
// (formats/golden/1.0/cloth_quad.prtk: linen and velvet, real tables baked on a small grid, 8-bit)
// shaded over a G-buffer of random valid samples (37 x 29, a count no blocking of 8 divides, with
// pixels that are not cloth and views below the surface) under random lights, with moderate and
// grazing views and with the finest settings, on the scalar reference, the SIMD backend per
// instruction set (through prt_cloth_shade) and GL (through prt_gl_cloth_shade into a float
// framebuffer), each within the float bound of cloth_gl_target.hpp: 2 D + 32 u S per pixel and
// channel (tests/cloth/gl/cloth_gl_test.cpp derives it).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cloth/gl/cloth_gl_target.hpp"
#include "gl/conformance.hpp"
#include "support/gl_test_util.hpp"
#include "support/limited_context.hpp"
#include "support/mesh_blob.hpp"

namespace prt_conformance {
namespace {

using prt_test::GBufferSamples;
using prt_test::Reference;

const float kClear[4] = {-1.0f, -2.0f, -3.0f, -4.0f};

prt_test::Bytes golden_blob() {
  std::ifstream in(std::string(PRT_SOURCE_DIR) + "/formats/golden/1.0/cloth_quad.prtk",
                   std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The largest |error| / tolerance of `rgb` (3 per sample) against the reference over the cloth
// samples, failing the test at the first few samples outside.
double compare(const char* what, const Reference& r, const GBufferSamples& g,
               const std::vector<float>& rgb, size_t stride, const std::vector<size_t>& at) {
  double worst = 0.0;
  int failures = 0;
  for (uint32_t i = 0; i < g.count(); ++i) {
    if (!g.cloth[i]) continue;
    for (int c = 0; c < 3; ++c) {
      const double err = std::fabs(double(rgb[stride * at[i] + size_t(c)]) - r.value[3 * i + c]);
      const double tol = r.tolerance[3 * i + c];
      worst = std::max(worst, tol > 0 ? err / tol : (err > 0 ? 1e30 : 0.0));
      if (!(err <= tol) && failures++ < 5)
        ADD_FAILURE() << what << ": sample " << i << " channel " << c << ": "
                      << rgb[stride * at[i] + size_t(c)] << ", reference " << r.value[3 * i + c]
                      << ", tolerance " << tol;
    }
  }
  return worst;
}

void check_all_backends(uint32_t fabric, bool grazing, uint32_t segments, uint32_t nodes) {
  PRT_REQUIRE_GL(gl);
  const prt_test::Bytes blob = golden_blob();
  ASSERT_FALSE(blob.empty()) << "formats/golden/1.0/cloth_quad.prtk is missing";
  GBufferSamples g = prt_test::random_gbuffer(37, 29, 11 + fabric);
  if (grazing) prt_test::make_views_grazing(g, 13 + fabric);
  const std::vector<prt_cloth_lobe> lobes = prt_test::random_lobes(10, 7 + fabric);
  const prt_cloth_light light = prt_test::light_of(lobes);
  const prt_cloth_settings settings = prt_test::settings_of(0, segments, nodes);
  Summary summary(std::string(fabric == 0 ? "linen" : "velvet") + (grazing ? ", grazing" : "") +
                  ", " + std::to_string(segments) + " panels, " + std::to_string(nodes) +
                  " phi nodes");

  const prt::ContextPtr cpu_ctx = prt_test::limited_context();
  prt_test::LoadedAsset cpu_asset(cpu_ctx.get(), blob);
  ASSERT_EQ(cpu_asset.result, PRT_OK) << prt_context_last_message(cpu_ctx.get());
  const Reference r = prt_test::reference(cpu_asset.asset, fabric, nullptr, lobes, &settings, g);
  std::vector<size_t> same(g.count());
  for (size_t i = 0; i < same.size(); ++i) same[i] = i;

  for_each_simd_isa(summary, [&](prt_context* ctx, const std::string& name) {
    prt_test::LoadedAsset asset(ctx, blob);
    ASSERT_EQ(asset.result, PRT_OK);
    std::vector<float> rgb(3 * size_t(g.count()));
    const prt_cloth_pixels pixels = g.pixels();
    const prt_result result = prt_cloth_shade(asset.asset, PRT_BACKEND_SIMD, fabric, nullptr,
                                              &light, &settings, &pixels, 0, g.count(), rgb.data());
    if (result == PRT_ERROR_UNSUPPORTED_BACKEND) {
      summary.skip(name, "no cloth kernel for this instruction set");
      return;
    }
    ASSERT_EQ(result, PRT_OK);
    summary.note(name, compare(name.c_str(), r, g, rgb, 3, same));
  });

  {
    const prt::ContextPtr ctx = prt_test::limited_context();
    prt_test::LoadedAsset asset(ctx.get(), blob);
    ASSERT_EQ(asset.result, PRT_OK);
    prt_gl_cloth_shader* raw = nullptr;
    ASSERT_EQ(prt_gl_cloth_create(ctx.get(), asset.asset, headless_gl_get_proc, gl.gl, &raw),
              PRT_OK)
        << prt_context_last_message(ctx.get());
    const prt_test::GlClothShaderPtr shader(raw);
    const prt_test::GlCalls calls;
    prt_test::GlTarget target(calls, g, 6, 2, kClear);
    const prt_gl_cloth_gbuffer gbuffer = target.gbuffer();
    ASSERT_EQ(prt_gl_cloth_shade(raw, fabric, nullptr, &light, &settings, &gbuffer), PRT_OK);
    const std::vector<float> rgba = target.read();
    std::vector<size_t> texel(g.count());
    for (size_t i = 0; i < texel.size(); ++i) texel[i] = target.texel_of(i);
    summary.note("gl (" + std::string(headless_gl_renderer(gl.gl)) + ")",
                 compare("gl", r, g, rgba, 4, texel));
  }
  summary.print("cloth");
}

}  // namespace

std::vector<Case> cloth_cases() {
  return {
      {"LinenDefaults", [] { check_all_backends(0, false, 0, 0); }},
      {"VelvetDefaults", [] { check_all_backends(1, false, 0, 0); }},
      {"LinenGrazingFinest", [] { check_all_backends(0, true, 8, 8); }},
      {"VelvetGrazingCoarsest", [] { check_all_backends(1, true, 1, 1); }},
  };
}

}  // namespace prt_conformance
