// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s source radiance fields: a diffuse sphere glowing with a constant
// basis function is seen from outside as a uniform cap, whose SH is zonal with coefficients
// from the integrals of Legendre polynomials (computed here), from inside as nothing (every
// ray reaches its back), and not at all through a blocker; a constant glossy BRDF glows as the
// diffuse sphere times its constant g; the fields are the same for any thread count; bad settings
// and objects are named. DISABLED_TeapotFigures prints the teapot's bake times, kept energy and
// field size
// (--gtest_also_run_disabled_tests).
#include <gtest/gtest.h>

#include <prt/prt_sh.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "prt/baker/scene.hpp"
#include "prt/baker/shadowfield/shadowfield_radiance.hpp"
#include "shadowfield/radiance/radiance_test_objects.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

using test::object_of;
using test::rays_of;

constexpr double kPi = 3.14159265358979323846;

std::string thrown_message(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& error) {
    return error.what();
  }
  return "(nothing thrown)";
}

// integral over [x, 1] of the Legendre polynomial P_l.
double legendre_tail(int l, double x) {
  if (l == 0) return 1.0 - x;
  double previous = 1.0, current = x;  // P_0, P_1
  std::vector<double> p = {previous, current};
  for (int n = 1; n <= l; ++n) {
    const double next = ((2 * n + 1) * x * current - n * previous) / (n + 1);
    previous = current;
    current = next;
    p.push_back(current);
  }
  return (p[l - 1] - p[l + 1]) / (2 * l + 1);
}

// SH (order n) of the function equal to `value` inside the cap of half-angle alpha about unit
// axis u: zonal about u, f_lm = value 2 pi integral_{cos alpha}^1 P_l Y_lm(u).
std::vector<double> cap_coefficients(std::uint32_t order, const glm::vec3& axis, double alpha,
                                     double value) {
  std::vector<float> y(order * order);
  prt_sh_eval(order, &axis.x, y.data());
  std::vector<double> out(y.size());
  for (int l = 0; l < int(order); ++l)
    for (int m = -l; m <= l; ++m)
      out[l * (l + 1) + m] =
          value * 2.0 * kPi * legendre_tail(l, std::cos(alpha)) * y[l * (l + 1) + m];
  return out;
}

// A finely tessellated unit sphere (inradius within 2e-4 of 1) glowing with B_0 = c.
constexpr float kGlow = 0.7f;
const Mesh& unit_sphere() {
  static const Mesh mesh = test::make_icosphere(5);
  return mesh;
}
ShadowfieldObject glowing_sphere() {
  ShadowfieldObject object = object_of(unit_sphere());
  test::set_sphere(object, glm::vec3(0.0f), 1.0f);
  object.basis_size = 1;
  object.basis.assign(unit_sphere().positions.size(), kGlow);
  return object;
}

// The largest error of any coefficient at any point against the cap seen from the point, over
// the constant's own coefficient c sqrt(4 pi), for field `field`, scaled by `g`.
double cap_error(const ShadowfieldObject& object, std::uint32_t field, double g) {
  const std::size_t n2 = std::size_t(object.order) * object.order;
  const std::uint64_t points = prt_sf_point_count(&object.srf_shells);
  double error = 0.0;
  for (std::uint64_t point = 0; point < points; ++point) {
    float p[3];
    prt_sf_point_position(&object.srf_shells, point, p);
    const glm::vec3 position(p[0], p[1], p[2]);
    const double distance = glm::length(position);
    const std::vector<double> expected = cap_coefficients(object.order, -position / float(distance),
                                                          std::asin(1.0 / distance), g * kGlow);
    const float* got = object.srf.data() + (field * points + point) * n2;
    for (std::size_t c = 0; c < n2; ++c) error = std::max(error, std::fabs(got[c] - expected[c]));
  }
  return error / (kGlow * std::sqrt(4.0 * kPi));
}

const SrfSettings kOutside{3, 2, 1.5f, 6.0f, 4096, 0};

TEST(Srf, ADiffuseSphereGlowsAsAnAnalyticCap) {
  ShadowfieldObject object = glowing_sphere();
  const SrfReport report =
      bake_source_radiance_fields(object, *rays_of(unit_sphere()), kOutside, Context{});
  ASSERT_EQ(report.points, 3u * 6 * 4);
  ASSERT_EQ(object.srf.size(), report.points * 16);
  EXPECT_EQ(report.floats, object.srf.size());
  EXPECT_FLOAT_EQ(object.srf_shells.radius, 1.0f);
  EXPECT_EQ(object.srf_shells.shells, 3u);
  // Quadrature of the cap's edge by 4096 directions; measured 2.5e-3.
  EXPECT_LT(cap_error(object, 0, 1.0), 6e-3);
}

TEST(Srf, MoreDirectionsConvergeToTheCap) {
  ShadowfieldObject few = glowing_sphere(), many = glowing_sphere();
  const auto rays = rays_of(unit_sphere());
  SrfSettings settings = kOutside;
  settings.directions = 256;
  bake_source_radiance_fields(few, *rays, settings, Context{});
  settings.directions = 16384;
  bake_source_radiance_fields(many, *rays, settings, Context{});
  EXPECT_LT(cap_error(many, 0, 1.0), 0.5 * cap_error(few, 0, 1.0));
}

TEST(Srf, FromInsideAClosedSurfaceNothingGlows) {
  ShadowfieldObject object = glowing_sphere();
  bake_source_radiance_fields(object, *rays_of(unit_sphere()), {2, 2, 0.2f, 0.8f, 256, 0},
                              Context{});
  for (float value : object.srf) ASSERT_EQ(value, 0.0f);
}

TEST(Srf, OtherGeometryBlocksButDoesNotGlow) {
  // A closed shell around the sphere, inside the innermost SRF shell: every ray hits it first.
  ShadowfieldObject object = glowing_sphere();
  const auto rays = rays_of(unit_sphere(), {test::make_icosphere(2, 1.3f)});
  bake_source_radiance_fields(object, *rays, kOutside, Context{});
  for (float value : object.srf) ASSERT_EQ(value, 0.0f);
}

TEST(Srf, AConstantGlossyBrdfGlowsAsTheDiffuseTimesItsG) {
  // Phong with n = 0 is the constant 1/pi = g_0 h_0 with g_0 = h_0 = 1/sqrt(pi).
  ShadowfieldObject diffuse = glowing_sphere(), glossy = glowing_sphere();
  glossy.material = test::phong_material(0.0, 1);
  const auto rays = rays_of(unit_sphere());
  bake_source_radiance_fields(diffuse, *rays, kOutside, Context{});
  bake_source_radiance_fields(glossy, *rays, kOutside, Context{});
  ASSERT_EQ(glossy.srf.size(), diffuse.srf.size());
  double error = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < diffuse.srf.size(); ++i) {
    error = std::max(error, std::fabs(glossy.srf[i] - diffuse.srf[i] / std::sqrt(kPi)));
    largest = std::max(largest, double(std::fabs(diffuse.srf[i])));
  }
  // Float rounding: measured 3.8e-8.
  EXPECT_LT(error / largest, 1e-7);
}

TEST(Srf, OneShellStoresItsRadiusAsBothEnds) {
  ShadowfieldObject object = glowing_sphere();
  bake_source_radiance_fields(object, *rays_of(unit_sphere()), {1, 1, 2.0f, 8.0f, 1024, 0},
                              Context{});
  EXPECT_EQ(object.srf_shells.outer, 2.0f);
  EXPECT_EQ(object.srf.size(), 6u * 16);
  // 1024 directions: measured 5.1e-3.
  EXPECT_LT(cap_error(object, 0, 1.0), 1.2e-2);
}

// The ball over the floor with a glossy 8-function basis.
ShadowfieldObject glossy_ball_on_floor(const EmbreeScene& rays, const Mesh& mesh) {
  ShadowfieldObject object = object_of(mesh, glm::vec3(0.9f, 0.5f, 0.3f));
  object.material = test::phong_material(10.0, 4);
  bake_surface_basis(object, rays, {8, 64, 2.0}, Context{});
  return object;
}

TEST(Srf, IsTheSameForAnyThreadCount) {
  const Mesh mesh = test::merged(
      {test::make_plane(1.5f, 8), test::make_icosphere(1, 0.5f, glm::vec3(0, 0.6f, 0))});
  const auto rays = rays_of(mesh);
  const ShadowfieldObject baked = glossy_ball_on_floor(*rays, mesh);
  std::vector<std::vector<float>> fields;
  for (unsigned threads : {1u, 2u, 3u}) {
    ShadowfieldObject object = baked;
    Context ctx;
    ctx.threads = threads;
    const SrfReport report =
        bake_source_radiance_fields(object, *rays, {2, 2, 0.5f, 4.0f, 256, 5}, ctx);
    EXPECT_EQ(report.floats, 8u * 4 * report.points * 16);
    fields.push_back(object.srf);
  }
  EXPECT_EQ(fields[0], fields[1]);
  EXPECT_EQ(fields[0], fields[2]);
  double largest = 0.0;
  for (float value : fields[0]) largest = std::max(largest, double(std::fabs(value)));
  EXPECT_GT(largest, 0.0);
}

TEST(Errors, BadSrfSettingsAreNamed) {
  const auto rays = rays_of(unit_sphere());
  auto bake = [&](SrfSettings settings) {
    return thrown_message([&] {
      ShadowfieldObject object = glowing_sphere();
      bake_source_radiance_fields(object, *rays, settings, Context{});
    });
  };
  EXPECT_NE(bake({0, 2, 0.2f, 8.0f, 64, 0}).find("shells"), std::string::npos);
  EXPECT_NE(bake({2, 0, 0.2f, 8.0f, 64, 0}).find("face_size"), std::string::npos);
  EXPECT_NE(bake({2, 2, 0.0f, 8.0f, 64, 0}).find("inner"), std::string::npos);
  EXPECT_NE(bake({2, 2, NAN, 8.0f, 64, 0}).find("inner"), std::string::npos);
  EXPECT_NE(bake({2, 2, 0.2f, 0.1f, 64, 0}).find("outer"), std::string::npos);
  EXPECT_NE(bake({2, 2, 0.2f, INFINITY, 64, 0}).find("outer"), std::string::npos);
  EXPECT_NE(bake({2, 2, 0.2f, 8.0f, 0, 0}).find("directions"), std::string::npos);
  EXPECT_NE(bake({256, 256, 0.2f, 8.0f, 64, 0}).find("size limit"), std::string::npos);
}

TEST(Errors, AnObjectWithoutABasisOrWithABadOrderIsNamed) {
  const auto rays = rays_of(unit_sphere());
  auto bake = [&](const std::function<void(ShadowfieldObject&)>& spoil) {
    return thrown_message([&] {
      ShadowfieldObject object = glowing_sphere();
      spoil(object);
      bake_source_radiance_fields(object, *rays, {2, 2, 0.2f, 8.0f, 64, 0}, Context{});
    });
  };
  EXPECT_NE(bake([](ShadowfieldObject& o) { o.basis_size = 0; }).find("no surface-radiance basis"),
            std::string::npos);
  EXPECT_NE(bake([](ShadowfieldObject& o) { o.basis.pop_back(); }).find("no surface-radiance"),
            std::string::npos);
  EXPECT_NE(bake([](ShadowfieldObject& o) { o.order = 1; }).find("order must be in 2..6"),
            std::string::npos);
  EXPECT_NE(bake([](ShadowfieldObject& o) { o.order = 7; }).find("order must be in 2..6"),
            std::string::npos);
}

TEST(Errors, CancellingStopsTheFields) {
  ShadowfieldObject object = glowing_sphere();
  Context ctx;
  ctx.progress = [](double, const std::string&) { return false; };
  EXPECT_EQ(thrown_message([&] {
              bake_source_radiance_fields(object, *rays_of(unit_sphere()), kOutside, ctx);
            }),
            "cancelled");
  EXPECT_TRUE(object.srf.empty());
}

// ---- Figures -----------------------------------------------------------------------------------

double seconds_of(const std::function<void()>& call) {
  const auto start = std::chrono::steady_clock::now();
  call();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(Figures, DISABLED_TeapotFigures) {
  const std::string path = prt_test::shared_asset("meshes/teapot.obj");
  if (path.empty()) GTEST_SKIP() << "shared assets missing";
  const Scene scene = import_scene(path, Context{});
  std::vector<Mesh> meshes = scene.meshes;
  const Mesh mesh = test::merged(meshes);
  const auto rays = rays_of(mesh);
  Context ctx;
  ctx.threads = 2;
  for (bool glossy : {false, true}) {
    ShadowfieldObject object = object_of(mesh);
    if (glossy) object.material = test::phong_material(10.0, 4);
    ShadowfieldBasisReport basis;
    const double basis_seconds =
        seconds_of([&] { basis = bake_surface_basis(object, *rays, {}, ctx); });
    SrfReport srf;
    const double srf_seconds =
        seconds_of([&] { srf = bake_source_radiance_fields(object, *rays, {}, ctx); });
    std::printf(
        "%s teapot, %zu vertices: basis %.2f s (%zu samples), energy kept N=4 %.6f N=8 %.6f "
        "N=16 %.6f; srf %.2f s, %llu points, %zu floats\n",
        glossy ? "phong n=10 K=4" : "diffuse", mesh.positions.size(), basis_seconds, basis.samples,
        basis.energy_kept_by(4), basis.energy_kept_by(8), basis.energy_kept_by(16), srf_seconds,
        static_cast<unsigned long long>(srf.points), srf.floats);
  }
}

}  // namespace
}  // namespace prt::bake
