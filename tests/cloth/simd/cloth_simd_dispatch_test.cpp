// SPDX-License-Identifier: MIT
// Which backend prt_cloth_shade runs on (support/simd_dispatch.hpp's rules), on the small
// hand-written CLTH section (cloth/clth_test_section.hpp: odd ranks, 8-bit values), so that it
// runs in every build, the one without SIMD included.
#include <gtest/gtest.h>

#include <prt/prt_cloth_asset.h>
#include <prt/prt.hpp>

#include <vector>

#include "cloth/clth_test_section.hpp"
#include "support/limited_context.hpp"
#include "support/simd_dispatch.hpp"

namespace {

const prt_test::Bytes& small_blob() {
  static const prt_test::Bytes blob = prt_test::clth_blob(prt_test::small_clth().bytes(), 2);
  return blob;
}

prt_result shade_all(const prt_asset* asset, prt_backend backend, std::vector<float>* out) {
  const float normals[] = {0.0f, 0.0f, 1.0f, 0.0f, 0.6f, 0.8f, 0.0f, 0.0f, 1.0f};
  const float warps[] = {1.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.6f, 0.8f, 0.0f};
  const float views[] = {0.3f, 0.2f, 0.9f, 0.0f, 0.0f, 1.0f, -0.5f, 0.1f, 0.8f};
  prt_cloth_lobe lobes[2] = {{{0.0f, 0.6f, 0.8f}, 4.0f, {1.0f, 0.5f, 0.2f}},
                             {{0.8f, 0.0f, 0.6f}, 60.0f, {0.3f, 0.3f, 0.9f}}};
  prt_cloth_light light = prt::sized<prt_cloth_light>();
  light.lobe_count = 2;
  light.lobes = lobes;
  prt_cloth_pixels pixels = prt::sized<prt_cloth_pixels>();
  pixels.normals = normals;
  pixels.warps = warps;
  pixels.views = views;
  out->assign(9, -1.0f);
  return prt_cloth_shade(asset, backend, 0, nullptr, &light, nullptr, &pixels, 0, 3, out->data());
}

TEST(ClothSimdDispatch, AutoPicksSimdWhereUsable) {
  const prt_test::DispatchRun probe(small_blob(), shade_all, PRT_BACKEND_AUTO, PRT_SIMD_ISA_AUTO);
  if (!prt_test::simd_usable(probe.context())) GTEST_SKIP() << "SIMD not usable here";
  // AUTO gives SIMD's bits, which are not the scalar reference's (float against double)
  EXPECT_FALSE(prt_test::expect_auto_shades_as_simd(small_blob(), shade_all));
}

TEST(ClothSimdDispatch, Sse41LimitMakesSimdUnsupportedAndAutoScalar) {
  const prt_test::DispatchRun run(small_blob(), shade_all, PRT_BACKEND_AUTO, PRT_SIMD_ISA_SSE41);
  run.shade(PRT_BACKEND_SIMD, PRT_ERROR_UNSUPPORTED_BACKEND);
  EXPECT_TRUE(prt_test::same_bits(run.shade(PRT_BACKEND_AUTO), run.shade(PRT_BACKEND_CPU)));
}

TEST(ClothSimdDispatch, LimitsRefuseSimd) {
  prt_test::expect_cpu_limit_refuses_simd(small_blob(), shade_all);
  prt_test::expect_isa_limit_none_refuses_simd(small_blob(), shade_all);
  prt_test::expect_gl_not_shaded_here(small_blob(), shade_all);
}

TEST(ClothSimdDispatch, CompiledOutSimdIsUnsupported) {
  if (PRT_TEST_SIMD_COMPILED) GTEST_SKIP() << "SIMD compiled in";
  prt_test::expect_compiled_out_simd_unsupported(small_blob(), shade_all);
}

}  // namespace
