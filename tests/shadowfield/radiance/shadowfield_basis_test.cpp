// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s surface-radiance basis: the area weights against the plane's area,
// the samples against a point light's radiance written here (and zero behind a wall or below
// the horizon), the PCA's properties (B W B^T = I, A^-1 A = I, a radiance in the span
// reproduced, the reconstruction error of the samples equal to the singular values' tail by
// Eckart-Young), determinism across thread counts, the extremes (one light, N = V, non-finite
// and unused vertices) and the errors of bad input.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "prt/baker/shadowfield/shadowfield_radiance.hpp"
#include "shadowfield/radiance/radiance_test_objects.hpp"

namespace prt::bake {
namespace {

using test::merged;
using test::object_of;
using test::rays_of;

constexpr double kPi = 3.14159265358979323846;
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

std::string thrown_message(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& error) {
    return error.what();
  }
  return "(nothing thrown)";
}

// A ball over a floor: the ball shadows the floor and the floor hides the ball's underside.
Mesh ball_on_floor() {
  return merged({test::make_plane(1.5f, 8), test::make_icosphere(1, 0.5f, glm::vec3(0, 0.6f, 0))});
}

struct Baked {
  ShadowfieldObject object;
  ShadowfieldBasisReport report;
};

Baked bake_ball_on_floor(const ShadowfieldBasisSettings& settings, ShadowfieldMaterial material,
                         unsigned threads = 0) {
  const Mesh mesh = ball_on_floor();
  Baked baked{object_of(mesh, glm::vec3(0.9f, 0.5f, 0.3f)), {}};
  baked.object.material = std::move(material);
  test::set_sphere(baked.object, glm::vec3(0.0f, 0.3f, 0.0f), 2.2f);
  Context ctx;
  ctx.threads = threads;
  baked.report = bake_surface_basis(baked.object, *rays_of(mesh), settings, ctx);
  return baked;
}

RowMajor basis_of(const ShadowfieldObject& object) {
  return Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
             object.basis.data(), object.basis_size, Eigen::Index(object.positions.size()))
      .cast<double>();
}

Eigen::VectorXd weights_of(const ShadowfieldObject& object) {
  return Eigen::Map<const Eigen::VectorXf>(object.vertex_weights.data(),
                                           Eigen::Index(object.vertex_weights.size()))
      .cast<double>();
}

RowMajor inverse_of(const ShadowfieldObject& object) {
  return Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
             object.basis_inverse.data(), object.basis_size, object.basis_size)
      .cast<double>();
}

double max_distance_to_identity(const Eigen::MatrixXd& m) {
  return (m - Eigen::MatrixXd::Identity(m.rows(), m.cols())).cwiseAbs().maxCoeff();
}

const ShadowfieldBasisSettings kSmall{8, 64, 2.0};

// ---- Weights and samples -----------------------------------------------------------------------

TEST(Weights, AThirdOfEachTriangleSumsToTheArea) {
  const ShadowfieldObject plane = object_of(test::make_plane(1.5f, 8));
  const std::vector<float> weights = shadowfield_vertex_weights(plane);
  double total = 0.0;
  for (float w : weights) total += w;
  EXPECT_NEAR(total, 9.0, 1e-5);
  // A corner touches one triangle of the two in its cell: a third of half a cell.
  const double cell = (3.0 / 8) * (3.0 / 8);
  EXPECT_NEAR(weights[0], cell / 6.0, 1e-7);
}

TEST(Samples, AnUnblockedLightGivesThePointLightsRadiance) {
  const Mesh plane = test::make_plane(0.5f, 2);
  const glm::vec3 albedo(0.8f, 0.6f, 0.4f);
  const ShadowfieldObject object = object_of(plane, albedo);
  const glm::vec3 light(0.2f, 2.0f, -0.1f);
  const double intensity = 3.0;
  const ShadowfieldRadianceSamples samples =
      shadowfield_radiance_samples(object, *rays_of(plane), {light}, intensity, Context{});
  ASSERT_EQ(samples.rows, 1u);
  const double luminance = 0.2126 * 0.8 + 0.7152 * 0.6 + 0.0722 * 0.4;
  for (std::size_t v = 0; v < plane.positions.size(); ++v) {
    const glm::dvec3 d = glm::dvec3(light) - glm::dvec3(plane.positions[v]);
    const double distance = glm::length(d), cosine = d.y / distance;
    const double expected = luminance * intensity * cosine / (kPi * distance * distance);
    EXPECT_NEAR(samples.at(0, v), expected, 1e-6 * expected) << "vertex " << v;
  }
}

TEST(Samples, ALightBehindAWallOrBelowTheHorizonGivesZero) {
  const Mesh plane = test::make_plane(0.5f, 2);
  const ShadowfieldObject object = object_of(plane);
  // The wall blocks; it is not part of the object.
  const auto rays = rays_of(plane, {test::make_plane(2.0f, 1, 1.0f)});
  const std::vector<glm::vec3> lights = {{0.0f, 2.0f, 0.0f}, {0.3f, -2.0f, 0.0f}};
  const ShadowfieldRadianceSamples samples =
      shadowfield_radiance_samples(object, *rays, lights, 1.0, Context{});
  for (double value : samples.values) EXPECT_EQ(value, 0.0);
}

TEST(Samples, GlossyTermsAreTheIncidentFactorsAtTheLight) {
  // With every term of the separable BRDF, sum_k g_k(wo) h_k(w) is the Phong BRDF up to the
  // table's interpolation, so the rows weighted by g_k(normal) give the radiance reflected
  // along the normal. A broad lobe (n = 1), which the 16 x 16 table resolves.
  const Mesh plane = test::make_plane(0.5f, 1);
  ShadowfieldObject object = object_of(plane, glm::vec3(1.0f));
  constexpr std::uint32_t kTerms = 256;  // the 16 x 16 grid's full rank
  object.material = test::phong_material(1.0, kTerms);
  const glm::vec3 light(0.0f, 3.0f, 0.0f);
  const ShadowfieldRadianceSamples samples =
      shadowfield_radiance_samples(object, *rays_of(plane), {light}, 1.0, Context{});
  ASSERT_EQ(samples.rows, kTerms);
  const glm::dvec3 up(0.0, 0.0, 1.0);
  for (std::size_t v = 0; v < plane.positions.size(); ++v) {
    const glm::dvec3 d = glm::dvec3(light) - glm::dvec3(plane.positions[v]);
    const double distance = glm::length(d), cosine = d.y / distance;
    double reflected = 0.0;  // towards the normal, with the samples' h_k
    for (std::uint32_t k = 0; k < kTerms; ++k)
      reflected += object.material.brdf.outgoing_at(k, up) * samples.at(k, v);
    const double phong = 3.0 / (2.0 * kPi) * cosine;
    const double expected = phong * cosine / (distance * distance);
    // The table's bilinear interpolation: measured 1.1e-2.
    EXPECT_NEAR(reflected, expected, 2.5e-2 * expected) << "vertex " << v;
  }
}

// ---- The basis ---------------------------------------------------------------------------------

TEST(Basis, IsOrthonormalInTheAreaWeightsAndItsInverseIsAs) {
  for (bool glossy : {false, true}) {
    const Baked baked =
        bake_ball_on_floor(kSmall, glossy ? test::phong_material(10.0, 4) : ShadowfieldMaterial{});
    const ShadowfieldObject& object = baked.object;
    ASSERT_EQ(object.basis_size, 8u);
    ASSERT_EQ(object.basis.size(), 8 * object.positions.size());
    const RowMajor b = basis_of(object);
    const Eigen::MatrixXd a = b * weights_of(object).asDiagonal() * b.transpose();
    // Float storage of the basis and its inverse only: measured 2.2e-8.
    EXPECT_LT(max_distance_to_identity(a), 6e-8) << (glossy ? "glossy" : "diffuse");
    EXPECT_LT(max_distance_to_identity(inverse_of(object) * a), 6e-8);
    EXPECT_EQ(baked.report.samples, glossy ? 256u : 64u);
  }
}

TEST(Basis, ARadianceInItsSpanIsReproduced) {
  const Baked baked = bake_ball_on_floor(kSmall, ShadowfieldMaterial{});
  const RowMajor b = basis_of(baked.object);
  const Eigen::VectorXd w = weights_of(baked.object);
  std::mt19937 random(3);
  std::normal_distribution<double> normal;
  Eigen::VectorXd c(8);
  for (int i = 0; i < 8; ++i) c[i] = normal(random);
  const Eigen::VectorXd r = b.transpose() * c;
  const Eigen::VectorXd fitted = inverse_of(baked.object) * (b * w.asDiagonal() * r);
  // Measured 1.2e-8.
  EXPECT_LT((fitted - c).cwiseAbs().maxCoeff(), 4e-8);
}

// Eckart-Young: the W-weighted least-squares residual of every sample against the span of the
// N functions is the sum of the other singular values squared. The residual is computed here by
// projecting each sample, which the bake never does.
TEST(Basis, ReconstructionErrorOfTheSamplesIsTheSingularValuesTail) {
  for (bool glossy : {false, true}) {
    ShadowfieldBasisSettings settings = kSmall;
    const Baked baked = bake_ball_on_floor(
        settings, glossy ? test::phong_material(10.0, 4) : ShadowfieldMaterial{});
    const ShadowfieldObject& object = baked.object;
    const float distance = 2.0f * object.oof_shells.radius;
    const std::vector<glm::vec3> lights =
        shadowfield_light_positions(settings.lights, glm::vec3(0.0f, 0.3f, 0.0f), distance);
    const Mesh mesh = ball_on_floor();
    const ShadowfieldRadianceSamples samples = shadowfield_radiance_samples(
        object, *rays_of(mesh), lights, double(distance) * distance, Context{});
    const RowMajor r = Eigen::Map<const RowMajor>(samples.values.data(), Eigen::Index(samples.rows),
                                                  Eigen::Index(samples.vertices));
    const RowMajor b = basis_of(object);
    const Eigen::VectorXd w = weights_of(object);
    const RowMajor coefficients =
        r * w.asDiagonal() * b.transpose() * inverse_of(object).transpose();
    const RowMajor residual = r - coefficients * b;
    const double error2 = (residual.array().square().rowwise() * w.transpose().array()).sum();
    const double total2 = (r.array().square().rowwise() * w.transpose().array()).sum();

    const std::vector<double>& sigma = baked.report.singular_values;
    double tail2 = 0.0, all2 = 0.0;
    for (std::size_t i = 0; i < sigma.size(); ++i) {
      all2 += sigma[i] * sigma[i];
      if (i >= settings.size) tail2 += sigma[i] * sigma[i];
    }
    // Double rounding over the samples: measured 4e-15 relative.
    EXPECT_NEAR(all2, total2, 1e-14 * total2);
    EXPECT_GT(tail2, 1e-4 * total2) << "the test needs a truncation that loses something";
    // Relative to the samples' energy. The float basis moves the span by about 1e-8, which
    // changes the residual only to second order: measured 1e-15.
    EXPECT_NEAR(error2 / total2, tail2 / total2, 3e-15) << (glossy ? "glossy" : "diffuse");
    EXPECT_NEAR(baked.report.energy_kept, 1.0 - tail2 / all2, 1e-15);
  }
}

TEST(Basis, KeptEnergyGrowsWithTheSizeToAll) {
  const Baked baked = bake_ball_on_floor(kSmall, ShadowfieldMaterial{});
  double previous = 0.0;
  for (std::size_t n = 1; n <= baked.report.singular_values.size(); ++n) {
    EXPECT_GE(baked.report.energy_kept_by(n), previous);
    previous = baked.report.energy_kept_by(n);
  }
  EXPECT_NEAR(previous, 1.0, 1e-12);
}

TEST(Basis, IsTheSameForAnyThreadCount) {
  const ShadowfieldMaterial glossy = test::phong_material(10.0, 4);
  const Baked one = bake_ball_on_floor(kSmall, glossy, 1);
  const Baked two = bake_ball_on_floor(kSmall, glossy, 2);
  const Baked three = bake_ball_on_floor(kSmall, glossy, 3);
  EXPECT_EQ(one.object.basis, two.object.basis);
  EXPECT_EQ(one.object.basis, three.object.basis);
  EXPECT_EQ(one.object.basis_inverse, three.object.basis_inverse);
  EXPECT_EQ(one.object.vertex_weights, three.object.vertex_weights);
}

// ---- Extremes ---------------------------------------------------------------------------------

// With one light and a diffuse surface there is one sample r: the one function is r / |r|_W.
TEST(Extremes, OneLightGivesTheSampleNormalised) {
  const Mesh mesh = ball_on_floor();
  ShadowfieldObject object = object_of(mesh);
  test::set_sphere(object, glm::vec3(0.0f, 0.3f, 0.0f), 2.2f);
  const auto rays = rays_of(mesh);
  const ShadowfieldBasisReport report = bake_surface_basis(object, *rays, {1, 1, 3.0}, Context{});
  const float distance = 3.0f * 2.2f;
  const ShadowfieldRadianceSamples sample = shadowfield_radiance_samples(
      object, *rays, shadowfield_light_positions(1, glm::vec3(0.0f, 0.3f, 0.0f), distance),
      double(distance) * distance, Context{});
  double norm2 = 0.0;
  for (std::size_t v = 0; v < sample.vertices; ++v)
    norm2 += object.vertex_weights[v] * sample.at(0, v) * sample.at(0, v);
  ASSERT_GT(norm2, 0.0);
  ASSERT_EQ(report.singular_values.size(), 1u);
  EXPECT_NEAR(report.singular_values[0], std::sqrt(norm2), 1e-12 * std::sqrt(norm2));
  double error = 0.0, largest = 0.0;
  for (std::size_t v = 0; v < sample.vertices; ++v) {
    const double expected = sample.at(0, v) / std::sqrt(norm2);
    error = std::max(error, std::fabs(object.basis[v] - expected));
    largest = std::max(largest, std::fabs(expected));
  }
  // Float storage: measured 2.6e-8.
  EXPECT_LT(error / largest, 6e-8);
}

// N = V: the basis spans every radiance, so every sample is kept whole.
TEST(Extremes, AsManyFunctionsAsVerticesKeepEverything) {
  const Mesh plane = test::make_plane(1.0f, 2);  // 9 vertices
  ShadowfieldObject object = object_of(plane);
  const ShadowfieldBasisReport report =
      bake_surface_basis(object, *rays_of(plane), {9, 64, 2.0}, Context{});
  EXPECT_NEAR(report.energy_kept, 1.0, 1e-15);
  const RowMajor b = basis_of(object);
  const Eigen::MatrixXd a = b * weights_of(object).asDiagonal() * b.transpose();
  // Float storage: measured 2.8e-8.
  EXPECT_LT(max_distance_to_identity(inverse_of(object) * a), 7e-8);
}

// A vertex with a non-finite position and one no triangle uses weigh nothing and get 0; the
// rest stays finite, fields included.
TEST(Extremes, NonFiniteAndUnusedVerticesGetNothing) {
  Mesh mesh = ball_on_floor();
  const std::size_t broken = 5, unused = mesh.positions.size();
  mesh.positions[broken] = glm::vec3(NAN, 0.0f, 0.0f);
  mesh.positions.emplace_back(0.0f, 5.0f, 0.0f);
  mesh.normals.emplace_back(0.0f, 1.0f, 0.0f);
  ShadowfieldObject object = object_of(mesh);
  const auto rays = rays_of(mesh);
  bake_surface_basis(object, *rays, kSmall, Context{});
  EXPECT_EQ(object.vertex_weights[broken], 0.0f);
  EXPECT_EQ(object.vertex_weights[unused], 0.0f);
  for (std::uint32_t i = 0; i < object.basis_size; ++i) {
    EXPECT_EQ(object.basis[i * mesh.positions.size() + broken], 0.0f);
    EXPECT_EQ(object.basis[i * mesh.positions.size() + unused], 0.0f);
  }
  for (float value : object.basis) ASSERT_TRUE(std::isfinite(value));
  for (float value : object.basis_inverse) ASSERT_TRUE(std::isfinite(value));
  bake_source_radiance_fields(object, *rays, {2, 2, 0.5f, 4.0f, 256, 0}, Context{});
  for (float value : object.srf) ASSERT_TRUE(std::isfinite(value));
}

// ---- Errors ------------------------------------------------------------------------------------

TEST(Errors, BadBasisSettingsAreNamed) {
  const Mesh mesh = ball_on_floor();
  const auto rays = rays_of(mesh);
  auto bake = [&](ShadowfieldBasisSettings settings) {
    return thrown_message([&] {
      ShadowfieldObject object = object_of(mesh);
      bake_surface_basis(object, *rays, settings, Context{});
    });
  };
  EXPECT_NE(bake({0, 64, 2.0}).find("size (N) must be at least 1"), std::string::npos);
  EXPECT_NE(bake({8, 0, 2.0}).find("lights must be at least 1"), std::string::npos);
  EXPECT_NE(bake({8, 64, 1.0}).find("light_distance"), std::string::npos);
  EXPECT_NE(bake({8, 64, NAN}).find("light_distance"), std::string::npos);
  EXPECT_NE(bake({8, 64, INFINITY}).find("light_distance"), std::string::npos);
  EXPECT_NE(bake({8, 4, 2.0}).find("exceeds"), std::string::npos);  // 4 samples < N
  EXPECT_NE(bake({100000, 1u << 17, 2.0}).find("exceeds the vertex count"), std::string::npos);
}

TEST(Errors, BadObjectsAreNamed) {
  const Mesh mesh = ball_on_floor();
  const auto rays = rays_of(mesh);
  auto bake = [&](const std::function<void(ShadowfieldObject&)>& spoil) {
    return thrown_message([&] {
      ShadowfieldObject object = object_of(mesh);
      spoil(object);
      bake_surface_basis(object, *rays, kSmall, Context{});
    });
  };
  EXPECT_NE(bake([](ShadowfieldObject& o) { o = ShadowfieldObject{}; }).find("no triangles"),
            std::string::npos);
  EXPECT_NE(bake([](ShadowfieldObject& o) { o.indices[4] = 100000; }).find("out of range"),
            std::string::npos);
  EXPECT_NE(bake([](ShadowfieldObject& o) { o.albedo.pop_back(); }).find("one albedo"),
            std::string::npos);
  EXPECT_NE(bake([](ShadowfieldObject& o) { o.indices.pop_back(); }).find("multiple of 3"),
            std::string::npos);
  EXPECT_NE(bake([](ShadowfieldObject& o) {
              o.material.glossy = true;  // without a BRDF
            }).find("incomplete"),
            std::string::npos);
  EXPECT_NE(bake([](ShadowfieldObject& o) {
              for (glm::vec3& p : o.positions) p = glm::vec3(1.0f);
            }).find("no surface area"),
            std::string::npos);
  EXPECT_NE(bake([](ShadowfieldObject& o) { o.albedo[2].g = NAN; }).find("albedo is not finite"),
            std::string::npos);
  EXPECT_NE(bake([](ShadowfieldObject& o) {
              o.oof_shells.radius = 1.0f;
              o.oof_shells.centre[1] = INFINITY;
            }).find("sphere is not finite"),
            std::string::npos);
}

TEST(Errors, CancellingStopsTheBake) {
  const Mesh mesh = ball_on_floor();
  ShadowfieldObject object = object_of(mesh);
  Context ctx;
  ctx.progress = [](double, const std::string&) { return false; };
  EXPECT_EQ(thrown_message([&] { bake_surface_basis(object, *rays_of(mesh), kSmall, ctx); }),
            "cancelled");
  EXPECT_EQ(object.basis_size, 0u);
}

}  // namespace
}  // namespace prt::bake
