// SPDX-License-Identifier: MIT
// Midpoint subdivision of a skinned character (prt/baker/pose/pose_subdivide.hpp): counts
// against the mesh's distinct edges counted here, one vertex per shared edge, weights that sum
// to 1 over at most four joints, the new vertices skinned at rest against the midpoints of their
// skinned ends, and CesiumMan reaching the paper's vertex count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "prt/baker/animation.hpp"
#include "prt/baker/pose/pose_subdivide.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

using prt_test::shared_asset;

#define IMPORT_OR_SKIP(var, relative)                                            \
  if (shared_asset(relative).empty()) GTEST_SKIP() << "shared assets not found"; \
  const Scene var = import_scene(shared_asset(relative), Context{})

std::set<std::pair<std::uint32_t, std::uint32_t>> edges_of(const Mesh& mesh) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = mesh.indices[t + e], b = mesh.indices[t + (e + 1) % 3];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  return edges;
}

// Two triangles sharing the edge 1-2, skinned to two joints.
Mesh two_triangles() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  m.local_positions = m.positions;
  m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
  m.local_normals = m.normals;
  m.texcoords0 = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  m.joints0 = {{0, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 0, 0}, {1, 2, 3, 4}};
  m.weights0 = {{1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}, {0.4f, 0.3f, 0.2f, 0.1f}};
  m.indices = {0, 1, 2, 2, 1, 3};
  return m;
}

TEST(PoseSubdivide, OneLevelAddsOneVertexPerEdgeAndFourTrianglesPerTriangle) {
  const Mesh m = two_triangles();
  const Mesh s = subdivide_mesh(m);
  EXPECT_EQ(s.vertex_count(), 4u + 5u);  // the shared edge 1-2 split once
  EXPECT_EQ(s.triangle_count(), 8u);
  // The original vertices keep their index and attributes.
  for (std::size_t v = 0; v < 4; ++v) EXPECT_EQ(s.positions[v], m.positions[v]);
  // Every attribute has one value per vertex.
  EXPECT_EQ(s.local_positions.size(), s.vertex_count());
  EXPECT_EQ(s.normals.size(), s.vertex_count());
  EXPECT_EQ(s.local_normals.size(), s.vertex_count());
  EXPECT_EQ(s.texcoords0.size(), s.vertex_count());
  EXPECT_EQ(s.joints0.size(), s.vertex_count());
  EXPECT_TRUE(s.tangents.empty() && s.colors0.empty());
  // Each new vertex is the midpoint of exactly one edge, and the shared edge's midpoint is in
  // the triangles of both sides.
  std::set<std::pair<float, float>> seen;
  for (std::size_t v = 4; v < s.vertex_count(); ++v)
    EXPECT_TRUE(seen.insert({s.positions[v].x, s.positions[v].y}).second) << v;
  std::size_t uses = 0;
  for (std::uint32_t i : s.indices) uses += s.positions[i] == glm::vec3(0.5f, 0.5f, 0.0f);
  EXPECT_EQ(uses, 6u);  // 3 of the 4 small triangles on each side touch it
  // Winding: every small triangle faces +z like its parent.
  for (std::size_t t = 0; t < s.indices.size(); t += 3) {
    const glm::vec3 a = s.positions[s.indices[t]], b = s.positions[s.indices[t + 1]],
                    c = s.positions[s.indices[t + 2]];
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << t / 3;
  }
}

TEST(PoseSubdivide, MidpointWeightsAverageTheEndsAndKeepTheFourLargest) {
  const Mesh s = subdivide_mesh(two_triangles());
  auto weight_of = [&](std::size_t v, std::uint16_t joint) {
    float w = 0.0f;
    for (int k = 0; k < 4; ++k) w += s.joints0[v][k] == joint ? s.weights0[v][k] : 0.0f;
    return w;
  };
  auto find = [&](glm::vec3 p) {
    for (std::size_t v = 4; v < s.vertex_count(); ++v)
      if (s.positions[v] == p) return v;
    ADD_FAILURE() << "no vertex at the midpoint";
    return std::size_t(0);
  };
  // Edge 0-1: joint 0 at (1 + 0.5) / 2, joint 1 at 0.5 / 2.
  const std::size_t m01 = find({0.5f, 0, 0});
  EXPECT_FLOAT_EQ(weight_of(m01, 0), 0.75f);
  EXPECT_FLOAT_EQ(weight_of(m01, 1), 0.25f);
  // Edge 2-3: joints 0, 1, 2, 3, 4 at 0.5, 0.2, 0.15, 0.1, 0.05; only four are kept, so joint 4
  // goes and the rest is renormalised by 0.95.
  const std::size_t m23 = find({0.5f, 1, 0});
  EXPECT_FLOAT_EQ(weight_of(m23, 0), 0.5f / 0.95f);
  EXPECT_FLOAT_EQ(weight_of(m23, 1), 0.2f / 0.95f);
  EXPECT_FLOAT_EQ(weight_of(m23, 2), 0.15f / 0.95f);
  EXPECT_FLOAT_EQ(weight_of(m23, 3), 0.10f / 0.95f);
  EXPECT_EQ(weight_of(m23, 4), 0.0f);
  // Normals: the mean renormalised.
  const std::size_t m23n = m23;
  EXPECT_NEAR(glm::length(s.normals[m23n]), 1.0f, 1e-6f);
  EXPECT_NEAR(s.normals[m23n].x, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(s.normals[m23n].y, std::sqrt(0.5f), 1e-6f);
}

// A level that fits in the target splits every edge; the last splits the longest edges, as many
// as reach the target exactly.
TEST(PoseSubdivide, PartialLastLevelSplitsTheLongestEdges) {
  Scene scene;
  scene.meshes.push_back(two_triangles());
  const Scene full = subdivide_scene(scene, 9);
  EXPECT_EQ(full.vertex_count(), 9u);
  EXPECT_EQ(full.triangle_count(), 8u);
  // 7 vertices: the two longest edges, the diagonal 1-2 (sqrt 2) and then, of the four unit
  // edges, the two with the lowest keys (0-1, 0-2).
  const Scene part = subdivide_scene(scene, 7);
  ASSERT_EQ(part.vertex_count(), 7u);
  const Mesh& m = part.meshes[0];
  std::set<std::pair<float, float>> mids;
  for (std::size_t v = 4; v < 7; ++v) mids.insert({m.positions[v].x, m.positions[v].y});
  EXPECT_EQ(mids, (std::set<std::pair<float, float>>{{0.5f, 0.5f}, {0.5f, 0.0f}, {0.0f, 0.5f}}));
  // Triangle 0-1-2 has three cut edges (4 triangles), 2-1-3 one (2): area and winding kept.
  EXPECT_EQ(m.triangle_count(), 6u);
  float area = 0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                    c = m.positions[m.indices[t + 2]];
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << t / 3;
    area += 0.5f * glm::cross(b - a, c - a).z;
  }
  EXPECT_FLOAT_EQ(area, 1.0f);
}

TEST(PoseSubdivide, CesiumManReachesPaperScale) {
  IMPORT_OR_SKIP(scene, "characters/CesiumMan.glb");
  std::size_t one_level = 0, triangles = 0;
  for (const Mesh& m : scene.meshes) {
    one_level += m.vertex_count() + edges_of(m).size();
    triangles += 4 * m.triangle_count();
  }
  Scene level;
  level.meshes = scene.meshes;
  for (Mesh& m : level.meshes) m = subdivide_mesh(m);
  EXPECT_EQ(level.vertex_count(), one_level);  // V + E
  EXPECT_EQ(level.triangle_count(), triangles);
  const Scene s = subdivide_scene(scene, 11534);  // the paper's character
  std::printf("CesiumMan: %zu vertices, %zu after one level, %zu at the target, %zu triangles\n",
              scene.vertex_count(), one_level, s.vertex_count(), s.triangle_count());
  EXPECT_EQ(s.vertex_count(), 11534u);
  EXPECT_EQ(subdivide_scene(scene, 0).vertex_count(), scene.vertex_count());
  for (std::size_t i = 0; i < s.meshes.size(); ++i) {
    const Mesh& m = s.meshes[i];
    ASSERT_EQ(m.weights0.size(), m.vertex_count());
    ASSERT_EQ(m.joints0.size(), m.vertex_count());
    ASSERT_EQ(m.local_positions.size(), m.vertex_count());
    ASSERT_EQ(m.local_normals.size(), m.vertex_count());
    // The file's own weights are kept as they are (CesiumMan's do not all sum to 1); every new
    // vertex's sum to 1 up to the rounding of four float divisions and the sum.
    for (std::size_t v = scene.meshes[i].vertex_count(); v < m.vertex_count(); ++v) {
      const glm::vec4 w = m.weights0[v];
      EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 8 * 0x1p-24) << v;
      EXPECT_TRUE(w.x >= 0 && w.y >= 0 && w.z >= 0 && w.w >= 0) << v;
      EXPECT_NEAR(glm::length(m.local_normals[v]), 1.0f, 4 * 0x1p-24) << v;
    }
  }
}

// At the rest pose every joint's skinning matrix is the same placement of the mesh when the
// file's rest pose is its bind pose; then an edge whose ends share their joints (at most four
// between them, so that no weight is dropped) has a new vertex skinned to exactly the midpoint
// of its skinned ends: the blend of the averaged weights is the mean of the two blends, and the
// skin is linear in the position. Float rounding of the skinning (a few operations of
// magnitude |K| |p| + |t|) is all that separates them.
TEST(PoseSubdivide, MidpointsSkinnedAtRestAreTheMidpointsOfTheSkinnedEnds) {
  IMPORT_OR_SKIP(scene, "characters/CesiumMan.glb");
  Scene s = scene;
  for (Mesh& m : s.meshes) m = subdivide_mesh(m);
  const std::vector<glm::mat4> world = ScenePose(s).world_matrices();
  std::size_t checked = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < s.meshes.size(); ++i) {
    const Mesh& before = scene.meshes[i];
    Mesh placed = s.meshes[i];
    place_mesh(s, world, placed);
    float extent = 0.0f;
    for (const glm::vec3& p : placed.positions)
      extent = std::max({extent, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    std::size_t next = before.vertex_count();
    std::set<std::pair<std::uint32_t, std::uint32_t>> done;
    for (std::size_t t = 0; t < before.indices.size(); t += 3)
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t a = before.indices[t + e], b = before.indices[t + (e + 1) % 3];
        if (!done.insert({std::min(a, b), std::max(a, b)}).second) continue;
        const std::size_t mid = next++;  // new vertices in order of first use
        std::set<int> joints;
        for (int k = 0; k < 4; ++k) {
          if (before.weights0[a][k] > 0) joints.insert(before.joints0[a][k]);
          if (before.weights0[b][k] > 0) joints.insert(before.joints0[b][k]);
        }
        const std::vector<glm::vec3>& bind = s.meshes[i].positions;
        ASSERT_EQ(bind[mid], 0.5f * (bind[a] + bind[b]))
            << "vertex " << mid << " is not edge " << a << "-" << b << "'s";
        if (joints.size() > 4) continue;
        const glm::vec3 expect = 0.5f * (placed.positions[a] + placed.positions[b]);
        worst = std::max(worst, double(glm::length(placed.positions[mid] - expect)) / extent);
        ++checked;
      }
  }
  std::printf("%zu midpoints checked: worst distance %.3g of the extent\n", checked, worst);
  EXPECT_GT(checked, 1000u);
  EXPECT_LE(worst, 64 * 0x1p-24);
}

}  // namespace
}  // namespace prt::bake
