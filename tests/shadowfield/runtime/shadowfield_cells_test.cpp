// SPDX-License-Identifier: MIT
// The frame's compact lookups (prt_sf_cell, runtime/src/shadowfield/shadowfield_cells.c) against
// the shell grid's own prt_sf_locate: the lookup a cell rebuilds must be bitwise the one
// prt_sf_locate gives, for points everywhere a receiver may be (between shells, on grid points,
// inside the innermost shell, at the centre, just beyond the outermost, far away) and for the
// grids' edge cases (one shell, one cell a face).
#include <gtest/gtest.h>

#include <prt/format/shadowfield_shells.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

extern "C" {
#include "shadowfield_scene.h"
}

namespace {

prt_sf_shells make_grid(std::uint32_t shells, std::uint32_t face_size, float inner, float outer) {
  prt_sf_shells grid{};
  grid.centre[0] = 0.3f;
  grid.centre[1] = -1.2f;
  grid.centre[2] = 2.5f;
  grid.radius = 1.7f;
  grid.inner = inner;
  grid.outer = outer;
  grid.shells = shells;
  grid.face_size = face_size;
  return grid;
}

// Whether the cell rebuilds prt_sf_locate's lookup of p bitwise; reports the first miss.
bool same_as_locate(const prt_sf_shells& grid, const std::array<float, 3>& p,
                    const prt_sf_cell& cell, int* differing) {
  prt_sf_lookup reference{}, rebuilt{};
  prt_sf_locate(&grid, p.data(), &reference);
  prt_sf_cell_lookup(&grid, &cell, &rebuilt);
  bool same = reference.count == rebuilt.count;
  for (std::uint32_t e = 0; same && e < reference.count; ++e)
    same = reference.index[e] == rebuilt.index[e] &&
           std::memcmp(&reference.weight[e], &rebuilt.weight[e], sizeof(float)) == 0;
  if (!same && (*differing)++ == 0)
    ADD_FAILURE() << "point (" << p[0] << ", " << p[1] << ", " << p[2] << "): count "
                  << reference.count << " vs " << rebuilt.count;
  return same;
}

// Counts the points whose lookups differ.
int compare(const prt_sf_shells& grid, const std::vector<std::array<float, 3>>& points) {
  const double span = prt_sf_log_span(&grid);
  int differing = 0;
  for (const auto& p : points) {
    prt_sf_cell cell{};
    prt_sf_cell_locate(&grid, span, p.data(), &cell);
    same_as_locate(grid, p, cell, &differing);
  }
  return differing;
}

std::vector<std::array<float, 3>> points_around(const prt_sf_shells& grid, std::uint32_t seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_real_distribution<float> log_scale(-3.0f, 3.5f);
  std::vector<std::array<float, 3>> points;
  const float reach = grid.radius * grid.outer;
  for (int e = 0; e < 4000; ++e) {
    float d[3] = {unit(generator), unit(generator), unit(generator)};
    const float length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(length > 0.0f)) continue;
    // Distances from far inside the innermost shell to twice the outermost.
    const float r = grid.radius * std::exp(log_scale(generator)) * (e % 7 == 0 ? 0.01f : 1.0f);
    points.push_back({grid.centre[0] + r * d[0] / length, grid.centre[1] + r * d[1] / length,
                      grid.centre[2] + r * d[2] / length});
  }
  // Every grid point (each reads itself), the centre, and either side of the outermost shell.
  for (std::uint64_t index = 0; index < prt_sf_point_count(&grid); ++index) {
    std::array<float, 3> p{};
    prt_sf_point_position(&grid, index, p.data());
    points.push_back(p);
  }
  points.push_back({grid.centre[0], grid.centre[1], grid.centre[2]});
  for (const float scale : {0.999999f, 1.0f, 1.000001f, 1.00001f})
    points.push_back({grid.centre[0], grid.centre[1] + reach * scale, grid.centre[2]});
  return points;
}

TEST(ShadowfieldCells, RebuildTheShellGridsLookupBitwise) {
  const prt_sf_shells grids[] = {
      make_grid(16, 16, 0.2f, 8.0f),  // the OOF's defaults
      make_grid(8, 8, 0.2f, 8.0f),    // the SRF's
      make_grid(5, 3, 0.35f, 4.0f),   // odd sizes
      make_grid(1, 4, 0.5f, 0.5f),    // one shell
      make_grid(3, 1, 0.1f, 12.0f),   // one cell a face
  };
  std::uint32_t seed = 1;
  for (const prt_sf_shells& grid : grids) EXPECT_EQ(compare(grid, points_around(grid, seed++)), 0);
}

// An object's two grids on one sphere (the OOF's and SRF's defaults, and an SRF that reaches
// less far): located together, each cell is still its own grid's lookup.
TEST(ShadowfieldCells, TwoGridsOnOneSphereLocateAsEachAlone) {
  const prt_sf_shells oof = make_grid(16, 16, 0.2f, 8.0f);
  for (const prt_sf_shells& srf : {make_grid(8, 8, 0.2f, 8.0f), make_grid(6, 5, 0.2f, 3.0f)}) {
    ASSERT_TRUE(prt_sf_shells_share_sphere(&oof, &srf));
    const double oof_span = prt_sf_log_span(&oof), srf_span = prt_sf_log_span(&srf);
    int differing = 0;
    for (const auto& p : points_around(oof, 7)) {
      prt_sf_cell a{}, b{};
      prt_sf_cell_locate_two(&oof, oof_span, &srf, srf_span, p.data(), &a, &b);
      same_as_locate(oof, p, a, &differing);
      same_as_locate(srf, p, b, &differing);
    }
    EXPECT_EQ(differing, 0);
  }
  prt_sf_shells moved = oof;
  moved.centre[1] += 0.25f;
  EXPECT_FALSE(prt_sf_shells_share_sphere(&oof, &moved));
}

}  // namespace
