// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s sharpest lobes through the whole pipeline (issue 15, "Extremes"):
// Phong n = 1000 and GGX alpha = 0.01, far narrower than the BRDF table's cells, separated,
// baked onto a sphere, written to blobs, loaded and shaded on the scalar backend and on the best
// one (SIMD where the machine has it). The output must be finite and within a bound that holds
// whatever the truncation makes of such a lobe.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "shadowfield_bake_scenes.hpp"

namespace prt::bake::test {
namespace {

const glm::vec3 kAlbedo(0.9f, 0.6f, 0.3f);
constexpr float kSky = 1.5f;

// The largest |sum_k g_k(wo_i) h_k(w_j)| over the table's cells. Bilinear reads of g and h are
// convex combinations of cell values, so no interpolated direction pair exceeds it.
double largest_separated_value(const SeparableBrdf& brdf) {
  double largest = 0.0;
  for (std::uint32_t i = 0; i < brdf.grid.count(); ++i)
    for (std::uint32_t j = 0; j < brdf.grid.count(); ++j) {
      double value = 0.0;
      for (std::uint32_t k = 0; k < brdf.terms; ++k) value += brdf.g(k, i) * brdf.h(k, j);
      largest = std::max(largest, std::abs(value));
    }
  return largest;
}

bool all_finite(const std::vector<float>& values) {
  return std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); });
}

double max_abs(const std::vector<float>& values) {
  double largest = 0.0;
  for (const float v : values) largest = std::max(largest, double(std::fabs(v)));
  return largest;
}

// A lone convex sphere under a constant sky: every vertex's transfer is the cosine-weighted
// Monte Carlo estimate of integral f_K(w, wo) L cos(w) dw with no occlusion, so its radiance is
// at most albedo x L x pi x the largest separated value (each sample's f_K is within it, the
// cosine-weighted estimator's weight is pi / samples). The exact lobes reflect at most albedo x
// L (normalised Phong, GGX with f0 <= 1); K terms on a grid coarser than the lobe cannot match
// that reference. Phong 1000 stays within it. GGX 0.01 does not: the table samples f at cell
// centres, and where a cell's mirror is a cell centre the lobe's peak stands for the whole cell,
// so that separation reflects more than the exact BRDF could; only the bound above holds for
// it. The same scene with a floor and three bounces must stay finite.
TEST(ShadowfieldBakeExtremes, PhongThousandAndGgxHundredthShadeFiniteAndBounded) {
  ShadowfieldMaterialDescription phong;
  phong.model = ShadowfieldBrdfModel::Phong;
  phong.phong = PhongBrdf{1000.0, 1.0, 0.0};
  ShadowfieldMaterialDescription ggx;
  ggx.model = ShadowfieldBrdfModel::Ggx;
  ggx.ggx = GgxBrdf{0.01, 0.9};
  const Mesh sphere = make_sphere_mesh(0, glm::vec3(0.0f, 1.0f, 0.0f), 0.5f, 12, 24);
  const Mesh floor = make_plane_mesh("floor", 0, 1.5f, 1.5f, 6, 6);
  ShadowfieldBakeSettings settings = small_bake_settings(3);
  settings.fields.oof_shells = 4;
  settings.fields.oof_face_size = 4;
  settings.basis.size = 4;
  settings.basis.lights = 16;
  settings.srf.shells = 3;
  settings.srf.face_size = 3;
  settings.srf.directions = 256;
  const std::vector<std::uint8_t> floor_blob =
      diffuse_blob(one_mesh_scene(floor, glm::vec3(0.7f)), settings);
  const std::vector<float> sky = constant_sky(3, kSky);
  const glm::vec3 eye(1.0f, 2.5f, 3.0f);

  for (const ShadowfieldMaterialDescription& description : {phong, ggx}) {
    const char* name = description.model == ShadowfieldBrdfModel::Phong ? "Phong 1000" : "GGX 0.01";
    const ShadowfieldMaterial material = make_shadowfield_material(description, settings.brdf);
    ASSERT_TRUE(material.glossy);
    for (const double value : material.brdf.outgoing) ASSERT_TRUE(std::isfinite(value)) << name;
    for (const double value : material.brdf.incident) ASSERT_TRUE(std::isfinite(value)) << name;
    const ShadowfieldBakeResult baked =
        bake_shadowfield_object(one_mesh_scene(sphere, kAlbedo), material, settings, Context{});
    const std::vector<std::uint8_t> blob = shadowfield_blob_of(baked.object, 16, "");
    const double bound = kSky * M_PI * largest_separated_value(material.brdf);

    for (const prt_backend backend : {PRT_BACKEND_CPU, PRT_BACKEND_AUTO}) {
      const std::vector<float> alone =
          shade_instances({blob}, {{0, glm::vec3(0.0f)}}, sky, eye, 0, backend)[0];
      ASSERT_EQ(alone.size(), 3 * sphere.positions.size());
      ASSERT_TRUE(all_finite(alone)) << name;
      double worst = 0.0;  // the largest |radiance| over the bound, over vertices and channels
      for (std::size_t v = 0; v < sphere.positions.size(); ++v)
        for (int c = 0; c < 3; ++c)
          worst = std::max(worst, std::fabs(alone[3 * v + c]) / (kAlbedo[c] * bound));
      EXPECT_LE(worst, 1.0) << name;
      if (description.model == ShadowfieldBrdfModel::Phong) {
        for (std::size_t v = 0; v < sphere.positions.size(); ++v)
          for (int c = 0; c < 3; ++c) EXPECT_LE(std::fabs(alone[3 * v + c]), kAlbedo[c] * kSky);
      }
      EXPECT_GT(max_abs(alone), 0.0) << name;  // lit: the check is not of zeros

      const std::vector<std::vector<float>> together = shade_instances(
          {blob, floor_blob}, {{0, glm::vec3(0.0f)}, {1, glm::vec3(0.0f)}}, sky, eye, 3, backend);
      ASSERT_TRUE(all_finite(together[0])) << name;
      ASSERT_TRUE(all_finite(together[1])) << name;
      std::printf(
          "%s, %s backend, %u of %u terms: sphere alone max |radiance| %.4g (%.3g of the "
          "bound), with the floor and 3 bounces max %.4g, floor max %.4g\n",
          name, backend == PRT_BACKEND_CPU ? "scalar" : "best", material.brdf.terms,
          material.brdf.requested_terms, max_abs(alone), worst, max_abs(together[0]),
          max_abs(together[1]));
    }
  }
}

}  // namespace
}  // namespace prt::bake::test
