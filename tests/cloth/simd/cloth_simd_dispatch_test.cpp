// SPDX-License-Identifier: MIT
// Which backend prt_cloth_shade runs on (support/simd_dispatch.hpp's rules), on the small
// hand-written CLTH section (cloth/clth_test_section.hpp: odd ranks, 8-bit values), so that it
// runs in every build, the one without SIMD included; and where calls with the paper's study
// switches (PRT_CLOTH_PAPER_*, scalar only) run.
#include <gtest/gtest.h>

#include <prt/prt_cloth_asset.h>
#include <prt/prt.hpp>

#include <cmath>
#include <vector>

#include "cloth/clth_test_section.hpp"
#include "support/limited_context.hpp"
#include "support/simd_dispatch.hpp"

namespace {

const prt_test::Bytes& small_blob() {
  static const prt_test::Bytes blob = prt_test::clth_blob(prt_test::small_clth().bytes(), 2);
  return blob;
}

prt_result shade_with(const prt_asset* asset, prt_backend backend, const prt_cloth_params* params,
                      const prt_cloth_settings* settings, std::vector<float>* out) {
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
  return prt_cloth_shade(asset, backend, 0, params, &light, settings, &pixels, 0, 3, out->data());
}

prt_result shade_all(const prt_asset* asset, prt_backend backend, std::vector<float>* out) {
  return shade_with(asset, backend, nullptr, nullptr, out);
}

prt_cloth_settings settings_of(uint32_t flags) {
  prt_cloth_settings s = prt::sized<prt_cloth_settings>();
  s.flags = flags;
  return s;
}

const uint32_t kPaperFlags[] = {PRT_CLOTH_PAPER_PHI_DOMAIN, PRT_CLOTH_PAPER_THETA_SEGMENTS,
                                PRT_CLOTH_PAPER_FRESNEL, PRT_CLOTH_PAPER_NARROW_GU,
                                PRT_CLOTH_PAPER_FLAGS | PRT_CLOTH_NO_CONE_TABLE};

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

// As the header says: a paper switch runs on the scalar reference under AUTO (where AUTO would
// pick SIMD) and is refused on an explicit SIMD call, as when the ISA lacks AVX2.
TEST(ClothSimdDispatch, PaperSwitchesRunOnTheScalarReferenceOnly) {
  for (const uint32_t flags : kPaperFlags) {
    const prt_cloth_settings settings = settings_of(flags);
    const prt_test::DispatchRun run(
        small_blob(),
        [&](const prt_asset* asset, prt_backend backend, std::vector<float>* out) {
          return shade_with(asset, backend, nullptr, &settings, out);
        },
        PRT_BACKEND_AUTO, PRT_SIMD_ISA_AUTO);
    run.shade(PRT_BACKEND_SIMD, PRT_ERROR_UNSUPPORTED_BACKEND);
    EXPECT_TRUE(prt_test::same_bits(run.shade(PRT_BACKEND_AUTO), run.shade(PRT_BACKEND_CPU)))
        << "flags " << flags;
  }
}

// g_u as printed is the model's Gaussian of standard deviation gamma / sqrt 2: the switch shades
// as the fabric with both gammas of both threads so narrowed.
TEST(ClothSimdDispatch, PaperNarrowGuShadesAsGammasOverSqrt2) {
  const prt::ContextPtr context = prt_test::limited_context(PRT_BACKEND_CPU, PRT_SIMD_ISA_AUTO);
  const prt_test::LoadedAsset a(context.get(), small_blob());
  ASSERT_EQ(a.result, PRT_OK);
  prt_cloth_params narrowed = prt::sized<prt_cloth_params>();
  ASSERT_EQ(prt_cloth_get_fabric(a.asset, 0, nullptr, &narrowed, nullptr, nullptr), PRT_OK);
  for (prt_cloth_thread& t : narrowed.threads) {
    t.gamma_s = static_cast<float>(t.gamma_s / std::sqrt(2.0));
    t.gamma_v = static_cast<float>(t.gamma_v / std::sqrt(2.0));
  }
  const prt_cloth_settings paper = settings_of(PRT_CLOTH_PAPER_NARROW_GU);
  std::vector<float> printed, expected, model;
  ASSERT_EQ(shade_with(a.asset, PRT_BACKEND_CPU, nullptr, &paper, &printed), PRT_OK);
  ASSERT_EQ(shade_with(a.asset, PRT_BACKEND_CPU, &narrowed, nullptr, &expected), PRT_OK);
  ASSERT_EQ(shade_with(a.asset, PRT_BACKEND_CPU, nullptr, nullptr, &model), PRT_OK);
  EXPECT_TRUE(prt_test::same_bits(printed, expected));
  EXPECT_FALSE(prt_test::same_bits(printed, model)) << "the switch changed nothing";
}

}  // namespace
