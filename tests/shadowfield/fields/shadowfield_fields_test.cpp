// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s per-object fields (prt/baker/shadowfield/shadowfield_fields.hpp): the
// occlusion field of a sphere against the analytic SH of the cap it hides, a field where every
// ray escapes against the quadrature of the basis, the inside of a closed object, the diffuse
// transfer of an open plane against the clamped-cosine band factors, a glossy transfer against a
// brute-force quadrature of h_k cos y_i, a sphere over a plane against its blocked cosine share,
// a convex sphere's vertices at every normal, scale and placement, non-finite and extreme input,
// determinism across thread counts, the object's assembly, the bounding sphere and bad settings.
#include <gtest/gtest.h>

#include <prt/prt_sh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "prt/baker/embree_scene.hpp"
#include "prt/baker/sampling.hpp"
#include "prt/baker/shadowfield/shadowfield_fields.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::size_t coefficients(std::uint32_t order) {
  return static_cast<std::size_t>(order) * order;
}

std::vector<double> sh_at(std::uint32_t order, const glm::dvec3& direction) {
  std::vector<float> y(coefficients(order));
  const glm::vec3 d(direction);
  prt_sh_eval(order, &d.x, y.data());
  return std::vector<double>(y.begin(), y.end());
}

// Legendre P_l(x) by the three-term recurrence.
double legendre(int l, double x) {
  double p0 = 1.0, p1 = x;
  if (l == 0) return p0;
  for (int k = 2; k <= l; ++k) {
    const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  return p1;
}

// The SH of the indicator of the cap {w : w.u > c}: a zonal function about u, so its (l, m)
// coefficient is 2 pi (integral from c to 1 of P_l) Y_lm(u), with the integral
// (P_(l-1)(c) - P_(l+1)(c)) / (2l + 1) for l >= 1 and 1 - c for l = 0.
std::vector<double> cap_sh(std::uint32_t order, const glm::dvec3& u, double c) {
  const std::vector<double> y = sh_at(order, u);
  std::vector<double> out(y.size());
  for (int l = 0; l < static_cast<int>(order); ++l) {
    const double integral =
        l == 0 ? 1.0 - c : (legendre(l - 1, c) - legendre(l + 1, c)) / (2.0 * l + 1.0);
    for (int m = -l; m <= l; ++m) out[l * (l + 1) + m] = 2.0 * kPi * integral * y[l * (l + 1) + m];
  }
  return out;
}

struct Baked {
  ShadowfieldObject object;
  std::size_t without_normal = 0;
};

Baked bake(const Scene& scene, const ShadowfieldFieldSettings& settings,
           const ShadowfieldMaterial& material = {}, unsigned threads = 0) {
  Context ctx;
  ctx.threads = threads;
  const EmbreeScene rays(scene, ctx);
  Baked baked{make_shadowfield_object(scene, material, settings.order)};
  bake_occlusion_field(baked.object, rays, settings, ctx);
  baked.without_normal = bake_self_transfer(baked.object, rays, settings, ctx);
  return baked;
}

ShadowfieldFieldSettings small_settings() {
  ShadowfieldFieldSettings s;
  s.oof_shells = 3;
  s.oof_face_size = 2;
  s.field_directions = 4096;
  s.transfer_rays = 256;
  return s;
}

TEST(OcclusionField, SphereHidesTheAnalyticCap) {
  constexpr float kRadius = 0.7f;
  ShadowfieldFieldSettings settings = small_settings();
  settings.inner = 1.25f;  // every shell outside the sphere
  const Baked baked = bake(test::scene_of({test::make_icosphere(4, kRadius)}), settings);
  const ShadowfieldObject& object = baked.object;
  const std::size_t n2 = coefficients(settings.order);
  const auto points = static_cast<std::size_t>(prt_sf_point_count(&object.oof_shells));
  ASSERT_EQ(object.oof.size(), points * n2);
  double worst = 0.0;
  for (std::size_t p = 0; p < points; ++p) {
    glm::vec3 position;
    prt_sf_point_position(&object.oof_shells, p, &position.x);
    const glm::dvec3 to_centre = -glm::dvec3(position);
    const double d = glm::length(to_centre), s = kRadius / d;
    std::vector<double> expected = cap_sh(settings.order, to_centre / d, std::sqrt(1.0 - s * s));
    for (double& e : expected) e = -e;
    expected[0] += std::sqrt(4.0 * kPi);
    for (std::size_t i = 0; i < n2; ++i)
      worst = std::max(worst, std::abs(object.oof[p * n2 + i] - expected[i]));
  }
  // The quadrature of a discontinuous cap by M directions dominates; the polygon is close.
  std::printf("sphere cap: worst coefficient error %.3g\n", worst);
  EXPECT_LT(worst, 0.025);
}

TEST(OcclusionField, EveryRayEscapingGivesTheBasisQuadrature) {
  // One degenerate triangle: Embree drops it, so nothing can be hit.
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  mesh.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  mesh.indices = {0, 1, 2};
  ShadowfieldFieldSettings settings = small_settings();
  settings.field_directions = 1024;
  const Baked baked = bake(test::scene_of({mesh}), settings);
  const std::size_t n2 = coefficients(settings.order);
  double worst = 0.0;
  for (std::size_t p = 0; p * n2 < baked.object.oof.size(); ++p) {
    const float* c = baked.object.oof.data() + p * n2;
    EXPECT_NEAR(c[0], std::sqrt(4.0 * kPi), 1e-5);
    for (std::size_t i = 1; i < n2; ++i) worst = std::max(worst, std::abs(double(c[i])));
    EXPECT_EQ(std::memcmp(c, baked.object.oof.data(), n2 * sizeof(float)), 0);
  }
  // The quadrature of y_i over the sphere (zero exactly) by M stratified directions.
  std::printf("all escape: worst higher coefficient %.3g\n", worst);
  EXPECT_LT(worst, 0.015);
}

TEST(OcclusionField, InsideAClosedObjectEveryRayHits) {
  ShadowfieldFieldSettings settings = small_settings();
  settings.inner = 0.2f;
  settings.outer = 0.9f;
  const Baked baked = bake(test::scene_of({test::make_icosphere(3, 1.0f)}), settings);
  for (float c : baked.object.oof) ASSERT_EQ(c, 0.0f);
}

TEST(SelfTransfer, OpenPlaneDiffuseIsTheCosineBandFactors) {
  ShadowfieldFieldSettings settings = small_settings();
  settings.transfer_rays = 1024;
  const Baked baked = bake(test::scene_of({test::make_plane(1.0f, 4)}), settings);
  const std::size_t n2 = coefficients(settings.order);
  const std::vector<double> y = sh_at(settings.order, {0, 1, 0});
  double worst = 0.0;
  for (std::size_t v = 0; v < baked.object.positions.size(); ++v) {
    const float* t = baked.object.transfer.data() + v * n2;
    EXPECT_FLOAT_EQ(t[0], static_cast<float>(y[0]));  // band 0 is exact
    for (int l = 0; l < static_cast<int>(settings.order); ++l)
      for (int m = -l; m <= l; ++m) {
        const std::size_t i = l * (l + 1) + m;
        const double expected = prt_sh_cosine_band_factor(l) / kPi * y[i];
        worst = std::max(worst, std::abs(t[i] - expected));
      }
  }
  std::printf("plane diffuse: worst coefficient error %.3g\n", worst);
  EXPECT_LT(worst, 0.0015);
}

// integral over the hemisphere of h_k(w_local) cos(w) y_i(w), midpoint rule in (cos theta, phi)
// of the local frame.
std::vector<double> glossy_transfer_reference(const SeparableBrdf& brdf, std::uint32_t order,
                                              const glm::vec3& normal) {
  constexpr int kCos = 400, kPhi = 800;
  const Frame frame(normal);
  const std::size_t n2 = coefficients(order);
  std::vector<double> out(brdf.terms * n2, 0.0);
  for (int c = 0; c < kCos; ++c) {
    const double z = (c + 0.5) / kCos, s = std::sqrt(1.0 - z * z);
    for (int p = 0; p < kPhi; ++p) {
      const double phi = 2.0 * kPi * (p + 0.5) / kPhi;
      const glm::dvec3 local(s * std::cos(phi), s * std::sin(phi), z);
      const std::vector<double> y = sh_at(order, frame.to_world(glm::vec3(local)));
      for (std::uint32_t k = 0; k < brdf.terms; ++k) {
        const double h = brdf.incident_at(k, local) * z;
        for (std::size_t i = 0; i < n2; ++i) out[k * n2 + i] += h * y[i];
      }
    }
  }
  for (double& o : out) o *= (1.0 / kCos) * (2.0 * kPi / kPhi);
  return out;
}

TEST(SelfTransfer, OpenPlaneGlossyMatchesAQuadrature) {
  ShadowfieldMaterial material;
  material.glossy = true;
  material.brdf = separate_brdf(brdf_function(PhongBrdf{10.0, 1.0, 0.0}), {16, 4});
  ShadowfieldFieldSettings settings = small_settings();
  settings.transfer_rays = 4096;
  const Baked baked = bake(test::scene_of({test::make_plane(1.0f, 2)}), settings, material);
  const std::size_t stride = 4 * coefficients(settings.order);
  ASSERT_EQ(baked.object.transfer.size(), baked.object.positions.size() * stride);
  const std::vector<double> expected =
      glossy_transfer_reference(material.brdf, settings.order, {0, 1, 0});
  double worst = 0.0, largest = 0.0;
  for (std::size_t v = 0; v < baked.object.positions.size(); ++v)
    for (std::size_t i = 0; i < stride; ++i) {
      worst = std::max(worst, std::abs(baked.object.transfer[v * stride + i] - expected[i]));
      largest = std::max(largest, std::abs(expected[i]));
    }
  std::printf("plane glossy: worst error %.3g, largest value %.3g\n", worst, largest);
  EXPECT_LT(worst, 4e-4);
}

// A sphere of radius a centred at height h over a plane vertex hides the cap of half-angle
// asin(a / h) about the normal, so the diffuse transfer is the open plane's minus
// (1 / pi) integral over the cap of cos y_i: for a cap about the normal, 2 (integral from c to 1
// of t P_l(t) dt) Y_lm(n), the integral by a fine midpoint rule here.
TEST(SelfTransfer, SphereOverAPlaneHidesItsCosineShare) {
  constexpr float kRadius = 0.5f, kHeight = 1.5f;
  ShadowfieldFieldSettings settings = small_settings();
  settings.transfer_rays = 1024;
  const Mesh plane = test::make_plane(2.0f, 4);  // vertex 12 at the origin
  ASSERT_EQ(plane.positions[12], glm::vec3(0.0f));
  const Baked baked = bake(
      test::scene_of({plane, test::make_icosphere(4, kRadius, {0.0f, kHeight, 0.0f})}), settings);
  const std::size_t n2 = coefficients(settings.order);
  const std::vector<double> y = sh_at(settings.order, {0, 1, 0});
  const double c = std::sqrt(1.0 - double(kRadius * kRadius) / (kHeight * kHeight));
  double worst = 0.0;
  for (int l = 0; l < static_cast<int>(settings.order); ++l) {
    constexpr int kSteps = 100000;
    double integral = 0.0;
    for (int k = 0; k < kSteps; ++k) {
      const double t = c + (1.0 - c) * (k + 0.5) / kSteps;
      integral += t * legendre(l, t);
    }
    integral *= (1.0 - c) / kSteps;
    for (int m = -l; m <= l; ++m) {
      const std::size_t i = l * (l + 1) + m;
      const double expected = (prt_sh_cosine_band_factor(l) / kPi - 2.0 * integral) * y[i];
      worst = std::max(worst, std::abs(baked.object.transfer[12 * n2 + i] - expected));
    }
  }
  // Far below the blocked share itself, so a bake that ignored the sphere would fail.
  std::printf("sphere over plane: worst coefficient error %.3g\n", worst);
  EXPECT_LT(worst, 0.004);
}

// A vertex of a convex sphere sees its whole tangent hemisphere (the faces lie inside the
// sphere, below every vertex's tangent plane), so each normal of the sphere gets the open plane's
// transfer: the tangent frame and the directions for normals all round.
TEST(SelfTransfer, ConvexSphereVerticesSeeTheirWholeHemisphere) {
  ShadowfieldFieldSettings settings = small_settings();
  settings.transfer_rays = 1024;
  const Baked baked = bake(test::scene_of({test::make_icosphere(2)}), settings);
  const std::size_t n2 = coefficients(settings.order);
  double worst = 0.0;
  for (std::size_t v = 0; v < baked.object.positions.size(); ++v) {
    const std::vector<double> y = sh_at(settings.order, baked.object.normals[v]);
    for (int l = 0; l < static_cast<int>(settings.order); ++l)
      for (int m = -l; m <= l; ++m) {
        const std::size_t i = l * (l + 1) + m;
        const double expected = prt_sh_cosine_band_factor(l) / kPi * y[i];
        worst = std::max(worst, std::abs(baked.object.transfer[v * n2 + i] - expected));
      }
  }
  std::printf("convex sphere diffuse: worst coefficient error %.3g\n", worst);
  EXPECT_LT(worst, 0.0015);
}

TEST(SelfTransfer, ConvexSphereGlossyMatchesAQuadratureAtTiltedNormals) {
  ShadowfieldMaterial material;
  material.glossy = true;
  material.brdf = separate_brdf(brdf_function(PhongBrdf{10.0, 1.0, 0.0}), {16, 4});
  ShadowfieldFieldSettings settings = small_settings();
  settings.transfer_rays = 4096;
  const Baked baked = bake(test::scene_of({test::make_icosphere(1)}), settings, material);
  const std::size_t stride = 4 * coefficients(settings.order);
  double worst = 0.0;
  for (std::size_t v : {0u, 5u, 20u}) {  // three normals, none along an axis
    const glm::vec3 n = baked.object.normals[v];
    const std::vector<double> expected =
        glossy_transfer_reference(material.brdf, settings.order, n);
    for (std::size_t i = 0; i < stride; ++i)
      worst = std::max(worst, std::abs(baked.object.transfer[v * stride + i] - expected[i]));
  }
  std::printf("convex sphere glossy: worst error %.3g\n", worst);
  EXPECT_LT(worst, 3e-4);
}

// The field depends on the object's shape alone: a sphere a thousand times smaller or larger,
// far from the origin, casts the same field up to the few rays that graze its silhouette.
TEST(OcclusionField, ScaleAndPlacementLeaveTheFieldAlone) {
  ShadowfieldFieldSettings settings = small_settings();
  settings.inner = 1.25f;
  settings.field_directions = 1024;
  const Baked unit = bake(test::scene_of({test::make_icosphere(3)}), settings);
  for (const float scale : {1e-3f, 1e3f}) {
    const glm::vec3 centre(scale * 50.0f, -scale * 20.0f, scale * 7.0f);
    const Baked scaled = bake(test::scene_of({test::make_icosphere(3, scale, centre)}), settings);
    ASSERT_EQ(scaled.object.oof.size(), unit.object.oof.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < unit.object.oof.size(); ++i)
      worst = std::max(worst, std::abs(double(scaled.object.oof[i]) - unit.object.oof[i]));
    // Only rays grazing the silhouette can flip; allowed: two, each worth 4 pi / M times |y_i| < 1.
    std::printf("scale %g: worst coefficient change %.3g\n", scale, worst);
    EXPECT_LT(worst, 2.0 * 4.0 * kPi / settings.field_directions);
  }
}

TEST(Fields, NonFinitePositionIsSkippedAndCounted) {
  Scene scene = test::scene_of({test::make_plane(1.0f, 2), test::make_icosphere(1, 0.2f)});
  scene.meshes[0].positions[0] = glm::vec3(NAN, 0.0f, 0.0f);
  const Baked baked = bake(scene, small_settings());
  EXPECT_EQ(baked.without_normal, 1u);
  EXPECT_NEAR(baked.object.oof_shells.radius, std::sqrt(2.0f), 1e-6f);
  for (float c : baked.object.oof) ASSERT_TRUE(std::isfinite(c));
  for (float t : baked.object.transfer) ASSERT_TRUE(std::isfinite(t));
}

TEST(Fields, ExtremeSettingsStayFinite) {
  ShadowfieldFieldSettings settings = small_settings();
  settings.order = 6;
  settings.field_directions = 1;
  settings.transfer_rays = 1;
  settings.oof_shells = 1;
  settings.oof_face_size = 1;
  const Baked baked = bake(test::scene_of({test::make_icosphere(1)}), settings);
  EXPECT_EQ(baked.object.oof.size(), 6u * 36u);
  EXPECT_EQ(baked.object.transfer.size(), baked.object.positions.size() * 36u);
  for (float c : baked.object.oof) ASSERT_TRUE(std::isfinite(c));
  for (float t : baked.object.transfer) ASSERT_TRUE(std::isfinite(t));
}

TEST(Fields, AnyThreadCountGivesTheSameBytes) {
  ShadowfieldMaterial material;
  material.glossy = true;
  material.brdf = separate_brdf(brdf_function(PhongBrdf{10.0, 1.0, 0.0}), {8, 2});
  ShadowfieldFieldSettings settings = small_settings();
  settings.oof_face_size = 4;  // several tasks of points
  settings.field_directions = 256;
  const Scene scene = test::scene_of(
      {test::make_plane(2.0f, 8), test::make_icosphere(2, 0.5f, {0.0f, 0.7f, 0.0f})});
  const Baked one = bake(scene, settings, material, 1);
  const Baked two = bake(scene, settings, material, 2);
  ASSERT_EQ(one.object.oof.size(), two.object.oof.size());
  ASSERT_EQ(one.object.transfer.size(), two.object.transfer.size());
  EXPECT_EQ(std::memcmp(one.object.oof.data(), two.object.oof.data(),
                        one.object.oof.size() * sizeof(float)),
            0);
  EXPECT_EQ(std::memcmp(one.object.transfer.data(), two.object.transfer.data(),
                        one.object.transfer.size() * sizeof(float)),
            0);
}

TEST(Fields, ShellsFollowTheBoundingSphereAndSettings) {
  ShadowfieldFieldSettings settings = small_settings();
  const Baked baked = bake(test::scene_of({test::make_icosphere(2, 0.7f, {1, 2, 3})}), settings);
  const prt_sf_shells& grid = baked.object.oof_shells;
  EXPECT_NEAR(grid.centre[0], 1.0f, 1e-6f);
  EXPECT_NEAR(grid.centre[1], 2.0f, 1e-6f);
  EXPECT_NEAR(grid.centre[2], 3.0f, 1e-6f);
  EXPECT_NEAR(grid.radius, 0.7f, 1e-6f);
  EXPECT_EQ(grid.inner, settings.inner);
  EXPECT_EQ(grid.outer, settings.outer);
  EXPECT_EQ(grid.shells, settings.oof_shells);
  EXPECT_EQ(grid.face_size, settings.oof_face_size);

  settings.oof_shells = 1;
  const Baked one = bake(test::scene_of({test::make_icosphere(1)}), settings);
  EXPECT_EQ(one.object.oof_shells.outer, settings.inner);  // the format's rule for one shell
  EXPECT_EQ(one.object.oof.size(), 6u * 2 * 2 * coefficients(settings.order));
}

TEST(Fields, ObjectConcatenatesTheMeshes) {
  Scene scene = test::scene_of({test::make_plane(1.0f, 1), test::make_icosphere(0)});
  scene.materials.push_back({});
  scene.materials[0].base_color = glm::vec4(0.25f, 0.5f, 2.0f, 1.0f);
  scene.meshes[1].material = 0;
  scene.meshes[1].normals[3] = glm::vec3(0.0f, 0.0f, 2.0f);
  scene.meshes[1].normals[4] = glm::vec3(NAN, 0.0f, 1.0f);
  const ShadowfieldObject object = make_shadowfield_object(scene, {}, 3);
  EXPECT_EQ(object.order, 3u);
  ASSERT_EQ(object.positions.size(), 4u + 12u);
  ASSERT_EQ(object.indices.size(), 6u + 60u);
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(object.indices[i], scene.meshes[0].indices[i]);
  for (std::size_t i = 0; i < 60; ++i)
    EXPECT_EQ(object.indices[6 + i], 4u + scene.meshes[1].indices[i]);
  EXPECT_EQ(object.positions[4 + 5], scene.meshes[1].positions[5]);
  EXPECT_EQ(object.albedo[0], glm::vec3(1.0f));
  EXPECT_EQ(object.albedo[4], glm::vec3(0.25f, 0.5f, 1.0f));  // clamped to [0, 1]
  EXPECT_EQ(object.normals[4 + 3], glm::vec3(0.0f, 0.0f, 1.0f));
  EXPECT_EQ(object.normals[4 + 4], glm::vec3(0.0f));
  EXPECT_TRUE(object.oof.empty() && object.transfer.empty());
}

TEST(Fields, BadNormalsGetZeroTransferAndOneWarning) {
  Scene scene = test::scene_of({test::make_plane(1.0f, 2)});
  scene.meshes[0].normals[0] = glm::vec3(0.0f);
  scene.meshes[0].normals[1] = glm::vec3(INFINITY, 0.0f, 0.0f);
  const ShadowfieldFieldSettings settings = small_settings();
  Context ctx;
  int warnings = 0;
  ctx.log = [&](LogLevel level, const std::string&) { warnings += level == LogLevel::Warning; };
  const EmbreeScene rays(scene, ctx);
  ShadowfieldObject object = make_shadowfield_object(scene, {}, settings.order);
  EXPECT_EQ(bake_self_transfer(object, rays, settings, ctx), 2u);
  EXPECT_EQ(warnings, 1);
  const std::size_t n2 = coefficients(settings.order);
  for (std::size_t i = 0; i < 2 * n2; ++i) EXPECT_EQ(object.transfer[i], 0.0f);
  EXPECT_GT(object.transfer[2 * n2], 0.0f);
  for (float t : object.transfer) EXPECT_TRUE(std::isfinite(t));
}

TEST(BoundingSphere, IsTheBoxCentreAndFarthestPoint) {
  const std::vector<glm::vec3> points = {{-1, 0, 0}, {3, 0, 0}, {0, 2, 0}, {0, -2, 1}};
  const BoundingSphere sphere = bounding_sphere(points);
  EXPECT_EQ(sphere.centre, glm::vec3(1.0f, 0.0f, 0.5f));
  EXPECT_FLOAT_EQ(sphere.radius, std::sqrt(1.0f + 4.0f + 0.25f));  // (0, +-2, .)
  const std::vector<glm::vec3> reversed(points.rbegin(), points.rend());
  const BoundingSphere again = bounding_sphere(reversed);
  EXPECT_EQ(again.centre, sphere.centre);
  EXPECT_EQ(again.radius, sphere.radius);
}

TEST(BoundingSphere, SinglePointAndNonFinitePoints) {
  EXPECT_EQ(bounding_sphere({{0, 0, 0}}).radius, 1e-5f);
  const BoundingSphere far = bounding_sphere({{1000, 0, 0}, {1000, 0, 0}});
  EXPECT_EQ(far.centre, glm::vec3(1000, 0, 0));
  EXPECT_EQ(far.radius, 1e-2f);
  const BoundingSphere skipped = bounding_sphere({{NAN, 0, 0}, {0, 0, 0}, {2, 0, INFINITY}});
  EXPECT_EQ(skipped.centre, glm::vec3(0.0f));
  EXPECT_GT(skipped.radius, 0.0f);
  EXPECT_THROW(bounding_sphere({}), Error);
  EXPECT_THROW(bounding_sphere({{NAN, 0, 0}}), Error);
}

TEST(Settings, DefaultsAreValid) {
  const ShadowfieldFieldSettings defaults;
  EXPECT_NO_THROW(check_shadowfield_field_settings(defaults));
  EXPECT_EQ(defaults.order, 4u);
  EXPECT_EQ(defaults.oof_shells, 16u);
  EXPECT_EQ(defaults.inner, 0.2f);
  EXPECT_EQ(defaults.outer, 8.0f);
  EXPECT_EQ(defaults.oof_face_size, 16u);
}

TEST(Settings, EachBadValueThrows) {
  using Change = void (*)(ShadowfieldFieldSettings&);
  const Change bad[] = {
      [](ShadowfieldFieldSettings& s) { s.order = 1; },
      [](ShadowfieldFieldSettings& s) { s.order = 7; },
      [](ShadowfieldFieldSettings& s) { s.oof_shells = 0; },
      [](ShadowfieldFieldSettings& s) { s.oof_shells = 65; },
      [](ShadowfieldFieldSettings& s) { s.oof_face_size = 0; },
      [](ShadowfieldFieldSettings& s) { s.oof_face_size = 129; },
      [](ShadowfieldFieldSettings& s) { s.field_directions = 0; },
      [](ShadowfieldFieldSettings& s) { s.field_directions = 65537; },
      [](ShadowfieldFieldSettings& s) { s.transfer_rays = 0; },
      [](ShadowfieldFieldSettings& s) { s.transfer_rays = 65537; },
      [](ShadowfieldFieldSettings& s) { s.inner = 0.0f; },
      [](ShadowfieldFieldSettings& s) { s.inner = -1.0f; },
      [](ShadowfieldFieldSettings& s) { s.inner = NAN; },
      [](ShadowfieldFieldSettings& s) { s.inner = INFINITY; },
      [](ShadowfieldFieldSettings& s) { s.outer = 0.1f; },
      [](ShadowfieldFieldSettings& s) { s.outer = s.inner; },
      [](ShadowfieldFieldSettings& s) { s.outer = NAN; },
      [](ShadowfieldFieldSettings& s) { s.outer = INFINITY; },
  };
  for (std::size_t i = 0; i < std::size(bad); ++i) {
    ShadowfieldFieldSettings settings;
    bad[i](settings);
    EXPECT_THROW(check_shadowfield_field_settings(settings), Error) << "change " << i;
  }
  ShadowfieldFieldSettings one_shell;
  one_shell.oof_shells = 1;
  one_shell.outer = one_shell.inner;
  EXPECT_NO_THROW(check_shadowfield_field_settings(one_shell));
}

TEST(Settings, BakesRefuseAMismatchedObjectOrEmptyInputs) {
  const Scene scene = test::scene_of({test::make_plane(1.0f, 1)});
  Context ctx;
  const EmbreeScene rays(scene, ctx);
  ShadowfieldObject object = make_shadowfield_object(scene, {}, 3);
  ShadowfieldFieldSettings settings = small_settings();  // order 4
  EXPECT_THROW(bake_occlusion_field(object, rays, settings, ctx), Error);
  EXPECT_THROW(bake_self_transfer(object, rays, settings, ctx), Error);
  EXPECT_THROW(make_shadowfield_object(scene, {}, 1), Error);
  EXPECT_THROW(make_shadowfield_object(Scene{}, {}, 4), Error);
  ShadowfieldMaterial glossy;
  glossy.glossy = true;  // without terms
  EXPECT_THROW(make_shadowfield_object(scene, glossy, 4), Error);
}

TEST(Settings, CancelledProgressStopsTheBake) {
  const Scene scene = test::scene_of({test::make_icosphere(1)});
  Context ctx;
  ctx.progress = [](double, const std::string&) { return false; };
  const EmbreeScene rays(scene, ctx);
  ShadowfieldObject object = make_shadowfield_object(scene, {}, 4);
  EXPECT_THROW(bake_occlusion_field(object, rays, small_settings(), ctx), Error);
}

}  // namespace
}  // namespace prt::bake
