// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s basis comparison (prt/baker/shadowfield/shadowfield_basis_study.hpp)
// on small generated meshes: every family orthonormal under W; a radiance that is one of a
// family's functions (written here from its formula) reproduced by that family exactly, and not
// by one that stops before it; errors that never rise with N; the PCA's least error on its own
// training samples against every other family (Eckart-Young); the receiver's irradiance from a
// glowing square against the analytic form factor; the comparison's rows and their bounds; the
// extremes (as many functions as vertices, non-finite uv, positions and weights, receivers
// without a normal) and the errors of bad input. Tolerances are a few times the rounding
// measured.
#include <gtest/gtest.h>

#include <prt/prt_sh.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/shadowfield/shadowfield_basis_study.hpp"
#include "prt/baker/shadowfield/shadowfield_fields.hpp"
#include "support/render_test_scenes.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string thrown_message(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& error) {
    return error.what();
  }
  return "(nothing thrown)";
}

struct Surface {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uv;
  std::vector<float> weights;
};

Surface surface_of(const Mesh& mesh, std::vector<glm::vec2> uv) {
  ShadowfieldObject object;
  object.positions = mesh.positions;
  object.indices = mesh.indices;
  return {mesh.positions, std::move(uv), shadowfield_vertex_weights(object)};
}

Surface floor_surface(int side = 12) {
  const Mesh floor = make_study_floor(glm::vec2(0.0f), 1.0f, 0.0f, side);
  return surface_of(floor, floor.texcoords0);
}

// The unit sphere with its latitude-longitude uv: uneven vertex spacing and area in uv.
Surface sphere_surface() {
  const Mesh sphere = test::make_icosphere(2);
  std::vector<glm::vec2> uv;
  for (const glm::vec3& p : sphere.positions)
    uv.emplace_back(0.5 + std::atan2(p.z, p.x) / (2.0 * kPi),
                    std::acos(std::clamp(double(p.y), -1.0, 1.0)) / kPi);
  return surface_of(sphere, uv);
}

SurfaceBasis family(SurfaceBasisFamily which, const Surface& s, std::size_t size) {
  switch (which) {
    case SurfaceBasisFamily::SphericalHarmonics:
      return sh_surface_basis(s.positions, glm::vec3(0.0f), s.weights, size);
    case SurfaceBasisFamily::Haar:
      return haar_surface_basis(s.uv, s.weights, size);
    default:
      return cosine_surface_basis(s.uv, s.weights, size);
  }
}

const SurfaceBasisFamily kFixedFamilies[] = {SurfaceBasisFamily::SphericalHarmonics,
                                             SurfaceBasisFamily::Haar,
                                             SurfaceBasisFamily::FourierCosine};

double weighted_norm(const std::vector<double>& a, const std::vector<double>& b,
                     const std::vector<float>& weights) {
  double sum = 0.0;
  for (std::size_t v = 0; v < a.size(); ++v)
    sum += double(weights[v]) * (a[v] - b[v]) * (a[v] - b[v]);
  return std::sqrt(sum);
}

// ||r - B^T A^-1 B W r||_W / ||r||_W.
double relative_error(const SurfaceBasis& basis, const std::vector<float>& weights,
                      const std::vector<double>& r) {
  const std::vector<double> zero(r.size(), 0.0);
  return weighted_norm(r, approximated_radiance(basis, weights, r), weights) /
         weighted_norm(r, zero, weights);
}

TEST(Bases, AreOrthonormalUnderTheVertexAreas) {
  for (const Surface& surface : {floor_surface(), sphere_surface()})
    for (SurfaceBasisFamily which : kFixedFamilies)
      for (std::size_t size : {4u, 8u, 16u}) {
        const SurfaceBasis basis = family(which, surface, size);
        ASSERT_EQ(basis.size, size);
        double worst = 0.0;
        for (std::size_t i = 0; i < size; ++i)
          for (std::size_t j = 0; j < size; ++j) {
            double dot = 0.0;
            for (std::size_t v = 0; v < basis.vertices; ++v)
              dot += double(surface.weights[v]) * basis.at(i, v) * basis.at(j, v);
            worst = std::max(worst, std::fabs(dot - (i == j ? 1.0 : 0.0)));
          }
        EXPECT_LT(worst, 6e-15) << surface_basis_name(which) << " " << size;
      }
}

// A family of size N reproduces its candidate functions up to N: the radiance equal to one
// of them (from its formula here) comes back to rounding, and a family cut before it does not.
void expect_in_span(const SurfaceBasis& with, const SurfaceBasis& without, const Surface& surface,
                    const std::vector<double>& radiance, const char* what) {
  EXPECT_LT(relative_error(with, surface.weights, radiance), 2e-15) << what;
  EXPECT_GT(relative_error(without, surface.weights, radiance), 0.1) << what;
}

TEST(Bases, ReproduceARadianceThatIsOneOfTheirFunctions) {
  const Surface floor = floor_surface();
  std::vector<double> cosine(floor.uv.size()), haar(floor.uv.size());
  for (std::size_t v = 0; v < floor.uv.size(); ++v) {
    const glm::vec2 uv = floor.uv[v];
    // (a, b) = (2, 1): a + b = 3, after the 6 of a + b <= 2 and (0, 3), (1, 2): the 9th.
    cosine[v] = std::cos(2.0 * kPi * uv.x) * std::cos(kPi * uv.y);
    // Level 1's diagonal detail of the cell u, v in [0.5, 1]: the 16th.
    const bool cell = uv.x >= 0.5f && uv.y >= 0.5f;
    haar[v] = cell ? ((uv.x < 0.75f) == (uv.y < 0.75f) ? 1.0 : -1.0) : 0.0;
  }
  expect_in_span(cosine_surface_basis(floor.uv, floor.weights, 9),
                 cosine_surface_basis(floor.uv, floor.weights, 8), floor, cosine, "cosine (2, 1)");
  expect_in_span(haar_surface_basis(floor.uv, floor.weights, 16),
                 haar_surface_basis(floor.uv, floor.weights, 15), floor, haar, "Haar diagonal");

  // SH of the sphere's own directions: the first 8 hold Y_0..Y_7 and not Y_8 (band 2, m = +2).
  const Surface sphere = sphere_surface();
  const SurfaceBasis sh8 = sh_surface_basis(sphere.positions, glm::vec3(0.0f), sphere.weights, 8);
  const SurfaceBasis sh9 = sh_surface_basis(sphere.positions, glm::vec3(0.0f), sphere.weights, 9);
  for (std::size_t index = 0; index < 9; ++index) {
    std::vector<double> y(sphere.positions.size());
    for (std::size_t v = 0; v < y.size(); ++v) {
      float values[9];
      ASSERT_EQ(prt_sh_eval(3, &sphere.positions[v].x, values), PRT_OK);
      y[v] = values[index];
    }
    EXPECT_LT(relative_error(sh9, sphere.weights, y), 5e-15) << "Y_" << index;
    if (index < 8)
      EXPECT_LT(relative_error(sh8, sphere.weights, y), 5e-15) << "Y_" << index;
    else
      EXPECT_GT(relative_error(sh8, sphere.weights, y), 0.1) << "Y_" << index;
  }
}

// The floor seen from its centre gives SH only the azimuth (one function per band and sign of
// m), so the first 16 independent functions reach past band 3 instead of failing.
TEST(Bases, ShSkipsFunctionsThatCoincideOnAFlatSurface) {
  const Surface floor = floor_surface(16);
  const SurfaceBasis basis = sh_surface_basis(floor.positions, glm::vec3(0.0f), floor.weights, 16);
  EXPECT_EQ(basis.size, 16u);
  // cos(5 phi) and sin(5 phi) of the azimuth about +Y: band 5, out of reach of bands <= 3.
  for (int phase = 0; phase < 2; ++phase) {
    std::vector<double> azimuth(floor.positions.size());
    for (std::size_t v = 0; v < azimuth.size(); ++v)
      azimuth[v] = std::cos(5.0 * std::atan2(floor.positions[v].z, floor.positions[v].x) -
                            0.5 * kPi * phase);
    // prt_sh_eval's float values bound how exactly the span holds it.
    EXPECT_LT(relative_error(basis, floor.weights, azimuth), 7.5e-7) << phase;
  }
}

// Nested spans: the error of a radiance never rises from N to N + 1.
TEST(Bases, ErrorsNeverRiseWithTheNumberOfTerms) {
  const Surface sphere = sphere_surface();
  std::vector<double> radiance(sphere.positions.size());
  for (std::size_t v = 0; v < radiance.size(); ++v) {
    const glm::vec3 to_light = glm::vec3(1.5f, 2.0f, 0.5f) - sphere.positions[v];
    const double cosine = glm::dot(glm::normalize(to_light), sphere.positions[v]);
    radiance[v] = std::max(0.0, cosine) / glm::dot(to_light, to_light);
  }
  for (SurfaceBasisFamily which : kFixedFamilies) {
    const SurfaceBasis full = family(which, sphere, 16);
    double previous = 1.0;
    for (std::size_t n = 1; n <= 16; ++n) {
      SurfaceBasis part = full;
      part.size = n;
      part.functions.resize(n * full.vertices);
      const double error = relative_error(part, sphere.weights, radiance);
      EXPECT_LE(error, previous + 1e-14) << surface_basis_name(which) << " " << n;
      previous = error;
    }
    EXPECT_LT(previous, 0.9) << surface_basis_name(which);
  }
}

// As many functions as vertices: the family spans every radiance, a random one comes back.
TEST(Bases, SpanEverythingWithAsManyFunctionsAsVertices) {
  const Surface floor = floor_surface(4);
  std::vector<double> radiance(floor.positions.size());
  for (std::size_t v = 0; v < radiance.size(); ++v) radiance[v] = std::sin(7.3 * v) + 1.5;
  for (SurfaceBasisFamily which : kFixedFamilies) {
    if (which == SurfaceBasisFamily::SphericalHarmonics) continue;  // the azimuth alone: fewer
    const SurfaceBasis basis = family(which, floor, floor.positions.size());
    EXPECT_LT(relative_error(basis, floor.weights, radiance), 1e-15) << surface_basis_name(which);
  }
}

// A vertex with a non-finite uv, position or weight neither breaks a family nor its fit: the
// functions stay finite and the fit of a finite radiance too.
TEST(Bases, TolerateNonFiniteVertexData) {
  Surface floor = floor_surface(6);
  floor.uv[3] = glm::vec2(NAN, 0.5f);
  floor.uv[4] = glm::vec2(0.5f, INFINITY);
  floor.positions[5] = glm::vec3(NAN);
  floor.weights[6] = NAN;
  floor.weights[7] = -1.0f;
  const std::vector<double> radiance(floor.positions.size(), 2.0);
  for (SurfaceBasisFamily which : kFixedFamilies) {
    const SurfaceBasis basis = family(which, floor, 8);
    for (double value : basis.functions) ASSERT_TRUE(std::isfinite(value));
    const std::vector<double> fit = approximated_radiance(basis, floor.weights, radiance);
    // The constant is every family's first function: a constant radiance comes back.
    for (std::size_t v = 0; v < fit.size(); ++v)
      EXPECT_NEAR(fit[v], 2.0, 3e-15) << surface_basis_name(which) << " " << v;
  }
}

struct BallOnFloor {
  Mesh floor = make_study_floor(glm::vec2(0.0f), 1.5f, 0.0f, 10);
  Mesh ball = test::make_icosphere(1, 0.4f, glm::vec3(0.2f, 0.4f, -0.1f));
  ShadowfieldObject object;
  std::unique_ptr<EmbreeScene> rays;
  BallOnFloor() {
    object.positions = floor.positions;
    object.normals = floor.normals;
    object.indices = floor.indices;
    object.albedo.assign(floor.positions.size(), glm::vec3(0.8f));
    rays = std::make_unique<EmbreeScene>(test::scene_of({floor, ball}), Context{});
  }
};

// Eckart-Young: over the training samples the PCA's summed squared error is the least any
// N-dimensional space gives, so no other family does better on them.
TEST(Bases, PcaHasTheLeastErrorOnItsTrainingSamples) {
  BallOnFloor scene;
  ShadowfieldBasisSettings settings;
  settings.lights = 64;
  bake_surface_basis(scene.object, *scene.rays, settings, Context{});
  const BoundingSphere sphere = bounding_sphere(scene.object.positions);
  const float distance = float(settings.light_distance) * sphere.radius;
  const ShadowfieldRadianceSamples samples = shadowfield_radiance_samples(
      scene.object, *scene.rays,
      shadowfield_light_positions(settings.lights, sphere.centre, distance),
      double(distance) * distance, Context{});
  const std::vector<float>& weights = scene.object.vertex_weights;
  const Surface floor{scene.floor.positions, scene.floor.texcoords0, weights};
  auto summed_error = [&](const SurfaceBasis& basis) {
    double sum = 0.0;
    for (std::size_t row = 0; row < samples.rows; ++row) {
      const std::vector<double> r(samples.values.begin() + row * samples.vertices,
                                  samples.values.begin() + (row + 1) * samples.vertices);
      const double e = weighted_norm(r, approximated_radiance(basis, weights, r), weights);
      sum += e * e;
    }
    return sum;
  };
  for (std::size_t size : {4u, 8u, 16u}) {
    const double pca = summed_error(pca_surface_basis(scene.object, size));
    for (SurfaceBasisFamily which : kFixedFamilies) {
      const SurfaceBasis other =
          which == SurfaceBasisFamily::SphericalHarmonics
              ? sh_surface_basis(floor.positions, sphere.centre, weights, size)
              : family(which, floor, size);
      EXPECT_LT(pca, summed_error(other)) << surface_basis_name(which) << " " << size;
    }
  }
}

// The irradiance at the centre under a square of radiance 1, half-size a at height h, facing
// down: pi x the form factor of four a x a rectangles seen from their corner.
double square_irradiance(double a, double h) {
  const double x = a / h, root = std::sqrt(1.0 + x * x);
  const double corner = (1.0 / kPi) * (x / root) * std::atan(x / root);  // Howell B-3, a = b
  return kPi * 4.0 * corner;
}

Mesh facing(Mesh mesh, float normal_y) {
  for (glm::vec3& n : mesh.normals) n = glm::vec3(0.0f, normal_y, 0.0f);
  return mesh;
}

TEST(SourceIrradiance, MatchesTheFormFactorOfAGlowingSquare) {
  const float a = 1.0f, h = 0.7f;
  for (float normal_y : {-1.0f, 1.0f}) {
    const Mesh square = facing(make_study_floor(glm::vec2(0.0f), a, h, 5), normal_y);
    ShadowfieldObject source;
    source.positions = square.positions;
    source.normals = square.normals;
    source.indices = square.indices;
    const EmbreeScene rays(test::scene_of({square}), Context{});
    const std::vector<glm::vec3> receivers = {glm::vec3(0.0f)}, normals = {glm::vec3(0, 1, 0)};
    const SourceIrradiance g = source_irradiance(source, rays, receivers, normals, 4096, 1, {});
    EXPECT_EQ(g.rays_traced, 4096u);
    const double e = g.apply(std::vector<double>(square.positions.size(), 1.0))[0];
    if (normal_y < 0.0f)
      EXPECT_NEAR(e, square_irradiance(a, h), 3e-3 * square_irradiance(a, h));
    else
      EXPECT_EQ(e, 0.0) << "the square's back glows nothing";
  }
}

// A receiver vertex without a usable normal (zero or NaN) casts no ray and receives nothing; a
// radiance of the wrong length is refused.
TEST(SourceIrradiance, SkipsReceiversWithoutANormal) {
  const Mesh square = facing(make_study_floor(glm::vec2(0.0f), 1.0f, 0.5f, 3), -1.0f);
  ShadowfieldObject source;
  source.positions = square.positions;
  source.normals = square.normals;
  source.indices = square.indices;
  const EmbreeScene rays(test::scene_of({square}), Context{});
  const std::vector<glm::vec3> receivers(3, glm::vec3(0.0f));
  const std::vector<glm::vec3> normals = {glm::vec3(0.0f), glm::vec3(NAN, 1.0f, 0.0f),
                                          glm::vec3(0.0f, 2.0f, 0.0f)};
  const SourceIrradiance g = source_irradiance(source, rays, receivers, normals, 64, 0, {});
  EXPECT_EQ(g.rays_traced, 64u);
  const std::vector<double> e = g.apply(std::vector<double>(square.positions.size(), 1.0));
  EXPECT_EQ(e[0], 0.0);
  EXPECT_EQ(e[1], 0.0);
  EXPECT_GT(e[2], 0.0);
  EXPECT_NE(thrown_message([&] { g.apply({1.0}); }).find("vertex count"), std::string::npos);
  EXPECT_NE(thrown_message([&] {
              source_irradiance(source, rays, receivers, {}, 64, 0, {});
            }).find("one normal per vertex"),
            std::string::npos);
}

TEST(Compare, GivesEveryFamilySizeAndLightingWithinBounds) {
  BasisStudyScene scene{"floor", make_study_floor(glm::vec2(0.0f), 1.5f, 0.0f, 12),
                        test::make_icosphere(1, 0.4f, glm::vec3(0.2f, 0.4f, -0.1f))};
  BasisStudySettings settings;
  settings.pca.lights = 32;
  settings.test_lights = 8;
  settings.sky_turns = 2;
  settings.sky_spp = 16;
  settings.receiver_directions = 16;
  const BasisStudyReport report = compare_surface_bases(scene, make_demo_sky(64), settings, {});
  ASSERT_EQ(report.rows.size(), 4u * 3u * 3u);
  EXPECT_EQ(report.sky_lightings, 2u);
  EXPECT_GT(report.point_lightings, 0u);
  for (const BasisStudyRow& row : report.rows) {
    // A W-orthogonal projection never lengthens: 0 <= error <= 1 for the radiance.
    EXPECT_GE(row.radiance_error, 0.0);
    EXPECT_LE(row.radiance_error, 1.0 + 1e-14) << row.basis << " " << row.terms;
    EXPECT_TRUE(std::isfinite(row.image_error));
    for (const BasisStudyRow& more : report.rows)
      if (more.basis == row.basis && more.lighting == row.lighting && more.terms > row.terms) {
        EXPECT_LE(more.radiance_error, row.radiance_error + 1e-14) << row.basis;
      }
  }
}

TEST(Compare, RefusesBadInput) {
  BasisStudyScene scene{"floor", make_study_floor(glm::vec2(0.0f), 1.0f, 0.0f, 4),
                        test::make_icosphere(0, 0.3f, glm::vec3(0, 0.4f, 0))};
  BasisStudySettings no_terms;
  no_terms.sizes = {4, 0};
  EXPECT_NE(thrown_message([&] {
              compare_surface_bases(scene, make_demo_sky(16), no_terms, {});
            }).find("at least 1 term"),
            std::string::npos);
  scene.surface.texcoords0.clear();
  EXPECT_NE(thrown_message([&] {
              compare_surface_bases(scene, make_demo_sky(16), {}, {});
            }).find("TEXCOORD_0"),
            std::string::npos);

  // A 2 x 2 floor has 4 vertices: no family has more than 4 independent functions on it.
  const Surface tiny = floor_surface(2);
  EXPECT_NE(thrown_message([&] {
              haar_surface_basis(tiny.uv, tiny.weights, 5);
            }).find("only 4 independent"),
            std::string::npos);
  EXPECT_EQ(haar_surface_basis(tiny.uv, tiny.weights, 4).size, 4u);
  const std::vector<float> no_area(tiny.weights.size(), 0.0f);
  EXPECT_NE(thrown_message([&] { cosine_surface_basis(tiny.uv, no_area, 1); }).find("no area"),
            std::string::npos);
  EXPECT_NE(thrown_message([&] { cosine_surface_basis({}, tiny.weights, 1); }).find("uv"),
            std::string::npos);
  EXPECT_NE(thrown_message([&] { make_study_floor(glm::vec2(0.0f), 1.0f, 0.0f, 1); }).find("2 x 2"),
            std::string::npos);
}

// spot's uv layout (shared asset): the uv families reach 16 functions over it, orthonormal.
TEST(Bases, FitSpotsUvLayout) {
  const std::string path = prt_test::shared_asset("meshes/spot.obj");
  if (path.empty()) GTEST_SKIP() << "meshes/spot.obj is not in the shared assets";
  const Scene imported = import_scene(path, Context{});
  ASSERT_EQ(imported.meshes.size(), 1u);
  const Surface spot = surface_of(imported.meshes[0], imported.meshes[0].texcoords0);
  ASSERT_EQ(spot.uv.size(), spot.positions.size());
  for (SurfaceBasisFamily which : kFixedFamilies) {
    const SurfaceBasis basis = family(which, spot, 16);
    double worst = 0.0;
    for (std::size_t i = 0; i < 16; ++i) {
      double dot = 0.0;
      for (std::size_t v = 0; v < basis.vertices; ++v)
        dot += double(spot.weights[v]) * basis.at(i, v) * basis.at(i, v);
      worst = std::max(worst, std::fabs(dot - 1.0));
    }
    EXPECT_LT(worst, 2e-14) << surface_basis_name(which);
  }
}

}  // namespace
}  // namespace prt::bake
