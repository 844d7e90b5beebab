// SPDX-License-Identifier: MIT
// The reference renderer's glossy surfaces and view-dependent radiance against values computed
// another way: brute-force quadratures of the exact BRDF (shadowfield_brdf.hpp), which share no
// code with the renderer's sampling; plus the Lambertian case's indifference to the eye and
// determinism across thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/reference.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

constexpr double kPi = 3.14159265358979323846;

double evaluate(const SurfaceBrdf& brdf, const glm::dvec3& w, const glm::dvec3& wo) {
  return brdf.model == SurfaceBrdf::Model::Phong ? evaluate_brdf(brdf.phong, w, wo)
                                                 : evaluate_brdf(brdf.ggx, w, wo);
}

// A unit vector's orthonormal completion (any will do: both models are isotropic).
void basis(const glm::dvec3& n, glm::dvec3* t, glm::dvec3* b) {
  *t = glm::normalize(std::abs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0))
                                          : glm::cross(n, glm::dvec3(0, 1, 0)));
  *b = glm::cross(n, *t);
}

// Directional albedo, integral of f(w, wo) max(0, w.z) dw over the sphere, in the local frame
// (normal +Z): the midpoint rule in polar coordinates about the mirror direction of wo, where
// every lobe here peaks, fine enough in the polar angle for a Phong lobe of exponent 1000.
double directional_albedo(const SurfaceBrdf& brdf, const glm::dvec3& wo) {
  constexpr int kPolar = 3000, kAzimuth = 256;
  const glm::dvec3 mirror(-wo.x, -wo.y, wo.z);
  glm::dvec3 t, b;
  basis(mirror, &t, &b);
  double sum = 0.0;
  for (int i = 0; i < kPolar; ++i) {
    const double a = (i + 0.5) * kPi / kPolar;
    double ring = 0.0;
    for (int j = 0; j < kAzimuth; ++j) {
      const double phi = (j + 0.5) * 2.0 * kPi / kAzimuth;
      const glm::dvec3 w =
          std::cos(a) * mirror + std::sin(a) * (std::cos(phi) * t + std::sin(phi) * b);
      if (w.z > 0.0) ring += evaluate(brdf, w, wo) * w.z;
    }
    sum += ring * std::sin(a);
  }
  return sum * (kPi / kPolar) * (2.0 * kPi / kAzimuth);
}

// wo of a vertex in its local frame, as the renderer sees it: towards the eye.
glm::dvec3 local_outgoing(const glm::vec3& position, const glm::vec3& normal,
                          const glm::vec3& eye) {
  const glm::dvec3 n = glm::normalize(glm::dvec3(normal));
  glm::dvec3 t, b;
  basis(n, &t, &b);
  const glm::dvec3 wo = glm::normalize(glm::dvec3(eye) - glm::dvec3(position));
  return {glm::dot(wo, t), glm::dot(wo, b), glm::dot(wo, n)};
}

ReferenceSettings glossy_settings(const SurfaceBrdf& brdf, std::uint32_t spp, float albedo) {
  ReferenceSettings settings;
  settings.spp = spp;
  settings.override_albedo = true;
  settings.albedo = glm::vec3(albedo);
  settings.brdf = brdf;
  return settings;
}

struct GlossyCase {
  const char* name;
  SurfaceBrdf brdf;
  double tolerance;
};

// White furnace: a closed convex sphere under radiance 1 never sees itself, so each vertex
// reflects albedo x the BRDF's directional albedo at its view angle (0 where it faces away from
// the eye), whatever the bounces.
class GlossyFurnace : public ::testing::TestWithParam<GlossyCase> {};

TEST_P(GlossyFurnace, EveryVertexReflectsTheDirectionalAlbedoAtItsViewAngle) {
  const GlossyCase& c = GetParam();
  const Scene scene = test::scene_of({test::make_icosphere(3)});
  const io::EnvMap env = io::constant_envmap(glm::vec3(1.0f));
  const float rho = 0.9f;
  ReferenceSettings settings = glossy_settings(c.brdf, 1024, rho);
  settings.bounces = 1;
  const ReferenceRenderer renderer(scene, env, settings, Context{});
  const glm::vec3 eye(0.3f, 0.5f, 4.0f);
  const VertexRadiance result = renderer.render_vertices(Context{}, eye);
  const Mesh& mesh = scene.meshes[0];
  double largest = 0.0;
  // Every 23rd vertex: view angles from head-on to grazing and beyond.
  for (std::size_t v = 0; v < mesh.vertex_count(); v += 23) {
    const glm::dvec3 wo = local_outgoing(mesh.positions[v], mesh.normals[v], eye);
    const double expected = wo.z > 0.0 ? rho * directional_albedo(c.brdf, wo) : 0.0;
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(result.radiance[v][ch], expected, c.tolerance)
          << c.name << " vertex " << v << " cos(view) " << wo.z;
    }
    largest = std::max(largest, std::abs(result.radiance[v].g - expected));
  }
  RecordProperty("largest_error", std::to_string(largest));
  RecordProperty("relative_rmse", std::to_string(result.relative_rmse));
}

INSTANTIATE_TEST_SUITE_P(
    Models, GlossyFurnace,
    // Tolerances, absolute on radiance: 2-4x the largest error over the vertices checked with
    // this seed, 1.5-2x the largest over a few other seeds (docs/reference-renderer.md).
    ::testing::Values(GlossyCase{"phong10", SurfaceBrdf::of(PhongBrdf{10.0, 1.0, 0.0}), 0.0025},
                      GlossyCase{"phong1000", SurfaceBrdf::of(PhongBrdf{1000.0, 1.0, 0.0}), 0.0025},
                      GlossyCase{"ggx0.3", SurfaceBrdf::of(GgxBrdf{0.3, 0.5}), 0.0025}),
    [](const auto& info) {
      std::string name = info.param.name;
      for (char& ch : name) ch = ch == '.' ? '_' : ch;
      return name;
    });

// A lat-long map, black but for a disc of radiance `radiance` about `centre` (unit) of angular
// radius `radius`: the texels whose centres lie inside it.
io::EnvMap make_disc_map(int width, const glm::vec3& centre, double radius, float radiance) {
  const int height = width / 2;
  io::EnvMap probe(width, height, std::vector<float>(std::size_t(width) * height * 3, 0.0f),
                   io::EnvMapping::LatLong, "probe");
  std::vector<float> rgb(std::size_t(width) * height * 3, 0.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      glm::vec3 dir;
      float omega = 0.0f;
      probe.texel(x, y, &dir, &omega);
      if (glm::dot(dir, centre) < std::cos(radius)) continue;
      for (int c = 0; c < 3; ++c) rgb[(std::size_t(y) * width + x) * 3 + c] = radiance;
    }
  }
  return io::EnvMap(width, height, std::move(rgb), io::EnvMapping::LatLong, "disc");
}

// A glossy plane under a small bright disc, seen from the disc's mirror direction (where the
// lobe points at it): each vertex reflects albedo x the integral of f(w, wo) cos(w) L over the
// disc, here the sum over the map's own texels of L_t f(w_t, wo) cos(w_t) omega_t.
TEST(GlossyReference, PlaneUnderADiscLightReflectsTheIntegralOfTheBrdfOverTheDisc) {
  const double tilt = 30.0 * kPi / 180.0;
  const glm::vec3 centre(std::sin(tilt), std::cos(tilt), 0.0f);
  const io::EnvMap env = make_disc_map(512, centre, 0.1, 100.0f);
  const Scene scene = test::scene_of({test::make_plane(1.0f, 4)});
  const glm::vec3 eye = 1000.0f * glm::vec3(-centre.x, centre.y, 0.0f);
  const float rho = 0.8f;
  // Tolerances on the largest relative error over the vertices: 2-3x what this seed gives,
  // 1.8-2x the largest over a few other seeds (docs/reference-renderer.md).
  const GlossyCase cases[] = {
      {"phong100", SurfaceBrdf::of(PhongBrdf{100.0, 1.0, 0.0}), 0.01},
      {"ggx0_3", SurfaceBrdf::of(GgxBrdf{0.3, 0.04}), 0.015},
  };
  for (const GlossyCase& c : cases) {
    const ReferenceRenderer renderer(scene, env, glossy_settings(c.brdf, 1024, rho), Context{});
    const VertexRadiance result = renderer.render_vertices(Context{}, eye);
    const Mesh& mesh = scene.meshes[0];
    double largest = 0.0, mean = 0.0;  // relative errors
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      // The plane's normal is +Y: local (x, y, z) = world (x, -z, y) keeps a right-handed frame.
      auto local = [](const glm::dvec3& d) { return glm::dvec3(d.x, -d.z, d.y); };
      const glm::dvec3 wo = local(glm::normalize(glm::dvec3(eye) - glm::dvec3(mesh.positions[v])));
      double sum = 0.0;
      for (int y = 0; y < env.height(); ++y) {
        for (int x = 0; x < env.width(); ++x) {
          const float value = env.texel_value(x, y).g;
          glm::vec3 dir;
          float omega = 0.0f;
          if (value == 0.0f || !env.texel(x, y, &dir, &omega)) continue;
          const glm::dvec3 w = local(glm::dvec3(dir));
          if (w.z > 0.0) sum += value * evaluate(c.brdf, w, wo) * w.z * omega;
        }
      }
      const double expected = rho * sum;
      largest = std::max(largest, std::abs(result.radiance[v].g / expected - 1.0));
      mean += (result.radiance[v].g / expected - 1.0) / mesh.vertex_count();
    }
    RecordProperty(std::string(c.name) + "_largest_relative_error", std::to_string(largest));
    RecordProperty(std::string(c.name) + "_mean_relative_error", std::to_string(mean));
    EXPECT_LT(largest, c.tolerance) << c.name;
    // Over seeds and map sizes the mean stays within about 0.1 %: no bias.
    EXPECT_LT(std::abs(mean), 0.003) << c.name;
  }
}

// A Lambertian surface reflects the same towards every eye: its path never reads the view.
TEST(GlossyReference, LambertianSceneWithAnEyeGivesTheBytesOfNoEye) {
  const Scene scene = make_demo_scene();
  const io::EnvMap sky = make_demo_sky(128);
  ReferenceSettings settings;
  settings.bounces = 2;
  settings.spp = 8;
  const ReferenceRenderer renderer(scene, sky, settings, Context{});
  const VertexRadiance plain = renderer.render_vertices(Context{});
  const VertexRadiance seen = renderer.render_vertices(Context{}, glm::vec3(1.0f, 2.0f, 3.0f));
  ASSERT_EQ(plain.radiance.size(), seen.radiance.size());
  EXPECT_EQ(std::memcmp(plain.radiance.data(), seen.radiance.data(), plain.radiance.size() * 12),
            0);
  EXPECT_EQ(plain.stats.rays, seen.stats.rays);
}

TEST(GlossyReference, GlossyResultsAreIdenticalOnOneAndTwoThreads) {
  const Scene scene = make_demo_scene();
  const io::EnvMap sky = make_demo_sky(128);
  ReferenceSettings settings;
  settings.bounces = 2;
  settings.spp = 4;
  settings.image_spp = 2;
  settings.seed = 5;
  settings.mesh_brdfs.assign(scene.meshes.size(), SurfaceBrdf::of(GgxBrdf{0.2, 0.5}));
  settings.mesh_brdfs[0] = SurfaceBrdf::of(PhongBrdf{30.0, 0.5, 0.4});
  const ReferenceRenderer renderer(scene, sky, settings, Context{});
  Context one, two;
  one.threads = 1;
  two.threads = 2;
  const glm::vec3 eye(0.0f, 1.0f, 5.0f);
  const VertexRadiance a = renderer.render_vertices(one, eye);
  const VertexRadiance b = renderer.render_vertices(two, eye);
  ASSERT_EQ(a.radiance.size(), b.radiance.size());
  EXPECT_EQ(std::memcmp(a.radiance.data(), b.radiance.data(), a.radiance.size() * 12), 0);
  EXPECT_EQ(a.stats.rays, b.stats.rays);
  const io::Camera camera = io::Camera::auto_frame(
      renderer.embree_scene().bounds_lo(), renderer.embree_scene().bounds_hi(), 4.0f / 3.0f);
  const io::LinearImage image_a = renderer.render_image(camera, 32, 24, one);
  const io::LinearImage image_b = renderer.render_image(camera, 32, 24, two);
  EXPECT_EQ(std::memcmp(image_a.pixels.data(), image_b.pixels.data(), image_a.pixels.size() * 12),
            0);
  // And the view matters on a glossy surface.
  const VertexRadiance c = renderer.render_vertices(one, glm::vec3(5.0f, 1.0f, 0.0f));
  EXPECT_NE(std::memcmp(a.radiance.data(), c.radiance.data(), a.radiance.size() * 12), 0);
}

TEST(GlossyReference, RejectsBadBrdfsAndParsesTheirNames) {
  const Scene scene = test::scene_of({test::make_plane(1.0f, 1)});
  const io::EnvMap env = io::constant_envmap(glm::vec3(1.0f));
  ReferenceSettings settings;
  settings.brdf = SurfaceBrdf::of(GgxBrdf{0.0, 0.04});
  EXPECT_THROW(ReferenceRenderer(scene, env, settings, Context{}), Error);
  settings.brdf = SurfaceBrdf::of(PhongBrdf{NAN, 1.0, 0.0});
  EXPECT_THROW(ReferenceRenderer(scene, env, settings, Context{}), Error);
  settings = ReferenceSettings{};
  settings.mesh_brdfs.resize(2);  // the scene has one mesh
  EXPECT_THROW(ReferenceRenderer(scene, env, settings, Context{}), Error);

  EXPECT_EQ(parse_surface_brdf("lambert").model, SurfaceBrdf::Model::Lambert);
  const SurfaceBrdf phong = parse_surface_brdf("phong:10");
  EXPECT_EQ(phong.model, SurfaceBrdf::Model::Phong);
  EXPECT_EQ(phong.phong.exponent, 10.0);
  EXPECT_EQ(phong.phong.specular, 1.0);
  EXPECT_EQ(surface_brdf_name(parse_surface_brdf("phong:20,0.5,0.25")), "phong:20,0.5,0.25");
  EXPECT_EQ(surface_brdf_name(parse_surface_brdf("ggx:0.3")), "ggx:0.3,0.04");
  for (const char* bad : {"", "phong", "phong:", "phong:x", "phong:1,2,3,4", "ggx:0", "ggx:0.3,2",
                          "ggx:0.3,", "mirror:1", "phong:-1", "ggx:nan"}) {
    EXPECT_THROW(parse_surface_brdf(bad), Error) << bad;
  }
}

// The relative RMS difference between two runs, and the noise their halves state for it.
struct RunDifference {
  double measured = 0.0, stated = 0.0;
};
RunDifference compare_runs(const VertexRadiance& a, const VertexRadiance& b) {
  double diff_sq = 0.0, radiance_sq = 0.0;
  for (std::size_t v = 0; v < a.radiance.size(); ++v) {
    const glm::dvec3 d = glm::dvec3(a.radiance[v]) - glm::dvec3(b.radiance[v]);
    diff_sq += glm::dot(d, d);
    radiance_sq += 0.5 * (glm::dot(glm::dvec3(a.radiance[v]), glm::dvec3(a.radiance[v])) +
                          glm::dot(glm::dvec3(b.radiance[v]), glm::dvec3(b.radiance[v])));
  }
  return {std::sqrt(diff_sq / radiance_sq), std::hypot(a.relative_rmse, b.relative_rmse)};
}

// Phong with exponent 0 is the constant 1/pi, and Phong with only its diffuse part is kd/pi:
// Lambert, but estimated through the glossy path (lobe and mixture sampling, the view carried
// from bounce to bounce). With bounces, both must agree with the Lambertian estimate within the
// noise the two runs state. No eye: a glossy surface seen from behind reflects nothing, where
// Lambert never reads the view.
TEST(GlossyReference, ConstantGlossyBrdfsAgreeWithLambertWithBounces) {
  const Scene scene = make_demo_scene();
  const io::EnvMap sky = make_demo_sky(128);
  ReferenceSettings settings;
  settings.bounces = 2;
  settings.spp = 16;
  const ReferenceRenderer lambert(scene, sky, settings, Context{});
  const VertexRadiance expected = lambert.render_vertices(Context{});
  settings.seed = 1;
  for (const char* brdf : {"phong:0", "phong:20,0,1"}) {
    settings.brdf = parse_surface_brdf(brdf);
    const ReferenceRenderer glossy(scene, sky, settings, Context{});
    const RunDifference d = compare_runs(expected, glossy.render_vertices(Context{}));
    RecordProperty(std::string(brdf) == "phong:0" ? "constant" : "diffuse_only",
                   std::to_string(d.measured / d.stated));
    EXPECT_GT(d.measured / d.stated, 0.9) << brdf << " " << d.measured << " " << d.stated;
    EXPECT_LT(d.measured / d.stated, 1.1) << brdf << " " << d.measured << " " << d.stated;
  }
}

// Two runs of a glossy scene with different seeds differ by what their halves state.
TEST(GlossyReference, StatedNoiseMatchesTheDifferenceBetweenSeeds) {
  const Scene scene = make_demo_scene();
  const io::EnvMap sky = make_demo_sky(128);
  ReferenceSettings settings;
  settings.bounces = 1;
  settings.spp = 32;
  settings.brdf = SurfaceBrdf::of(GgxBrdf{0.2, 0.5});
  const glm::vec3 eye(1.0f, 2.0f, 5.0f);
  settings.seed = 1;
  const ReferenceRenderer first(scene, sky, settings, Context{});
  settings.seed = 2;
  const ReferenceRenderer second(scene, sky, settings, Context{});
  const RunDifference d =
      compare_runs(first.render_vertices(Context{}, eye), second.render_vertices(Context{}, eye));
  RecordProperty("ratio", std::to_string(d.measured / d.stated));
  EXPECT_GT(d.measured / d.stated, 0.9) << d.measured << " " << d.stated;
  EXPECT_LT(d.measured / d.stated, 1.1) << d.measured << " " << d.stated;
}

// An eye that is not a usable point (NaN), or that sits on a vertex, leaves the view along the
// normal: the same bytes as no eye there.
TEST(GlossyReference, AnEyeWithoutADirectionFallsBackToTheNormal) {
  const Scene scene = test::scene_of({test::make_icosphere(1)});
  const io::EnvMap sky = make_demo_sky(64);
  ReferenceSettings settings = glossy_settings(SurfaceBrdf::of(PhongBrdf{10.0, 1.0, 0.0}), 8, 1.0f);
  const ReferenceRenderer renderer(scene, sky, settings, Context{});
  const VertexRadiance plain = renderer.render_vertices(Context{});
  const VertexRadiance nan_eye = renderer.render_vertices(Context{}, glm::vec3(NAN, 0.0f, 0.0f));
  EXPECT_EQ(std::memcmp(plain.radiance.data(), nan_eye.radiance.data(), plain.radiance.size() * 12),
            0);
  const glm::vec3 vertex = scene.meshes[0].positions[5];
  const VertexRadiance on_vertex = renderer.render_vertices(Context{}, vertex);
  EXPECT_EQ(std::memcmp(&plain.radiance[5], &on_vertex.radiance[5], 12), 0);
  EXPECT_NE(std::memcmp(&plain.radiance[6], &on_vertex.radiance[6], 12), 0);
  for (const glm::vec3& r : on_vertex.radiance) EXPECT_TRUE(std::isfinite(r.g));
}

// An image pixel is shaded towards the camera: a sphere with the constant Phong (n = 0, 1/pi)
// in the white furnace shows its albedo wherever it is hit, through the glossy path.
TEST(GlossyReference, ImageOfAGlossySphereInTheFurnaceShowsItsAlbedo) {
  const Scene scene = test::scene_of({test::make_icosphere(3)});
  const io::EnvMap env = io::constant_envmap(glm::vec3(1.0f));
  ReferenceSettings settings = glossy_settings(parse_surface_brdf("phong:0"), 2, 0.5f);
  settings.image_spp = 64;
  const ReferenceRenderer renderer(scene, env, settings, Context{});
  const io::Camera camera = io::Camera::auto_frame(glm::vec3(-1.0f), glm::vec3(1.0f), 1.0f);
  const io::LinearImage image = renderer.render_image(camera, 32, 32, Context{});
  double centre = 0.0;  // the central 8x8 pixels: the sphere
  for (int y = 12; y < 20; ++y) {
    for (int x = 12; x < 20; ++x) centre += image.pixels[y * 32 + x].g / 64.0;
  }
  RecordProperty("centre", std::to_string(centre));
  // Unlike cosine sampling of Lambert, the lobe's samples vary: about twice the largest error
  // over a few seeds.
  EXPECT_NEAR(centre, 0.5, 0.005);
}

}  // namespace
}  // namespace prt::bake
