// SPDX-License-Identifier: MIT
// The reference renderer against analytic values: white furnace, cosine-weighted visibility of
// an open box, irradiance from a few bright texels; plus determinism and an honest noise figure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/reference.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

constexpr double kPi = 3.14159265358979323846;

ReferenceSettings settings_with(int bounces, std::uint32_t spp, glm::vec3 albedo) {
  ReferenceSettings s;
  s.bounces = bounces;
  s.spp = spp;
  s.override_albedo = true;
  s.albedo = albedo;
  return s;
}

Context threads(unsigned n) {
  Context ctx;
  ctx.threads = n;
  return ctx;
}

// White furnace: a closed convex sphere in a constant environment of radiance 1 reflects
// exactly its albedo at every point (it never sees itself), with or without bounces.
class WhiteFurnace : public ::testing::TestWithParam<std::tuple<float, int>> {};

TEST_P(WhiteFurnace, EveryVertexReflectsItsAlbedo) {
  const auto [rho, bounces] = GetParam();
  const Scene scene = test::scene_of({test::make_icosphere(3, 2.0f)});
  const io::EnvMap env = io::constant_envmap(glm::vec3(1.0f));
  const ReferenceRenderer renderer(scene, env, settings_with(bounces, 1024, glm::vec3(rho)),
                                   Context{});
  const VertexRadiance result = renderer.render_vertices(Context{});
  ASSERT_EQ(result.radiance.size(), scene.vertex_count());
  for (std::size_t v = 0; v < result.radiance.size(); ++v) {
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(result.radiance[v][c], rho, 0.01 * rho) << v;
  }
  EXPECT_LT(result.relative_rmse, 0.01);
  EXPECT_GT(result.stats.rays, 0u);
}

INSTANTIATE_TEST_SUITE_P(AlbedoAndBounces, WhiteFurnace,
                         ::testing::Combine(::testing::Values(0.5f, 0.8f),
                                            ::testing::Values(0, 3)));

// Form factor from a point to a parallel a x b rectangle at distance c with one corner above the
// point (Howell, A Catalog of Radiation Heat Transfer Configuration Factors, B-3).
double corner_rectangle_factor(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double sx = std::sqrt(1.0 + x * x), sy = std::sqrt(1.0 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * kPi);
}

TEST(ReferenceRenderer, OpenBoxFloorCentreSeesTheCosineWeightedOpening) {
  // Direct light only, sky of radiance 1: L = rho * (cosine-weighted fraction of the sky seen),
  // and from the floor's centre the sky is the 2x2 opening at height h: four corner rectangles.
  for (const float height : {0.5f, 1.0f, 2.0f}) {
    const Scene scene = test::scene_of({test::make_open_box(height)});
    const io::EnvMap env = io::constant_envmap(glm::vec3(1.0f));
    const float rho = 0.6f;
    const ReferenceRenderer renderer(scene, env, settings_with(0, 4096, glm::vec3(rho)), Context{});
    const VertexRadiance result = renderer.render_vertices(Context{});
    const double expected = rho * 4.0 * corner_rectangle_factor(1.0, 1.0, height);
    EXPECT_NEAR(result.radiance[0].g, expected, 0.01 * expected) << "height " << height;
  }
}

TEST(ReferenceRenderer, ImportanceSamplingOfAFewBrightTexelsGivesTheirIrradiance) {
  // A plane facing up under a map that is black but for 2x2 bright texels. Expected radiance:
  // rho/pi * E with E = sum over the texels of L cos(theta) solid angle, from the map's own
  // texel directions and solid angles.
  const glm::vec3 sun(8000.0f, 6000.0f, 3000.0f);
  const io::EnvMap env = test::make_sun_map(256, 100, 20, 2, sun);
  glm::dvec3 irradiance(0.0);
  for (int y = 0; y < env.height(); ++y) {
    for (int x = 0; x < env.width(); ++x) {
      glm::vec3 dir;
      float omega = 0.0f;
      ASSERT_TRUE(env.texel(x, y, &dir, &omega));
      irradiance +=
          glm::dvec3(env.texel_value(x, y)) * std::max(0.0, double(dir.y)) * double(omega);
    }
  }
  ASSERT_GT(irradiance.r, 0.0);
  const glm::vec3 rho(0.7f, 0.5f, 0.3f);
  const Scene scene = test::scene_of({test::make_plane(1.0f, 4)});
  const ReferenceRenderer renderer(scene, env, settings_with(0, 4096, rho), Context{});
  const VertexRadiance result = renderer.render_vertices(Context{});
  for (std::size_t v = 0; v < result.radiance.size(); ++v) {
    for (int c = 0; c < 3; ++c) {
      const double expected = rho[c] / kPi * irradiance[c];
      // 4096 samples, a share importance-sampled towards the four texels: a few times the
      // largest error over seeds.
      ASSERT_NEAR(result.radiance[v][c], expected, 0.005 * expected)
          << "vertex " << v << " c " << c;
    }
  }
}

TEST(ReferenceRenderer, SphereUnderRealMapsMatchesTexelSums) {
  // Direct light on a convex sphere (nothing blocked): at a vertex with normal n,
  // L = rho/pi * sum over the map's texels of L_t max(0, n.d_t) omega_t, from the texels' own
  // directions and solid angles, without the renderer's sampling. One map per mapping,
  // including the sun map and the cross whose padding must get no weight.
  const std::filesystem::path envmaps = std::filesystem::path(PRT_SHARED_DIR) / "assets/envmaps";
  const char* maps[] = {"spiaggia_di_mondello_1k.hdr", "grace_cross.hdr", "rnl_probe.hdr"};
  const Scene scene = test::scene_of({test::make_icosphere(1)});
  const float rho = 0.5f;
  for (const char* name : maps) {
    const std::filesystem::path path = envmaps / name;
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found";
    const io::EnvMap env = io::load_envmap(path.string(), io::EnvMapping::Auto);
    const ReferenceRenderer renderer(scene, env, settings_with(0, 4096, glm::vec3(rho)), Context{});
    const VertexRadiance result = renderer.render_vertices(Context{});
    struct Texel {
      glm::vec3 dir, weighted;  // direction; radiance x solid angle
    };
    std::vector<Texel> texels;
    for (int y = 0; y < env.height(); ++y) {
      for (int x = 0; x < env.width(); ++x) {
        glm::vec3 dir;
        float omega = 0.0f;
        if (env.texel(x, y, &dir, &omega)) texels.push_back({dir, env.texel_value(x, y) * omega});
      }
    }
    const Mesh& mesh = scene.meshes[0];
    double error_sq = 0.0, expected_sq = 0.0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      glm::dvec3 sum(0.0);
      for (const Texel& t : texels) {
        const float c = glm::dot(t.dir, mesh.normals[v]);
        if (c > 0.0f) sum += glm::dvec3(t.weighted) * static_cast<double>(c);
      }
      const glm::dvec3 expected = sum * (rho / kPi);
      const glm::dvec3 d = glm::dvec3(result.radiance[v]) - expected;
      error_sq += glm::dot(d, d);
      expected_sq += glm::dot(expected, expected);
    }
    // Texel sums and the integral of the bilinear radiance agree to a fraction of a percent.
    const double relative_error = std::sqrt(error_sq / expected_sq);
    EXPECT_LT(relative_error, 0.01) << name;
    RecordProperty(name, std::to_string(relative_error));
  }
}

TEST(ReferenceRenderer, SameSeedGivesIdenticalResultsOnOneAndTwoThreads) {
  const Scene scene = make_demo_scene();
  const io::EnvMap sky = make_demo_sky(128);
  ReferenceSettings settings;
  settings.bounces = 2;
  settings.spp = 4;
  settings.image_spp = 2;
  settings.seed = 42;
  const ReferenceRenderer renderer(scene, sky, settings, Context{});
  const VertexRadiance one = renderer.render_vertices(threads(1));
  const VertexRadiance two = renderer.render_vertices(threads(2));
  ASSERT_EQ(one.radiance.size(), two.radiance.size());
  EXPECT_EQ(std::memcmp(one.radiance.data(), two.radiance.data(), one.radiance.size() * 12), 0);
  EXPECT_EQ(one.relative_rmse, two.relative_rmse);
  EXPECT_EQ(one.stats.rays, two.stats.rays);

  const io::Camera camera = io::Camera::auto_frame(
      renderer.embree_scene().bounds_lo(), renderer.embree_scene().bounds_hi(), 4.0f / 3.0f);
  const io::LinearImage a = renderer.render_image(camera, 64, 48, threads(1));
  const io::LinearImage b = renderer.render_image(camera, 64, 48, threads(2));
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * 12), 0);

  // And a different seed gives a different (but close) answer.
  settings.seed = 43;
  const ReferenceRenderer other(scene, sky, settings, Context{});
  const VertexRadiance three = other.render_vertices(threads(2));
  EXPECT_NE(std::memcmp(one.radiance.data(), three.radiance.data(), one.radiance.size() * 12), 0);
}

// The scene command measures a few vertices of an object: each gets the bits it gets in the
// whole scene's render, in the list's order; an index past the scene is refused.
TEST(ReferenceRenderer, AListOfVerticesGetsTheirWholeSceneBits) {
  const Scene scene = make_demo_scene();
  const io::EnvMap sky = make_demo_sky(128);
  ReferenceSettings settings;
  settings.bounces = 1;
  settings.spp = 4;
  settings.seed = 5;
  const ReferenceRenderer renderer(scene, sky, settings, Context{});
  const VertexRadiance all = renderer.render_vertices(threads(2));
  const std::vector<std::size_t> subset = {9000, 3, 3, 12000, 0, scene.vertex_count() - 1};
  const VertexRadiance some = renderer.render_vertices(subset, threads(2));
  ASSERT_EQ(some.radiance.size(), subset.size());
  for (std::size_t i = 0; i < subset.size(); ++i) {
    EXPECT_EQ(std::memcmp(&some.radiance[i], &all.radiance[subset[i]], 12), 0) << subset[i];
  }
  EXPECT_GT(some.relative_rmse, 0.0);
  EXPECT_THROW(renderer.render_vertices({scene.vertex_count()}, Context{}), Error);
}

TEST(ReferenceRenderer, StatedNoiseMatchesTheDifferenceBetweenSeeds) {
  // Two independent runs differ by sqrt(2) x the RMSE of one: the estimate from the two halves
  // of each run must agree with that. Both are RMS over every vertex and channel of the demo
  // scene, so their ratio stays within a few percent of 1 over seeds: a noise figure off by
  // sqrt(2) fails.
  const Scene scene = make_demo_scene();
  const io::EnvMap sky = make_demo_sky(128);
  for (const int bounces : {0, 1}) {
    ReferenceSettings settings;
    settings.bounces = bounces;
    settings.spp = 16;
    settings.seed = 1;
    const ReferenceRenderer first(scene, sky, settings, Context{});
    settings.seed = 2;
    const ReferenceRenderer second(scene, sky, settings, Context{});
    const VertexRadiance a = first.render_vertices(Context{});
    const VertexRadiance b = second.render_vertices(Context{});
    double diff_sq = 0.0, radiance_sq = 0.0;
    for (std::size_t v = 0; v < a.radiance.size(); ++v) {
      const glm::dvec3 d = glm::dvec3(a.radiance[v]) - glm::dvec3(b.radiance[v]);
      diff_sq += glm::dot(d, d);
      radiance_sq += 0.5 * (glm::dot(glm::dvec3(a.radiance[v]), glm::dvec3(a.radiance[v])) +
                            glm::dot(glm::dvec3(b.radiance[v]), glm::dvec3(b.radiance[v])));
    }
    const double measured = std::sqrt(diff_sq / 2.0 / radiance_sq);
    const double stated = 0.5 * (a.relative_rmse + b.relative_rmse);
    EXPECT_GT(stated, 0.0);
    EXPECT_GT(measured / stated, 0.9)
        << "bounces " << bounces << " measured " << measured << " stated " << stated;
    EXPECT_LT(measured / stated, 1.1)
        << "bounces " << bounces << " measured " << measured << " stated " << stated;
  }
}

TEST(ReferenceRenderer, ImageShowsTheEnvironmentWhereRaysMissAndTheObjectWhereTheyHit) {
  // A sphere of albedo 0.5 in the white furnace: every hit pixel is 0.5, every miss is 1.
  const Scene scene = test::scene_of({test::make_icosphere(3)});
  const io::EnvMap env = io::constant_envmap(glm::vec3(1.0f));
  ReferenceSettings settings = settings_with(1, 2, glm::vec3(0.5f));
  settings.image_spp = 64;
  const ReferenceRenderer renderer(scene, env, settings, Context{});
  const io::Camera camera = io::Camera::auto_frame(glm::vec3(-1.0f), glm::vec3(1.0f), 1.0f);
  RenderStats stats;
  const io::LinearImage image = renderer.render_image(camera, 32, 32, Context{}, &stats);
  ASSERT_EQ(image.pixels.size(), 32u * 32u);
  EXPECT_NEAR(image.pixels[0].g, 1.0f, 1e-6f);  // corner: background
  double centre = 0.0;                          // the central 8x8 pixels: the sphere
  for (int y = 12; y < 20; ++y) {
    for (int x = 12; x < 20; ++x) centre += image.pixels[y * 32 + x].g / 64.0;
  }
  EXPECT_NEAR(centre, 0.5, 0.5 * 0.005);  // 64 x 64 samples: a few times their spread over seeds
  EXPECT_GT(stats.rays, 32u * 32u * 64u);
}

TEST(ReferenceRenderer, RejectsBadSettings) {
  const Scene scene = test::scene_of({test::make_plane(1.0f, 1)});
  const io::EnvMap env = io::constant_envmap(glm::vec3(1.0f));
  ReferenceSettings settings;
  settings.spp = 1;
  EXPECT_THROW(ReferenceRenderer(scene, env, settings, Context{}), Error);
  settings = ReferenceSettings{};
  settings.bounces = -1;
  EXPECT_THROW(ReferenceRenderer(scene, env, settings, Context{}), Error);
  settings = ReferenceSettings{};
  settings.override_albedo = true;
  settings.albedo = glm::vec3(1.5f);
  EXPECT_THROW(ReferenceRenderer(scene, env, settings, Context{}), Error);
}

TEST(ReferenceRenderer, CancelledProgressStopsTheRender) {
  const Scene scene = test::scene_of({test::make_icosphere(3)});
  const io::EnvMap env = io::constant_envmap(glm::vec3(1.0f));
  const ReferenceRenderer renderer(scene, env, ReferenceSettings{}, Context{});
  Context ctx;
  ctx.progress = [](double, const std::string&) { return false; };
  EXPECT_THROW(renderer.render_vertices(ctx), Error);
}

}  // namespace
}  // namespace prt::bake
