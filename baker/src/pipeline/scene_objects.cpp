// SPDX-License-Identifier: MIT
// A scene's objects for the content pipeline: each node with a mesh, cut out with its materials
// and images, what kind of node it is, and what makes it unbakeable (prt/baker/scene_bake.hpp).
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "prt/baker/embree_scene.hpp"
#include "prt/baker/scene_bake.hpp"

#include "../common/numbers.hpp"

namespace prt::bake {
namespace {

// A name usable as a file name on every platform: letters, digits, '-', '_' and '.' kept, the
// rest '_'; never empty, never starting with '.'.
std::string file_safe(const std::string& name) {
  std::string out;
  for (const char c : name) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ||
                      (c == '.' && !out.empty());
    out += keep ? c : '_';
  }
  return out;
}

// The node's meshes alone; materials and images renumbered to those they use.
Scene cut_out(const Scene& scene, int node) {
  Scene object;
  object.source = scene.source;
  object.nodes = scene.nodes;  // Mesh::node, skins and animations keep their indices
  object.skins = scene.skins;
  object.animations = scene.animations;
  std::map<int, int> materials, images;
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.node != node) continue;
    Mesh copy = mesh;
    if (mesh.material >= 0) {
      auto [it, added] = materials.try_emplace(mesh.material, int(object.materials.size()));
      if (added) {
        Material material = scene.materials[mesh.material];
        if (material.base_color_texture >= 0) {
          auto [image, new_image] =
              images.try_emplace(material.base_color_texture, int(object.images.size()));
          if (new_image) object.images.push_back(scene.images[material.base_color_texture]);
          material.base_color_texture = image->second;
        }
        object.materials.push_back(std::move(material));
      }
      copy.material = it->second;
    }
    object.meshes.push_back(std::move(copy));
  }
  return object;
}

// Whether the node stays where the file puts it: no skin poses it and it does not move.
bool stays_put(const Scene& scene, int node) {
  const NodeKind kind = node_kind(scene, node);
  return !kind.skinned && !kind.moves;
}

// The meshes of every other node that stays put, as occluders of `node`'s bake: positions and
// triangles only (rays stop on them; nothing is shaded on them).
std::vector<Mesh> static_surroundings(const Scene& scene, int node) {
  std::vector<Mesh> occluders;
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.node < 0 || mesh.node == node || !stays_put(scene, mesh.node)) continue;
    Mesh occluder;
    occluder.name = mesh.name;
    occluder.node = mesh.node;
    occluder.positions = mesh.positions;
    occluder.indices = mesh.indices;
    occluders.push_back(std::move(occluder));
  }
  return occluders;
}

std::vector<std::string> problems_of(const Scene& object) {
  std::vector<std::string> problems;
  std::size_t triangles = 0, degenerate = 0;
  bool non_finite = false;
  for (const Mesh& mesh : object.meshes) {
    for (const glm::vec3& p : mesh.positions) non_finite = non_finite || !finite(p);
    triangles += mesh.triangle_count();
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
      degenerate += is_degenerate_triangle(mesh, t);
  }
  if (non_finite)
    problems.push_back("non-finite positions (a NaN or infinity in its transform or vertices)");
  if (triangles == 0)
    problems.push_back("no triangles");
  else if (degenerate == triangles)
    problems.push_back("every triangle is degenerate (zero area or a repeated index)");
  return problems;
}

// What the keep-going import recorded about the node, as "import: <reason>" (the import records
// a texture problem for each node whose meshes use the material).
std::vector<std::string> import_problems(const Scene& scene, int node) {
  std::vector<std::string> problems;
  for (const ImportProblem& problem : scene.problems) {
    if (problem.node == node) problems.push_back("import: " + problem.reason);
  }
  return problems;
}

}  // namespace

NodeKind node_kind(const Scene& scene, int node) {
  NodeKind kind;
  const Node& n = scene.nodes.at(static_cast<std::size_t>(node));
  kind.has_mesh = n.mesh >= 0;
  kind.skinned = n.skin >= 0;
  kind.moves = n.animated || n.hints.dynamic;
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.node != node || mesh.material < 0) continue;
    const Material& material = scene.materials[static_cast<std::size_t>(mesh.material)];
    kind.cloth = kind.cloth || material.sheen || material.cloth;
  }
  return kind;
}

ObjectFit static_diffuse_fit(const Scene& scene, int node) {
  const NodeKind kind = node_kind(scene, node);
  if (kind.skinned) return {false, "skinned"};
  if (kind.moves) return {false, "moves (animated or marked dynamic)"};
  if (kind.cloth) return {false, "has a cloth material"};
  return {true, "static, diffuse"};
}

std::vector<SceneObject> scene_objects(const Scene& scene) {
  std::vector<SceneObject> objects;
  std::set<std::string> names;
  for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
    const Node& node = scene.nodes[n];
    if (node.mesh < 0) continue;
    SceneObject object;
    object.node = int(n);
    const std::string base = file_safe(node.name.empty() ? "node" + std::to_string(n) : node.name);
    object.name = base;
    for (int k = 2; !names.insert(object.name).second; ++k)
      object.name = base + "-" + std::to_string(k);
    object.skipped = node.hints.skip;
    object.scene = cut_out(scene, int(n));
    // A static object is baked in its static surroundings, which shadow it; what moves is left
    // out, since it is not there in every frame.
    if (stays_put(scene, int(n))) object.scene.occluders = static_surroundings(scene, int(n));
    object.problems = import_problems(scene, int(n));
    for (std::string& problem : problems_of(object.scene)) {
      // Meshes the import dropped leave no triangles: its problems already say why.
      if (problem == "no triangles" && !object.problems.empty()) continue;
      object.problems.push_back(std::move(problem));
    }
    objects.push_back(std::move(object));
  }
  return objects;
}

}  // namespace prt::bake
