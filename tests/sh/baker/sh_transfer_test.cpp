// SPDX-License-Identifier: MIT
// SH transfer (technique sh) against independent values: a white furnace, the analytic
// clamped-cosine projection, the analytic view factor of an open box's opening, the reference
// path tracer under an environment that SH represents exactly, and determinism.
#include <gtest/gtest.h>

#include <prt/prt_sh.h>

#include <cmath>
#include <cstring>
#include <tuple>

#include "prt/baker/reference.hpp"
#include "prt/baker/sh/sh_transfer.hpp"
#include "sh/sh_test_scenes.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

constexpr double kPi = 3.14159265358979323846;

ShTransferSettings transfer_settings(ShTransferKind kind, std::uint32_t order, std::uint32_t rays,
                                     glm::vec3 albedo, int bounces = 1) {
  ShTransferSettings s;
  s.kind = kind;
  s.order = order;
  s.rays = rays;
  s.bounces = bounces;
  s.override_albedo = true;
  s.albedo = albedo;
  return s;
}

Context threads(unsigned n) {
  Context ctx;
  ctx.threads = n;
  return ctx;
}

// Only L_00 = sqrt(4 pi) for a constant environment of radiance 1.
std::vector<glm::vec3> constant_light(std::uint32_t order) {
  std::vector<glm::vec3> light(order * order, glm::vec3(0.0f));
  light[0] = glm::vec3(float(std::sqrt(4.0 * kPi)));
  return light;
}

// Ramamoorthi & Hanrahan 2001: SH coefficients of max(0, cos) scaled to the convolution factor,
// A_0 = pi, A_1 = 2 pi / 3, odd l > 1: 0, even l: 2 pi (-1)^(l/2-1) / ((l+2)(l-1)) l! / (2^l
// ((l/2)!)^2).
double clamped_cosine_factor(int l) {
  if (l == 0) return kPi;
  if (l == 1) return 2.0 * kPi / 3.0;
  if (l % 2 == 1) return 0.0;
  const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
  return 2.0 * kPi * sign / ((l + 2.0) * (l - 1.0)) * std::tgamma(l + 1.0) /
         (std::pow(2.0, l) * std::pow(std::tgamma(l / 2 + 1.0), 2.0));
}

// Relative RMS difference of two per-vertex radiance arrays (over vertices and channels, divided
// by the RMS of b), skipping nothing.
double relative_rms_difference(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  double diff = 0.0, norm = 0.0;
  for (std::size_t v = 0; v < a.size(); ++v) {
    const glm::dvec3 d = glm::dvec3(a[v]) - glm::dvec3(b[v]);
    diff += glm::dot(d, d);
    norm += glm::dot(glm::dvec3(b[v]), glm::dvec3(b[v]));
  }
  return std::sqrt(diff / norm);
}

// White furnace: a closed convex sphere under constant radiance 1 reflects exactly its albedo at
// every vertex, for every kind (it never sees itself). Cosine-weighted directions make t_00 exact
// for a vertex that sees its whole hemisphere, so the tolerance is float rounding only.
class ShWhiteFurnace
    : public ::testing::TestWithParam<std::tuple<ShTransferKind, float, std::uint32_t>> {};

TEST_P(ShWhiteFurnace, EveryVertexReflectsItsAlbedo) {
  const auto [kind, rho, order] = GetParam();
  const Scene scene = test::scene_of({test::make_icosphere(3, 2.0f)});
  const ShTransfer transfer = compute_sh_transfer(
      scene, nullptr, transfer_settings(kind, order, 256, glm::vec3(rho), 2), Context{});
  ASSERT_EQ(transfer.vertex_count, scene.vertex_count());
  ASSERT_EQ(transfer.coefficients.size(), scene.vertex_count() * 3 * order * order);
  EXPECT_EQ(transfer.vertices_without_normal, 0u);
  if (kind != ShTransferKind::Unshadowed) {
    EXPECT_GT(transfer.rays_traced, 0u);
  }
  const std::vector<glm::vec3> radiance = shade_sh_transfer(transfer, constant_light(order));
  for (std::size_t v = 0; v < radiance.size(); ++v) {
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(radiance[v][c], rho, 1e-5) << "vertex " << v;
  }
}

INSTANTIATE_TEST_SUITE_P(KindsAlbedosOrders, ShWhiteFurnace,
                         ::testing::Combine(::testing::Values(ShTransferKind::Unshadowed,
                                                              ShTransferKind::Shadowed,
                                                              ShTransferKind::Interreflected),
                                            ::testing::Values(0.5f, 0.9f),
                                            ::testing::Values(1u, 4u)));

TEST(ShTransfer, UnshadowedIsTheClampedCosineProjection) {
  // t_lm = (rho/pi) A_l Y_lm(n) (the clamped cosine is zonal about n; Funk-Hecke). Unbounded
  // by occlusion, so any mesh will do; the icosphere gives 42 spread normals.
  const std::uint32_t order = 7;
  const glm::vec3 rho(0.9f, 0.6f, 0.3f);
  const Scene scene = test::scene_of({test::make_icosphere(1)});
  const ShTransfer transfer = compute_sh_transfer(
      scene, nullptr, transfer_settings(ShTransferKind::Unshadowed, order, 4096, rho), Context{});
  EXPECT_EQ(transfer.rays_traced, 0u);
  std::vector<float> y(order * order);
  double worst = 0.0;
  for (std::size_t v = 0; v < scene.vertex_count(); ++v) {
    ASSERT_EQ(prt_sh_eval(order, &scene.meshes[0].normals[v].x, y.data()), PRT_OK);
    for (int c = 0; c < 3; ++c) {
      const float* t = transfer.vertex_channel(v, c);
      for (int l = 0; l < int(order); ++l) {
        for (int m = -l; m <= l; ++m) {
          const int k = l * (l + 1) + m;
          const double expected = rho[c] / kPi * clamped_cosine_factor(l) * y[k];
          worst = std::max(worst, std::abs(t[k] - expected));
          // 4096 scrambled Sobol points of an integrand bounded by |y| <= ~1 with a kink at the
          // horizon: far below the plain Monte Carlo sigma (~1/64); a few times the largest
          // error over seeds (in the highest band), so a band's factor A_l 10 % off fails.
          ASSERT_NEAR(t[k], expected, 1e-3) << "vertex " << v << " l " << l << " m " << m;
        }
      }
    }
  }
  RecordProperty("worst_abs_error", std::to_string(worst));
}

// Form factor from a point to a parallel a x b rectangle at distance c with one corner above the
// point (Howell, A Catalog of Radiation Heat Transfer Configuration Factors, B-3).
double corner_rectangle_factor(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double sx = std::sqrt(1.0 + x * x), sy = std::sqrt(1.0 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * kPi);
}

TEST(ShTransfer, ShadowedOpenBoxFloorCentreSeesTheOpening) {
  // l = 0: t_00 = (rho/pi) y_00 integral of V cos = rho y_00 F, F the view factor of the 2x2
  // opening at height h from the floor's centre (four corner rectangles). The box is symmetric
  // under x -> -x and z -> -z, so the l = 1 terms along world x and z vanish.
  const float rho = 0.7f;
  for (const float height : {0.5f, 1.0f, 2.0f}) {
    const Scene scene = test::scene_of({test::make_open_box(height)});
    const ShTransfer transfer = compute_sh_transfer(
        scene, nullptr, transfer_settings(ShTransferKind::Shadowed, 3, 4096, glm::vec3(rho)),
        Context{});
    const double y00 = 0.5 / std::sqrt(kPi);
    const double expected = rho * y00 * 4.0 * corner_rectangle_factor(1.0, 1.0, height);
    const float* t = transfer.vertex_channel(0, 1);
    EXPECT_NEAR(t[0], expected, 0.01 * expected) << "height " << height;
    // Directions x and z: evaluate the basis there to find which l = 1 coefficients they carry.
    std::vector<float> yx(9), yz(9);
    const float ex[3] = {1, 0, 0}, ez[3] = {0, 0, 1};
    prt_sh_eval(3, ex, yx.data());
    prt_sh_eval(3, ez, yz.data());
    double along_x = 0.0, along_z = 0.0;
    for (int k = 1; k < 4; ++k) {
      along_x += t[k] * yx[k];
      along_z += t[k] * yz[k];
    }
    EXPECT_NEAR(along_x, 0.0, 0.01 * expected) << "height " << height;
    EXPECT_NEAR(along_z, 0.0, 0.01 * expected) << "height " << height;
  }
}

// L(w) = a + b w_y + c w_x per channel: only bands 0 and 1, so SH of order >= 2 represents it
// exactly and SH shading must equal the path-traced reference up to both estimates' noise.
glm::vec3 band_limited_sky(glm::vec3 w) {
  return glm::vec3(1.0f, 0.8f, 0.6f) + glm::vec3(0.6f, 0.5f, 0.2f) * w.y +
         glm::vec3(0.3f, -0.2f, 0.25f) * w.x;
}

struct Comparison {
  double difference = 0.0;  // relative RMS difference SH vs reference
  double noise = 0.0;       // combined relative RMSE of the two estimates
};

Comparison compare_with_reference(const Scene& scene, ShTransferKind kind, int bounces,
                                  glm::vec3 rho) {
  const std::uint32_t order = 3;
  const io::EnvMap env = test::make_function_map(512, band_limited_sky);
  const std::vector<glm::vec3> light = test::project_function(order, band_limited_sky);

  ReferenceSettings ref_settings;
  ref_settings.bounces = bounces;
  ref_settings.spp = 1024;
  ref_settings.override_albedo = true;
  ref_settings.albedo = rho;
  const ReferenceRenderer renderer(scene, env, ref_settings, Context{});
  const VertexRadiance reference = renderer.render_vertices(Context{});

  // Two independent seeds give the SH estimate's own noise: Var(a - b) = 2 Var(a).
  ShTransferSettings settings = transfer_settings(kind, order, 1024, rho, bounces);
  const std::vector<glm::vec3> sh = shade_sh_transfer(
      compute_sh_transfer(scene, &renderer.embree_scene(), settings, Context{}), light);
  settings.seed = 1;
  const std::vector<glm::vec3> sh_other = shade_sh_transfer(
      compute_sh_transfer(scene, &renderer.embree_scene(), settings, Context{}), light);
  const double sh_noise = relative_rms_difference(sh, sh_other) / std::sqrt(2.0);

  Comparison result;
  result.difference = relative_rms_difference(sh, reference.radiance);
  result.noise = std::sqrt(sh_noise * sh_noise + reference.relative_rmse * reference.relative_rmse);
  return result;
}

TEST(ShTransfer, ShadowedMatchesTheReferenceUnderABandLimitedSky) {
  // An open box (concave, so vertices are partly shadowed) with a sphere standing in it.
  std::vector<Mesh> meshes = test::make_fine_open_box(1.0f, 16, 8);
  meshes.push_back(test::make_icosphere(2, 0.4f, glm::vec3(0.2f, 0.4f, -0.1f)));
  const Scene scene = test::scene_of(std::move(meshes));
  const Comparison c =
      compare_with_reference(scene, ShTransferKind::Shadowed, 0, glm::vec3(0.8f, 0.6f, 0.4f));
  RecordProperty("relative_difference", std::to_string(c.difference));
  RecordProperty("noise", std::to_string(c.noise));
  // Both are unbiased estimates of the same integral: they differ by noise alone. Over the
  // scene's thousands of vertices the RMS difference is within a few percent of the combined
  // noise, so 1.25 noise leaves room for that spread and fails a bias of 0.75 noise.
  EXPECT_LT(c.difference, 1.25 * c.noise) << "noise " << c.noise;
}

TEST(ShTransfer, OneBounceMatchesTheReferenceInABowl) {
  // Interreflection gathers the previous pass's transfer interpolated linearly across the hit
  // triangle, where the reference evaluates the hit point exactly. The bowl is smooth and has no
  // seams, so that interpolation error is small: the RMS difference is the two estimates' noise
  // (within 1.25 of it, as for the shadowed transfer) and 0.6 % of interpolation and facets
  // (what the cavity-law test finds of them, with room), added in quadrature.
  const Scene scene = test::scene_of({test::make_bowl(16, 48)});
  const Comparison c =
      compare_with_reference(scene, ShTransferKind::Interreflected, 1, glm::vec3(0.8f));
  RecordProperty("relative_difference", std::to_string(c.difference));
  RecordProperty("noise", std::to_string(c.noise));
  EXPECT_LT(c.difference, std::hypot(1.25 * c.noise, 0.006)) << "noise " << c.noise;
}

TEST(ShTransfer, BowlUnderAConstantSkyFollowsTheSphereCavityLaw) {
  // Inside a sphere every surface element sees every other with view factor dA / (4 pi R^2), so
  // a hemispherical bowl's opening and its own surface each take half of every point's cosine-
  // weighted hemisphere, and under a constant sky of radiance 1 with uniform albedo rho every
  // point has L_0 = rho/2 directly and each bounce multiplies by rho/2:
  // L = rho/2 * sum_{i<=b} (rho/2)^i. The mesh's flat facets (48 x 16 cells) stand in for the
  // sphere: stated tolerance 1.5 %.
  const Scene scene = test::scene_of({test::make_bowl(16, 48)});
  const float rho = 0.8f;
  for (int bounces = 0; bounces <= 2; ++bounces) {
    const ShTransfer t = compute_sh_transfer(
        scene, nullptr,
        transfer_settings(ShTransferKind::Interreflected, 3, 1024, glm::vec3(rho), bounces),
        Context{});
    double expected = 0.0;
    for (int i = 0; i <= bounces; ++i) expected += rho / 2.0 * std::pow(rho / 2.0, i);
    const std::vector<glm::vec3> radiance = shade_sh_transfer(t, constant_light(3));
    double mean = 0.0;
    for (const glm::vec3& l : radiance) mean += l.g / radiance.size();
    EXPECT_NEAR(mean, expected, 0.015 * expected) << "bounces " << bounces;
    for (std::size_t v = 0; v < radiance.size(); ++v) {
      ASSERT_NEAR(radiance[v].g, expected, 0.03 * expected) << "bounces " << bounces << " v " << v;
    }
  }
}

TEST(ShTransfer, InterreflectedWithoutBouncesIsShadowed) {
  const Scene scene = test::scene_of(test::make_fine_open_box(1.0f, 8, 4));
  const ShTransfer shadowed = compute_sh_transfer(
      scene, nullptr, transfer_settings(ShTransferKind::Shadowed, 4, 64, glm::vec3(0.5f)),
      Context{});
  const ShTransfer zero_bounces = compute_sh_transfer(
      scene, nullptr, transfer_settings(ShTransferKind::Interreflected, 4, 64, glm::vec3(0.5f), 0),
      Context{});
  EXPECT_EQ(shadowed.coefficients, zero_bounces.coefficients);
}

TEST(ShTransfer, BouncesOnlyAddLightInAConcaveScene) {
  // Every bounce adds light gathered from a non-negative sky: radiance under a constant sky
  // grows with the bounce count, and stays below the albedo (energy conservation).
  const Scene scene = test::scene_of(test::make_fine_open_box(1.0f, 8, 4));
  const float rho = 0.8f;
  std::vector<glm::vec3> previous;
  for (int bounces = 0; bounces <= 2; ++bounces) {
    const ShTransfer t = compute_sh_transfer(
        scene, nullptr,
        transfer_settings(ShTransferKind::Interreflected, 3, 128, glm::vec3(rho), bounces),
        Context{});
    const std::vector<glm::vec3> radiance = shade_sh_transfer(t, constant_light(3));
    for (std::size_t v = 0; v < radiance.size(); ++v) {
      ASSERT_LE(radiance[v].r, rho * 1.0001f) << "vertex " << v;
      if (!previous.empty()) {
        ASSERT_GE(radiance[v].r, previous[v].r) << "vertex " << v;
      }
    }
    previous = radiance;
  }
}

TEST(ShTransfer, DeterministicForOneAndTwoThreads) {
  std::vector<Mesh> meshes = test::make_fine_open_box(1.0f, 12, 6);
  meshes.push_back(test::make_icosphere(2, 0.4f, glm::vec3(0.0f, 0.4f, 0.0f)));
  const Scene scene = test::scene_of(std::move(meshes));
  const ShTransferSettings settings =
      transfer_settings(ShTransferKind::Interreflected, 4, 64, glm::vec3(0.7f), 2);
  const ShTransfer one = compute_sh_transfer(scene, nullptr, settings, threads(1));
  const ShTransfer two = compute_sh_transfer(scene, nullptr, settings, threads(2));
  ASSERT_EQ(one.coefficients.size(), two.coefficients.size());
  EXPECT_EQ(std::memcmp(one.coefficients.data(), two.coefficients.data(),
                        one.coefficients.size() * sizeof(float)),
            0);
  EXPECT_EQ(one.rays_traced, two.rays_traced);
}

TEST(ShTransfer, VerticesWithoutNormalGetZeroAndAreCounted) {
  Mesh mesh = test::make_plane(1.0f, 2);
  mesh.normals[0] = glm::vec3(0.0f);
  mesh.normals[4] = glm::vec3(NAN, 1.0f, 0.0f);
  const Scene scene = test::scene_of({mesh});
  std::vector<std::string> warnings;
  Context ctx;
  ctx.log = [&](LogLevel level, const std::string& text) {
    if (level == LogLevel::Warning) warnings.push_back(text);
  };
  const ShTransfer t = compute_sh_transfer(
      scene, nullptr, transfer_settings(ShTransferKind::Interreflected, 3, 32, glm::vec3(0.5f)),
      ctx);
  EXPECT_EQ(t.vertices_without_normal, 2u);
  ASSERT_EQ(warnings.size(), 1u);
  for (std::size_t v : {std::size_t(0), std::size_t(4)}) {
    for (int c = 0; c < 3; ++c) {
      for (std::size_t k = 0; k < 9; ++k) EXPECT_EQ(t.vertex_channel(v, c)[k], 0.0f);
    }
  }
  EXPECT_GT(t.vertex_channel(1, 0)[0], 0.0f);
  for (float value : t.coefficients) ASSERT_TRUE(std::isfinite(value));
}

TEST(ShTransfer, RejectsInvalidSettingsAndCancels) {
  const Scene scene = test::scene_of({test::make_plane(1.0f, 2)});
  ShTransferSettings s = transfer_settings(ShTransferKind::Shadowed, 0, 16, glm::vec3(0.5f));
  EXPECT_THROW(compute_sh_transfer(scene, nullptr, s, Context{}), Error);
  s.order = PRT_SH_MAX_ORDER + 1;
  EXPECT_THROW(compute_sh_transfer(scene, nullptr, s, Context{}), Error);
  s.order = PRT_SH_MAX_ORDER;  // the maximum order itself is fine
  EXPECT_NO_THROW(compute_sh_transfer(scene, nullptr, s, Context{}));
  s.rays = 0;
  EXPECT_THROW(compute_sh_transfer(scene, nullptr, s, Context{}), Error);
  s.rays = 16;
  s.albedo = glm::vec3(1.5f);
  EXPECT_THROW(compute_sh_transfer(scene, nullptr, s, Context{}), Error);
  s.albedo = glm::vec3(0.5f);
  EXPECT_THROW(parse_sh_transfer_kind("glossy"), Error);
  EXPECT_EQ(parse_sh_transfer_kind("interreflected"), ShTransferKind::Interreflected);

  Context cancelling;
  std::string stage;
  cancelling.progress = [&](double, const std::string& name) {
    stage = name;
    return false;
  };
  EXPECT_THROW(compute_sh_transfer(scene, nullptr, s, cancelling), Error);
  EXPECT_EQ(stage.rfind("sh transfer", 0), 0u);
}

}  // namespace
}  // namespace prt::bake
