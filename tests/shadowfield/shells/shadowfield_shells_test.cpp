// SPDX-License-Identifier: MIT
// The shell grid: every value below follows from the grid's definition (shells evenly spaced in
// log radius, cube-map cell centres) or from a property of interpolation (weights sum to 1, a grid
// point reads itself, a linear function of log radius is reproduced).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>

#include "prt/format/shadowfield_shells.h"

namespace {

prt_sf_shells paper_grid() {
  prt_sf_shells grid{};
  grid.centre[0] = 1.0f;
  grid.centre[1] = -2.0f;
  grid.centre[2] = 0.5f;
  grid.radius = 2.0f;
  grid.inner = 0.2f;
  grid.outer = 8.0f;
  grid.shells = 16;
  grid.face_size = 16;
  return grid;
}

double distance_from_centre(const prt_sf_shells& grid, const float p[3]) {
  const double dx = p[0] - grid.centre[0], dy = p[1] - grid.centre[1], dz = p[2] - grid.centre[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

TEST(ShadowfieldShells, RadiiAreEvenInLogFromInnerToOuter) {
  const prt_sf_shells grid = paper_grid();
  EXPECT_FLOAT_EQ(prt_sf_shell_radius(&grid, 0), 0.4f);
  EXPECT_FLOAT_EQ(prt_sf_shell_radius(&grid, 15), 16.0f);
  const double ratio = std::pow(40.0, 1.0 / 15.0);
  for (std::uint32_t s = 1; s < grid.shells; ++s)
    EXPECT_NEAR(prt_sf_shell_radius(&grid, s) / prt_sf_shell_radius(&grid, s - 1), ratio, 1e-6);
  prt_sf_shells single = grid;
  single.shells = 1;
  EXPECT_FLOAT_EQ(prt_sf_shell_radius(&single, 0), 0.4f);
}

TEST(ShadowfieldShells, PointsLieOnTheirShellsAndAreDistinct) {
  const prt_sf_shells grid = paper_grid();
  ASSERT_EQ(prt_sf_points_per_shell(&grid), 6u * 16u * 16u);
  ASSERT_EQ(prt_sf_point_count(&grid), 16u * 6u * 16u * 16u);
  std::set<std::tuple<float, float, float>> seen;
  for (std::uint64_t i = 0; i < prt_sf_point_count(&grid); ++i) {
    float p[3];
    prt_sf_point_position(&grid, i, p);
    const std::uint32_t shell = static_cast<std::uint32_t>(i / prt_sf_points_per_shell(&grid));
    EXPECT_NEAR(distance_from_centre(grid, p), prt_sf_shell_radius(&grid, shell),
                4e-7 * prt_sf_shell_radius(&grid, shell) + 4e-7);
    seen.insert({p[0], p[1], p[2]});
  }
  EXPECT_EQ(seen.size(), prt_sf_point_count(&grid));
}

TEST(ShadowfieldShells, CubeFaceInvertsCubeDirection) {
  for (std::uint32_t face = 0; face < 6; ++face)
    for (float s : {0.03f, 0.5f, 0.97f})
      for (float t : {0.1f, 0.45f, 0.9f}) {
        float d[3], s2, t2;
        prt_sf_cube_direction(face, s, t, d);
        EXPECT_EQ(prt_sf_cube_face(d, &s2, &t2), face);
        EXPECT_NEAR(s2, s, 1e-6f);
        EXPECT_NEAR(t2, t, 1e-6f);
      }
}

TEST(ShadowfieldShells, EachFaceIsTheSideOfItsAxis) {
  const float axes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (std::uint32_t face = 0; face < 6; ++face) {
    float d[3];
    prt_sf_cube_direction(face, 0.5f, 0.5f, d);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(d[c], axes[face][c]) << face;
  }
}

TEST(ShadowfieldShells, AGridPointReadsItselfAlone) {
  const prt_sf_shells grid = paper_grid();
  for (std::uint64_t i = 0; i < prt_sf_point_count(&grid); i += 97) {
    float p[3];
    prt_sf_point_position(&grid, i, p);
    prt_sf_lookup lookup;
    prt_sf_locate(&grid, p, &lookup);
    ASSERT_GT(lookup.count, 0u);
    float own = 0.0f, sum = 0.0f;
    for (std::uint32_t k = 0; k < lookup.count; ++k) {
      sum += lookup.weight[k];
      if (lookup.index[k] == i) own += lookup.weight[k];
    }
    EXPECT_NEAR(sum, 1.0f, 1e-6f);
    EXPECT_NEAR(own, 1.0f, 2e-5f) << i;
  }
}

TEST(ShadowfieldShells, LogRadiusIsInterpolatedLinearly) {
  // f(point) = log(radius of its shell) is linear in log radius, so between shells the lookup
  // returns log |p - c| exactly (up to float rounding).
  const prt_sf_shells grid = paper_grid();
  for (double rho : {0.41, 0.9, 1.7, 3.3, 7.5, 15.9}) {
    const float p[3] = {grid.centre[0] + static_cast<float>(rho * 0.48),
                        grid.centre[1] + static_cast<float>(rho * 0.6),
                        grid.centre[2] + static_cast<float>(rho * 0.64)};
    prt_sf_lookup lookup;
    prt_sf_locate(&grid, p, &lookup);
    ASSERT_EQ(lookup.count, 8u);
    EXPECT_EQ(lookup.inside, 0u);
    double value = 0.0;
    for (std::uint32_t k = 0; k < lookup.count; ++k) {
      const std::uint32_t shell =
          static_cast<std::uint32_t>(lookup.index[k] / prt_sf_points_per_shell(&grid));
      value += lookup.weight[k] * std::log(prt_sf_shell_radius(&grid, shell));
    }
    EXPECT_NEAR(value, std::log(distance_from_centre(grid, p)), 2e-6) << rho;
  }
}

TEST(ShadowfieldShells, InsideReadsTheInnerShellAndBeyondReadsNothing) {
  const prt_sf_shells grid = paper_grid();
  for (float offset : {0.0f, 0.1f, 0.399f}) {
    const float p[3] = {grid.centre[0], grid.centre[1] + offset, grid.centre[2]};
    prt_sf_lookup lookup;
    prt_sf_locate(&grid, p, &lookup);
    EXPECT_EQ(lookup.inside, 1u);
    ASSERT_EQ(lookup.count, 4u);
    for (std::uint32_t k = 0; k < lookup.count; ++k)
      EXPECT_LT(lookup.index[k], prt_sf_points_per_shell(&grid));
  }
  const float far_away[3] = {grid.centre[0] + 16.01f, grid.centre[1], grid.centre[2]};
  const float not_finite[3] = {NAN, 0.0f, 0.0f};
  for (const float* p : {far_away, not_finite}) {
    prt_sf_lookup lookup;
    prt_sf_locate(&grid, p, &lookup);
    EXPECT_EQ(lookup.count, 0u);
  }
}

TEST(ShadowfieldShells, OneCellPerFaceAndOneShellStillRead) {
  prt_sf_shells grid = paper_grid();
  grid.shells = 1;
  grid.face_size = 1;
  grid.outer = grid.inner;
  const float p[3] = {grid.centre[0] + 0.3f, grid.centre[1] - 0.1f, grid.centre[2]};
  prt_sf_lookup lookup;
  prt_sf_locate(&grid, p, &lookup);
  ASSERT_EQ(lookup.count, 4u);
  float sum = 0.0f;
  for (std::uint32_t k = 0; k < lookup.count; ++k) {
    EXPECT_EQ(lookup.index[k], 0u);  // face +X, its only cell
    sum += lookup.weight[k];
  }
  EXPECT_NEAR(sum, 1.0f, 1e-6f);
}

}  // namespace
