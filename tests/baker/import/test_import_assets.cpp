// SPDX-License-Identifier: MIT
// Every scene in shared/assets imports, with the counts MANIFEST.md states, positions within the
// POSITION min/max each file records, and the Draco files equal to their originals within the
// quantisation step.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "prt/baker/scene.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

using prt_test::read_bytes;
using prt_test::shared_asset;

Scene import_asset(const std::string& relative) {
  const std::string path = shared_asset(relative);
  if (path.empty()) return Scene{};
  return import_scene(path, Context{});
}

#define IMPORT_OR_SKIP(var, relative)                                            \
  if (shared_asset(relative).empty()) GTEST_SKIP() << "shared assets not found"; \
  const Scene var = import_asset(relative)

// The glTF JSON of a .gltf or .glb file, read here independently of the importer.
nlohmann::json gltf_json(const std::string& path) {
  const std::string bytes = read_bytes(path);
  if (bytes.compare(0, 4, "glTF") == 0) {
    std::uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    return nlohmann::json::parse(bytes.substr(20, length));
  }
  return nlohmann::json::parse(bytes);
}

void local_bounds(const Mesh& mesh, glm::vec3& lo, glm::vec3& hi) {
  lo = glm::vec3(1e30f);
  hi = glm::vec3(-1e30f);
  for (const glm::vec3& p : mesh.local_positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
}

// Every mesh's mesh-local positions span exactly the min/max its POSITION accessor records
// (within tol x the extent).
void expect_positions_match_recorded_bounds(const std::string& relative, const Scene& scene,
                                            double tol) {
  const nlohmann::json doc = gltf_json(shared_asset(relative));
  ASSERT_FALSE(scene.meshes.empty());
  for (const Mesh& mesh : scene.meshes) {
    const int gltf_mesh = scene.nodes[mesh.node].mesh;
    // Mesh names carry "#p" when the glTF mesh has several primitives.
    const std::size_t hash = mesh.name.rfind('#');
    const int primitive = hash == std::string::npos ? 0 : std::stoi(mesh.name.substr(hash + 1));
    const int accessor =
        doc["meshes"][gltf_mesh]["primitives"][primitive]["attributes"]["POSITION"].get<int>();
    const auto& record = doc["accessors"][accessor];
    ASSERT_TRUE(record.contains("min") && record.contains("max")) << relative;
    glm::vec3 lo, hi;
    local_bounds(mesh, lo, hi);
    double extent = 0.0;
    for (int c = 0; c < 3; ++c) {
      extent = std::max(extent, record["max"][c].get<double>() - record["min"][c].get<double>());
    }
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(lo[c], record["min"][c].get<double>(), tol * extent) << relative << " axis " << c;
      EXPECT_NEAR(hi[c], record["max"][c].get<double>(), tol * extent) << relative << " axis " << c;
    }
  }
}

void expect_unit_normals(const Scene& scene) {
  for (const Mesh& mesh : scene.meshes) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (std::size_t i = 0; i < mesh.normals.size(); i += 17) {
      EXPECT_NEAR(glm::length(mesh.normals[i]), 1.0f, 1e-4f);
    }
  }
}

// ---- OBJ ----------------------------------------------------------------------------------------

TEST(ImportAssets, StanfordBunny) {
  IMPORT_OR_SKIP(scene, "meshes/stanford-bunny.obj");
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.vertex_count(), 35947u);
  EXPECT_EQ(scene.triangle_count(), 69451u);
  EXPECT_TRUE(scene.meshes[0].normals_generated);
  expect_unit_normals(scene);
}

TEST(ImportAssets, Teapot) {
  IMPORT_OR_SKIP(scene, "meshes/teapot.obj");
  EXPECT_EQ(scene.vertex_count(), 3644u);
  EXPECT_EQ(scene.triangle_count(), 6320u);
}

TEST(ImportAssets, Armadillo) {
  IMPORT_OR_SKIP(scene, "meshes/armadillo.obj");
  EXPECT_EQ(scene.vertex_count(), 12502u);
  EXPECT_EQ(scene.triangle_count(), 25000u);
}

TEST(ImportAssets, SpotKeepsFileOrderAndSplitsUvSeams) {
  IMPORT_OR_SKIP(scene, "meshes/spot.obj");
  ASSERT_EQ(scene.meshes.size(), 1u);
  const Mesh& mesh = scene.meshes[0];
  EXPECT_EQ(scene.triangle_count(), 5856u);
  // 2930 positions; UV seams add vertices, never more than the 3225 texcoords allow.
  EXPECT_GE(mesh.vertex_count(), 2930u);
  EXPECT_LE(mesh.vertex_count(), 3225u);
  std::set<std::array<float, 3>> unique;
  for (const glm::vec3& p : mesh.positions) unique.insert({p.x, p.y, p.z});
  EXPECT_EQ(unique.size(), 2930u);
  // The first vertex is the file's first `v` line.
  EXPECT_FLOAT_EQ(mesh.positions[0].x, 0.348799f);
  EXPECT_FLOAT_EQ(mesh.positions[0].y, -0.334989f);
  EXPECT_FLOAT_EQ(mesh.positions[0].z, -0.0832331f);
  EXPECT_EQ(mesh.texcoords0.size(), mesh.vertex_count());
  EXPECT_EQ(mesh.tangents.size(), mesh.vertex_count());
  EXPECT_TRUE(mesh.tangents_generated);
}

// ---- glTF ---------------------------------------------------------------------------------------

TEST(ImportAssets, Fox) {
  IMPORT_OR_SKIP(scene, "characters/Fox.glb");
  EXPECT_EQ(scene.vertex_count(), 1728u);
  ASSERT_EQ(scene.skins.size(), 1u);
  EXPECT_EQ(scene.skins[0].joints.size(), 24u);
  ASSERT_EQ(scene.animations.size(), 3u);
  std::set<std::string> names;
  for (const Animation& a : scene.animations) {
    names.insert(a.name);
    EXPECT_GT(a.duration, 0.0f);
  }
  EXPECT_EQ(names, (std::set<std::string>{"Survey", "Walk", "Run"}));
  EXPECT_EQ(scene.images.size(), 1u);
  EXPECT_GT(scene.images[0].width, 0);
  EXPECT_EQ(scene.meshes[0].skin, 0);
  expect_positions_match_recorded_bounds("characters/Fox.glb", scene, 1e-5);
  expect_unit_normals(scene);
}

TEST(ImportAssets, CesiumMan) {
  IMPORT_OR_SKIP(scene, "characters/CesiumMan.glb");
  EXPECT_EQ(scene.vertex_count(), 3273u);
  ASSERT_EQ(scene.skins.size(), 1u);
  EXPECT_EQ(scene.skins[0].joints.size(), 19u);
  EXPECT_EQ(scene.animations.size(), 1u);
  ASSERT_EQ(scene.images.size(), 1u);  // the embedded JPEG, decoded
  EXPECT_EQ(scene.images[0].rgba.size(),
            static_cast<std::size_t>(scene.images[0].width) * scene.images[0].height * 4);
  expect_positions_match_recorded_bounds("characters/CesiumMan.glb", scene, 1e-5);
  expect_unit_normals(scene);
  // Skinned and standing: the rest pose is about 1.5 m tall along +Y, feet at 0.
  glm::vec3 lo, hi;
  scene.bounds(lo, hi);
  EXPECT_NEAR(lo.y, 0.0f, 0.01f);
  EXPECT_NEAR(hi.y - lo.y, 1.5f, 0.1f);
}

TEST(ImportAssets, RiggedFigure) {
  IMPORT_OR_SKIP(scene, "characters/RiggedFigure.glb");
  EXPECT_EQ(scene.vertex_count(), 370u);
  ASSERT_EQ(scene.skins.size(), 1u);
  EXPECT_EQ(scene.skins[0].joints.size(), 19u);
  EXPECT_EQ(scene.animations.size(), 1u);
  EXPECT_TRUE(scene.images.empty());
  expect_positions_match_recorded_bounds("characters/RiggedFigure.glb", scene, 1e-5);
}

TEST(ImportAssets, RiggedSimpleWithExternalBuffer) {
  IMPORT_OR_SKIP(scene, "characters/RiggedSimple/RiggedSimple.gltf");
  EXPECT_EQ(scene.vertex_count(), 96u);
  ASSERT_EQ(scene.skins.size(), 1u);
  EXPECT_EQ(scene.skins[0].joints.size(), 2u);
  EXPECT_EQ(scene.animations.size(), 1u);
  expect_positions_match_recorded_bounds("characters/RiggedSimple/RiggedSimple.gltf", scene, 1e-5);
}

TEST(ImportAssets, SimpleSkinWithDataUris) {
  IMPORT_OR_SKIP(scene, "characters/SimpleSkin.gltf");
  EXPECT_EQ(scene.vertex_count(), 10u);
  ASSERT_EQ(scene.skins.size(), 1u);
  EXPECT_EQ(scene.skins[0].joints.size(), 2u);
  ASSERT_EQ(scene.animations.size(), 1u);
  // The glTF tutorial's skin: the second joint rotates about Z, linearly, in quaternion keys.
  const AnimationChannel& channel = scene.animations[0].channels.at(0);
  EXPECT_EQ(channel.path, AnimationChannel::Path::Rotation);
  EXPECT_EQ(channel.components, 4);
  EXPECT_EQ(channel.values.size(), channel.times.size() * 4);
  expect_positions_match_recorded_bounds("characters/SimpleSkin.gltf", scene, 1e-6);
  EXPECT_TRUE(scene.meshes[0].normals_generated);  // the file has no NORMAL
}

TEST(ImportAssets, SheenClothKeepsTangents) {
  IMPORT_OR_SKIP(scene, "meshes/SheenCloth/SheenCloth.gltf");
  EXPECT_EQ(scene.vertex_count(), 58081u);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const Mesh& mesh = scene.meshes[0];
  EXPECT_FALSE(mesh.tangents_generated);
  EXPECT_FALSE(mesh.normals_generated);
  ASSERT_EQ(mesh.tangents.size(), mesh.vertex_count());
  for (std::size_t i = 0; i < mesh.vertex_count(); i += 101) {
    EXPECT_NEAR(glm::dot(glm::vec3(mesh.tangents[i]), mesh.normals[i]), 0.0f, 0.02f);
    EXPECT_EQ(std::abs(mesh.tangents[i].w), 1.0f);
  }
  ASSERT_EQ(scene.images.size(), 4u);
  for (const Image& image : scene.images) {
    EXPECT_EQ(image.width, 256);
    EXPECT_EQ(image.height, 256);
  }
  ASSERT_EQ(scene.materials.size(), 1u);
  // KHR_texture_transform scale (30, -30) on the base colour texture.
  EXPECT_FLOAT_EQ(scene.materials[0].base_color_uv_transform[0][0], 30.0f);
  EXPECT_FLOAT_EQ(scene.materials[0].base_color_uv_transform[1][1], -30.0f);
  // KHR_materials_sheen's factors as the file states them (its sheen textures are not read).
  const nlohmann::json sheen = gltf_json(shared_asset(
      "meshes/SheenCloth/SheenCloth.gltf"))["materials"][0]["extensions"]["KHR_materials_sheen"];
  EXPECT_TRUE(scene.materials[0].sheen);
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(scene.materials[0].sheen_color[c], sheen["sheenColorFactor"][c].get<float>());
  }
  EXPECT_FLOAT_EQ(scene.materials[0].sheen_roughness, sheen["sheenRoughnessFactor"].get<float>());
  expect_positions_match_recorded_bounds("meshes/SheenCloth/SheenCloth.gltf", scene, 1e-5);
}

// ---- Draco --------------------------------------------------------------------------------------

TEST(ImportAssets, BoxDraco) {
  IMPORT_OR_SKIP(scene, "draco/Box_Draco.glb");
  EXPECT_EQ(scene.vertex_count(), 24u);
  EXPECT_EQ(scene.triangle_count(), 12u);
  // The Khronos box is the unit cube centred at the origin; its 24 vertices carry face normals.
  glm::vec3 lo, hi;
  scene.bounds(lo, hi);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(lo[c], -0.5f, 1e-3f);
    EXPECT_NEAR(hi[c], 0.5f, 1e-3f);
  }
  for (const glm::vec3& n : scene.meshes[0].local_normals) {
    EXPECT_NEAR(std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)}), 1.0f, 1e-2f);
  }
}

TEST(ImportAssets, FoxDraco) {
  IMPORT_OR_SKIP(scene, "draco/Fox_Draco.glb");
  EXPECT_EQ(scene.triangle_count(), 576u);  // Fox.glb: 1728 unindexed vertices = 576 triangles
  ASSERT_EQ(scene.skins.size(), 1u);
  EXPECT_EQ(scene.skins[0].joints.size(), 24u);
  EXPECT_EQ(scene.animations.size(), 3u);
}

TEST(ImportAssets, SheenClothDraco) {
  IMPORT_OR_SKIP(scene, "draco/SheenCloth_Draco.glb");
  EXPECT_EQ(scene.vertex_count(), 58081u);
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_FALSE(scene.meshes[0].tangents_generated);
  EXPECT_EQ(scene.images.size(), 4u);
}

// CesiumMan_Draco.glb was written by gltf-transform's `draco` command with its default
// quantisation: POSITION 14 bits, TEXCOORD 12 bits, generic (WEIGHTS) 12 bits; JOINTS lossless.
// Draco quantises a position attribute over the cube of side R = the largest extent of its
// bounding box, so one step is q = R / (2^14 - 1) and every decoded coordinate lies within q/2
// of the original. Draco reorders and splits vertices, so vertices are matched by nearest
// position and the triangle sets compared as sets of original positions.
TEST(ImportAssets, CesiumManDracoMatchesOriginalWithinQuantisationStep) {
  if (shared_asset("draco/CesiumMan_Draco.glb").empty() ||
      shared_asset("characters/CesiumMan.glb").empty()) {
    GTEST_SKIP() << "shared assets not found";
  }
  const Scene original = import_asset("characters/CesiumMan.glb");
  const Scene draco = import_asset("draco/CesiumMan_Draco.glb");
  ASSERT_EQ(original.meshes.size(), 1u);
  ASSERT_EQ(draco.meshes.size(), 1u);
  const Mesh& a = original.meshes[0];
  const Mesh& b = draco.meshes[0];
  ASSERT_EQ(a.triangle_count(), b.triangle_count());

  glm::vec3 lo, hi;
  local_bounds(a, lo, hi);
  const float range = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  const float step = range / float((1 << 14) - 1);
  const float uv_step = 1.0f / float((1 << 12) - 1);  // texcoords here span at most [0,1]

  // Distinct original positions, each with its id.
  std::map<std::array<float, 3>, int> position_id;
  std::vector<glm::vec3> distinct;
  std::vector<int> id_of_vertex(a.vertex_count());
  for (std::size_t i = 0; i < a.vertex_count(); ++i) {
    const glm::vec3& p = a.local_positions[i];
    auto [it, added] =
        position_id.emplace(std::array<float, 3>{p.x, p.y, p.z}, int(distinct.size()));
    if (added) distinct.push_back(p);
    id_of_vertex[i] = it->second;
  }
  // Each Draco vertex: its nearest original position, within half a step on every axis, and an
  // original vertex at that position with the same joints and a texcoord within a UV step.
  std::vector<int> id_of_draco(b.vertex_count());
  float worst = 0.0f;
  for (std::size_t i = 0; i < b.vertex_count(); ++i) {
    const glm::vec3& p = b.local_positions[i];
    float best = 1e30f;
    int best_id = -1;
    for (std::size_t k = 0; k < distinct.size(); ++k) {
      const glm::vec3 d = distinct[k] - p;
      const float dist = glm::dot(d, d);
      if (dist < best) {
        best = dist;
        best_id = int(k);
      }
    }
    const glm::vec3 diff = glm::abs(distinct[best_id] - p);
    worst = std::max({worst, diff.x, diff.y, diff.z});
    id_of_draco[i] = best_id;
    bool attributes_match = false;
    for (std::size_t k = 0; k < a.vertex_count() && !attributes_match; ++k) {
      if (id_of_vertex[k] != best_id) continue;
      const glm::vec2 duv = glm::abs(a.texcoords0[k] - b.texcoords0[i]);
      attributes_match = a.joints0[k] == b.joints0[i] && duv.x <= uv_step && duv.y <= uv_step;
    }
    EXPECT_TRUE(attributes_match) << "draco vertex " << i;
  }
  EXPECT_LE(worst, 0.5f * step * 1.001f) << "quantisation step " << step;

  auto triangles = [](const Mesh& mesh, const std::vector<int>& ids) {
    std::multiset<std::array<int, 3>> set;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      std::array<int, 3> tri = {ids[mesh.indices[3 * t]], ids[mesh.indices[3 * t + 1]],
                                ids[mesh.indices[3 * t + 2]]};
      std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()),
                  tri.end());  // keeps winding
      set.insert(tri);
    }
    return set;
  };
  EXPECT_TRUE(triangles(a, id_of_vertex) == triangles(b, id_of_draco));

  // Same skeleton and animation.
  ASSERT_EQ(original.skins.size(), draco.skins.size());
  EXPECT_EQ(original.skins[0].joints.size(), draco.skins[0].joints.size());
  ASSERT_EQ(original.animations.size(), draco.animations.size());
  EXPECT_FLOAT_EQ(original.animations[0].duration, draco.animations[0].duration);
}

}  // namespace
}  // namespace prt::bake
