// SPDX-License-Identifier: MIT
// The mixed scene of issue 16, assembled in memory: a static ground and ring (a torus, which
// shadows itself), a cloth rug, a crate that moves at run time (extras.prt.dynamic) and a character
// (a shared asset, appended), each its own node: one object for each technique of prt-bake scene.
#pragma once

#include <string>
#include <utility>

#include "prt/baker/mesh_generators.hpp"
#include "prt/baker/scene.hpp"
#include "prt/baker/scene_bake.hpp"

namespace prt_test {

namespace mixed_scene_detail {

inline prt::bake::Material named_material(const char* name, glm::vec3 colour) {
  prt::bake::Material m;
  m.name = name;
  m.base_color = glm::vec4(colour, 1.0f);
  return m;
}

inline void add_node(prt::bake::Scene& scene, const char* name, prt::bake::Mesh mesh) {
  prt::bake::Node node;
  node.name = name;
  node.mesh = int(scene.nodes.size());
  mesh.node = int(scene.nodes.size());
  scene.nodes.push_back(node);
  scene.meshes.push_back(std::move(mesh));
}

}  // namespace mixed_scene_detail

// Nodes "ground", "ring", "rug" (linen, its warp along +X), "crate", then `character`'s.
inline prt::bake::Scene mixed_scene(const prt::bake::Scene& character) {
  using namespace prt::bake;
  using mixed_scene_detail::add_node;
  using mixed_scene_detail::named_material;
  Scene scene;
  scene.source = "mixed scene";
  scene.materials = {named_material("ground", {0.6f, 0.6f, 0.6f}),
                     named_material("ring", {0.7f, 0.4f, 0.3f}),
                     named_material("linen_plain", {0.5f, 0.1f, 0.1f}),
                     named_material("crate", {0.6f, 0.5f, 0.3f})};
  scene.materials[2].sheen = true;
  scene.materials[2].sheen_color = glm::vec3(0.6f, 0.1f, 0.1f);
  scene.materials[2].sheen_roughness = 0.5f;
  add_node(scene, "ground", make_plane_mesh("ground", 0, 2.0f, 2.0f, 12, 12));
  add_node(scene, "ring", make_torus_mesh(1, {-1.0f, 0.12f, 0.8f}, 0.3f, 0.12f, 16, 32));
  Mesh rug = make_plane_mesh("rug", 2, 0.5f, 0.3f, 8, 6);
  for (glm::vec3& p : rug.positions) p += glm::vec3(1.0f, 0.01f, 1.0f);
  rug.tangents.assign(rug.vertex_count(), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  add_node(scene, "rug", rug);
  add_node(scene, "crate", make_box_mesh(3, {1.2f, 0.25f, -1.0f}, 0.25f, 0.4f, 3));
  scene.nodes.back().hints.dynamic = true;
  append_scene(scene, character);
  return scene;
}

// How the mixed-scene test and prt_scene_table bake it: under `light` alone, no bounce, 96
// probe vertices against a 512-sample reference, the budget `budget` (a fraction).
inline prt::bake::SceneBakeSettings mixed_scene_settings(const std::string& out, double budget,
                                                         const std::string& light) {
  prt::bake::SceneBakeSettings s;
  s.scene = "mixed";
  s.out_dir = out;
  s.error_budget = budget;
  s.envs = {light};
  s.bounces = 0;
  s.ref_spp = 512;
  s.probe_vertices = 96;
  return s;
}

}  // namespace prt_test
