// SPDX-License-Identifier: MIT
// One object's whole bake through blob, runtime load, scene and shading, against analytic values:
// a lone convex sphere under a constant sky, a sphere's shadow on a floor below it (the
// cosine-weighted cap it hides) and the light the floor bounces back onto the sphere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "shadowfield_bake_scenes.hpp"

namespace prt::bake::test {
namespace {

const glm::vec3 kSphereAlbedo(0.7f, 0.5f, 0.3f);
const glm::vec3 kFloorAlbedo(0.6f, 0.6f, 0.6f);

// Band 0 of an unoccluded vertex's transfer is exact (the cosine-weighted estimator of a constant
// is the constant) and every vertex of a convex sphere is unoccluded, so under radiance 1 every
// vertex reflects its albedo; the constant row is stored exactly, so only float rounding and the
// few grazing rays that clip a neighbouring face remain.
TEST(ShadowfieldBake, LoneConvexSphereReflectsItsAlbedoUnderAConstantSky) {
  const Mesh sphere = make_sphere_mesh(0, glm::vec3(0.0f), 1.0f, 16, 32);
  const Scene scene = one_mesh_scene(sphere, kSphereAlbedo);
  const auto blob = diffuse_blob(scene, small_bake_settings(4));
  const auto rgb = shade_instances({blob}, {{0, glm::vec3(0.0f)}}, constant_sky(4, 1.0f),
                                   glm::vec3(0.0f, 0.0f, 5.0f), 0)[0];
  ASSERT_EQ(rgb.size(), 3 * sphere.positions.size());
  double worst = 0.0;
  for (std::size_t v = 0; v < sphere.positions.size(); ++v)
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(double(rgb[3 * v + c]) - kSphereAlbedo[c]));
  std::printf("lone sphere: max |radiance - albedo| %.3g\n", worst);
  EXPECT_LT(worst, 2e-7);  // a few float roundings of values below 1
}

// A sphere of radius a centred at height d above a floor patch; the floor vertex right below
// sees it as a cap of half-angle asin(a / d) about its normal, which hides (a / d)^2 of its
// cosine-weighted sky.
struct SphereOverFloor {
  static constexpr float a = 0.5f, d = 1.0f, half = 1.0f;
  Mesh sphere = make_sphere_mesh(0, glm::vec3(0.0f, d, 0.0f), a, 24, 48);
  Mesh floor = make_plane_mesh("floor", 0, half, half, 8, 8);
  std::vector<std::vector<std::uint8_t>> blobs;

  explicit SphereOverFloor(std::uint32_t order) {
    blobs.push_back(
        diffuse_blob(one_mesh_scene(sphere, kSphereAlbedo), small_bake_settings(order)));
    blobs.push_back(diffuse_blob(one_mesh_scene(floor, kFloorAlbedo), small_bake_settings(order)));
  }
  std::vector<std::vector<float>> shade(std::uint32_t order, std::uint32_t bounces) const {
    return shade_instances(blobs, {{0, glm::vec3(0.0f)}, {1, glm::vec3(0.0f)}},
                           constant_sky(order, 1.0f), glm::vec3(0.0f, 3.0f, 4.0f), bounces);
  }
  // The radiance of the floor vertex below the sphere's centre over its albedo.
  double floor_share(std::uint32_t order) const {
    const auto rgb = shade(order, 0);
    return rgb[1][3 * nearest_vertex(floor, glm::vec3(0.0f))] / kFloorAlbedo.x;
  }
};

// Legendre polynomial P_l(x).
double legendre(int l, double x) {
  double previous = 1.0, current = x;
  if (l == 0) return previous;
  for (int k = 2; k <= l; ++k) {
    const double next = ((2 * k - 1) * x * current - (k - 1) * previous) / k;
    previous = current;
    current = next;
  }
  return current;
}

// What order n keeps of the floor vertex's share: the clamped cosine / pi and the visibility
// (0 inside the cap cos(theta) > sqrt(1 - (a/d)^2)) are zonal about the normal, so their
// truncated product is sum over bands l < n of (2l + 1) / (4 pi) T_l V_l with T_l, V_l their
// projections on P_l (a midpoint rule in cos(theta)).
double truncated_share(std::uint32_t order, double a_over_d) {
  const int steps = 20000;
  const double cap = std::sqrt(1.0 - a_over_d * a_over_d), dx = 2.0 / steps;
  double share = 0.0;
  for (int l = 0; l < int(order); ++l) {
    double t = 0.0, v = 0.0;
    for (int i = 0; i < steps; ++i) {
      const double x = -1.0 + (i + 0.5) * dx, p = legendre(l, x);
      t += 2.0 * std::max(x, 0.0) * p * dx;  // 2 pi / pi
      v += 2.0 * M_PI * (x > cap ? 0.0 : 1.0) * p * dx;
    }
    share += (2 * l + 1) / (4.0 * M_PI) * t * v;
  }
  return share;
}

// The floor's share against the analytic 1 - (a/d)^2. Most of the error is the SH truncation of
// the transfer-visibility product (the clamped cosine's bands n and up are lost: -1.3 % at order
// 4, +0.2 % at order 6, computed by truncated_share), so the order-4 bound is about twice the
// truncation and order 6 must do better; against the truncated product itself what is left
// (the OOF's quadrature, its interpolation between shells, the sphere's facets) is a few tenths
// of a percent.
TEST(ShadowfieldBake, SphereShadowOnTheFloorIsTheCosineWeightedCap) {
  const double a_over_d = SphereOverFloor::a / SphereOverFloor::d;
  const double exact = 1.0 - a_over_d * a_over_d;
  const double order4 = SphereOverFloor(4).floor_share(4);
  const double order6 = SphereOverFloor(6).floor_share(6);
  const double error4 = std::abs(order4 - exact) / exact, error6 = std::abs(order6 - exact) / exact;
  std::printf(
      "floor below the sphere: share %.5f at order 4 (truncated %.5f), %.5f at order 6 "
      "(truncated %.5f), exact %.5f\n",
      order4, truncated_share(4, a_over_d), order6, truncated_share(6, a_over_d), exact);
  EXPECT_LT(error4, 0.03);
  EXPECT_LT(error6, error4);
  EXPECT_LT(error6, 0.005);
  for (const auto& [order, share] : {std::pair{4u, order4}, std::pair{6u, order6}}) {
    const double truncated = truncated_share(order, a_over_d);
    EXPECT_NEAR(share, truncated, 0.005 * truncated) << "order " << order;
  }
}

// With one bounce the lit floor brightens the sphere's underside: a positive gain bounded by the
// floor's brightest radiance (albedo x the sky) times the share of the bottom vertex's
// cosine-weighted hemisphere the patch covers, at most a disc of radius half sqrt(2) at distance
// d - a: R^2 / (R^2 + h^2).
TEST(ShadowfieldBake, OneBounceFromTheFloorBrightensTheSphereUnderside) {
  const SphereOverFloor scene(4);
  const auto direct = scene.shade(4, 0), bounced = scene.shade(4, 1);
  const std::size_t bottom =
      nearest_vertex(scene.sphere, glm::vec3(0.0f, SphereOverFloor::d - SphereOverFloor::a, 0.0f));
  const double r2 = 2.0 * SphereOverFloor::half * SphereOverFloor::half;
  const double h = SphereOverFloor::d - SphereOverFloor::a;
  const double share = r2 / (r2 + h * h);
  for (int c = 0; c < 3; ++c) {
    const double gain = bounced[0][3 * bottom + c] - direct[0][3 * bottom + c];
    const double bound = kSphereAlbedo[c] * kFloorAlbedo[c] * share;
    std::printf("sphere underside, channel %d: bounce gain %.4f, bound %.4f\n", c, gain, bound);
    EXPECT_GT(gain, 0.0);
    EXPECT_LT(gain, bound);
  }
  // The floor keeps its direct light in the sum.
  const std::size_t below = nearest_vertex(scene.floor, glm::vec3(0.0f));
  EXPECT_GE(bounced[1][3 * below], direct[1][3 * below]);
}

// A glossy plane alone under radiance 1, seen along its normal: L_o = albedo x the integral of
// f(w, +Z) cos(w), which is ks + kd for normalised Phong with the lobe inside the hemisphere, and
// the same integral of the separated BRDF the bake stored, which the runtime must reproduce.
TEST(ShadowfieldBake, GlossyPlaneSeenAlongItsNormalReflectsItsDirectionalAlbedo) {
  const PhongBrdf phong{10.0, 0.5, 0.3};
  const Mesh plane = make_plane_mesh("plane", 0, 1.0f, 1.0f, 2, 2);
  const Scene scene = one_mesh_scene(plane, glm::vec3(0.8f));
  ShadowfieldBakeSettings settings = small_bake_settings(4);
  settings.brdf.terms = 8;
  settings.fields.transfer_rays = 4096;
  ShadowfieldMaterialDescription description;
  description.model = ShadowfieldBrdfModel::Phong;
  description.phong = phong;
  const ShadowfieldBakeResult baked = bake_shadowfield_object(
      scene, make_shadowfield_material(description, settings.brdf), settings, Context{});
  const auto blob = shadowfield_blob_of(baked.object, 16, "");
  const std::size_t centre = nearest_vertex(plane, glm::vec3(0.0f));
  const auto rgb = shade_instances({blob}, {{0, glm::vec3(0.0f)}}, constant_sky(4, 1.0f),
                                   glm::vec3(0.0f, 2.0f, 0.0f), 0)[0];
  const double expected = 0.8 * (phong.specular + phong.diffuse);
  // The same integral of the separated BRDF the bake stored, over its own grid's cells.
  const SeparableBrdf& brdf = baked.object.material.brdf;
  double separated = 0.0;
  for (std::uint32_t cell = 0; cell < brdf.grid.count(); ++cell) {
    const glm::dvec3 w = brdf.grid.direction(cell);
    for (std::uint32_t k = 0; k < brdf.terms; ++k)
      separated += brdf.outgoing_at(k, glm::dvec3(0, 0, 1)) * brdf.h(k, cell) * w.z *
                   brdf.grid.solid_angle();
  }
  separated *= 0.8;
  std::printf("glossy plane along its normal: %.5f, separated BRDF %.5f, exact %.5f\n",
              rgb[3 * centre], separated, expected);
  // The transfer's quadrature of the separated BRDF's integral: a few tenths of a percent.
  EXPECT_NEAR(rgb[3 * centre], separated, 0.005 * separated);
  // The separation itself (K = 8 on the 32 x 32 grid) is off by about 5 % at the lobe's peak.
  EXPECT_NEAR(rgb[3 * centre], expected, 0.1 * expected);
}

}  // namespace
}  // namespace prt::bake::test
