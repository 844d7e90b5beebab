// SPDX-License-Identifier: MIT
// The generated meshes the shadowfield scenes stand on (prt/baker/mesh_generators.hpp): vertex
// counts from the grid sizes, triangles wound to agree with the normals, and enclosed volumes
// against the exact volume of the inscribed polyhedron or the analytic solid.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/constants.hpp>

#include "prt/baker/mesh_generators.hpp"

namespace prt::bake {
namespace {

constexpr double kPi = glm::pi<double>();

// Divergence theorem: sum of a . (b x c) / 6 over the triangles; positive when they wind
// counter-clockwise seen from outside.
double signed_volume(const Mesh& mesh) {
  double volume = 0.0;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
        c(mesh.positions[mesh.indices[t + 2]]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return volume;
}

// Triangles whose winding disagrees with a corner's normal. The slivers a sphere keeps at its
// bottom pole, where sin(pi) rounds to a few 1e-8 rather than 0, have no meaningful winding and
// are left out (as tests/baker/cli/test_demo_scene.cpp does).
std::size_t misoriented_triangles(const Mesh& mesh) {
  std::size_t bad = 0;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                    c = mesh.positions[mesh.indices[t + 2]];
    const glm::vec3 face = glm::cross(b - a, c - a);
    if (glm::length(face) < 1e-6f) continue;
    for (int k = 0; k < 3; ++k) {
      if (glm::dot(face, mesh.normals[mesh.indices[t + k]]) <= 0.0f) {
        ++bad;
        break;
      }
    }
  }
  return bad;
}

TEST(Meshes, PlaneHasTheGridsVerticesAndFacesUp) {
  const Mesh plane = make_plane_mesh("floor", 0, 2.0f, 1.0f, 63, 31);
  EXPECT_EQ(plane.vertex_count(), 64u * 32u);
  EXPECT_EQ(plane.triangle_count(), 2u * 63u * 31u);
  EXPECT_EQ(misoriented_triangles(plane), 0u);
}

TEST(Meshes, BoxEnclosesItsCube) {
  const Mesh box = make_box_mesh(0, glm::vec3(0.3f, 0.5f, -0.2f), 0.5f, 0.7f, 4);
  EXPECT_EQ(box.vertex_count(), 6u * 5u * 5u);
  EXPECT_EQ(misoriented_triangles(box), 0u);
  EXPECT_NEAR(signed_volume(box), 1.0, 1.5e-8);
}

TEST(Meshes, CylinderEnclosesItsInscribedPrism) {
  const int cols = 24;
  const double r = 0.5, h = 1.2;
  const Mesh cylinder =
      make_cylinder_mesh(0, glm::vec3(1.0f, 0.0f, 2.0f), float(r), float(h), 3, cols, 2);
  EXPECT_EQ(cylinder.vertex_count(), std::size_t(4 * (cols + 1) + 2 * 3 * (cols + 1)));
  EXPECT_EQ(misoriented_triangles(cylinder), 0u);
  // A prism on the regular 24-gon inscribed in the circle.
  const double polygon = 0.5 * cols * r * r * std::sin(2.0 * kPi / cols);
  EXPECT_NEAR(signed_volume(cylinder), polygon * h, 5e-8);
}

// The inscribed polyhedra fall short of the solids' volumes by the square of the grid step:
// halving the step quarters the shortfall.
TEST(Meshes, SphereAndTorusWindOutwardAndConvergeToTheirVolume) {
  EXPECT_EQ(misoriented_triangles(make_sphere_mesh(0, glm::vec3(0.0f), 1.0f, 48, 96)), 0u);
  EXPECT_EQ(misoriented_triangles(make_torus_mesh(0, glm::vec3(0.0f), 0.7f, 0.3f, 48, 96)), 0u);
  const double ball = 4.0 / 3.0 * kPi, ring = 2.0 * kPi * kPi * 0.7 * 0.3 * 0.3;
  auto sphere_shortfall = [&](int n) {
    return 1.0 - signed_volume(make_sphere_mesh(0, glm::vec3(0.0f), 1.0f, n, 2 * n)) / ball;
  };
  auto torus_shortfall = [&](int n) {
    return 1.0 - signed_volume(make_torus_mesh(0, glm::vec3(0.0f), 0.7f, 0.3f, n, 2 * n)) / ring;
  };
  for (int n : {24, 48}) {
    EXPECT_GT(sphere_shortfall(2 * n), 0.0);
    EXPECT_NEAR(sphere_shortfall(n) / sphere_shortfall(2 * n), 4.0, 0.03) << n;
    EXPECT_GT(torus_shortfall(2 * n), 0.0);
    EXPECT_NEAR(torus_shortfall(n) / torus_shortfall(2 * n), 4.0, 0.03) << n;
  }
}

}  // namespace
}  // namespace prt::bake
