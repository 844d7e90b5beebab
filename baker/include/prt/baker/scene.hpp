// SPDX-License-Identifier: MIT
// The raw scene: what the importers (glTF, OBJ) produce and every bake stage reads.
//
// World frame: glTF's, right-handed, +Y up, metres (formats/SPEC.md §Frames). OBJ files are
// taken to be in the same frame. Every mesh's positions/normals/tangents are in world space;
// the mesh-local originals are kept for the techniques that animate (skinning, rigid motion).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "prt/baker/context.hpp"

namespace prt::bake {

struct Material {
  std::string name;
  glm::vec4 base_color{1.0f};   // linear RGBA factor (glTF baseColorFactor)
  int base_color_texture = -1;  // index into Scene::images, -1 = none
  int base_color_texcoord = 0;  // which TEXCOORD_n the texture uses
  // KHR_texture_transform of the base colour texture: uv' = (M * vec3(uv, 1)).xy.
  glm::mat3 base_color_uv_transform{1.0f};
  bool double_sided = false;
  // KHR_materials_sheen (cloth-like materials); sheen = false when the extension is absent.
  bool sheen = false;
  glm::vec3 sheen_color{0.0f};   // sheenColorFactor (linear)
  float sheen_roughness = 0.0f;  // sheenRoughnessFactor
  // extras.prt.cloth: true marks the material as woven cloth for `prt-bake scene`.
  bool cloth = false;
};

// A decoded texture image, RGBA8 as stored (sRGB for base colour).
struct Image {
  std::string name;
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width*height*4
};

struct Node {
  std::string name;
  int parent = -1;
  std::vector<int> children;
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
  glm::vec3 scale{1.0f};
  glm::mat4 local{1.0f};  // T*R*S, or the node's matrix
  glm::mat4 world{1.0f};  // parent world * local
  int mesh = -1;          // glTF mesh index, -1 = none
  int skin = -1;          // index into Scene::skins, -1 = none
  // What extras.prt says to `prt-bake scene` (docs/pipeline.md).
  struct Hints {
    bool dynamic = false;   // extras.prt.dynamic: true: the node moves at run time
    std::string technique;  // extras.prt.technique: forces this technique; empty: none
    // extras.prt.settings: {"order": 4, "rays": 256} as option arguments
    // {"--order","4"},{"--rays","256"}
    std::vector<std::pair<std::string, std::string>> settings;
    bool skip = false;  // extras.prt.skip: true: not baked
  } hints;
  bool animated = false;  // an animation channel (translation, rotation or scale) targets this
                          // node or one of its ancestors
};

struct Skin {
  std::string name;
  std::vector<int> joints;              // node indices
  std::vector<glm::mat4> inverse_bind;  // one per joint (identity where the file has none)
  int skeleton = -1;                    // root node, -1 = none given
};

struct AnimationChannel {
  enum class Path { Translation, Rotation, Scale, Weights };
  enum class Interpolation { Linear, Step, CubicSpline };
  int node = -1;
  Path path = Path::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;   // seconds, ascending
  std::vector<float> values;  // times.size() * components (x3 for CubicSpline: in, value, out)
  int components = 3;         // 3 (T, S), 4 (R as x,y,z,w), or the morph-target count
};

struct Animation {
  std::string name;
  std::vector<AnimationChannel> channels;
  float duration = 0.0f;  // seconds
};

// One triangle list (a glTF primitive, or an OBJ object) in world space.
struct Mesh {
  std::string name;
  int node = -1;      // node that places it (-1 for OBJ)
  int material = -1;  // index into Scene::materials, -1 = default (white)
  int skin = -1;      // index into Scene::skins, -1 = not skinned

  // World space. For a skinned mesh: the bind pose placed by the skin's joints at their rest
  // transforms (glTF ignores the mesh node's own transform then).
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // unit length; generated (area-weighted) where the file has none
  std::vector<glm::vec4> tangents;  // xyz unit, w = handedness; empty where no UVs to derive them
  // Mesh-local attributes as stored in the file (before any node or skin transform).
  std::vector<glm::vec3> local_positions;
  std::vector<glm::vec3> local_normals;

  std::vector<glm::vec2> texcoords0;  // empty if absent
  std::vector<glm::vec4> colors0;     // linear RGBA, empty if absent
  std::vector<glm::u16vec4> joints0;  // empty if not skinned
  std::vector<glm::vec4> weights0;    // empty if not skinned

  std::vector<std::uint32_t> indices;  // 3 per triangle, each < positions.size()

  bool normals_generated = false;
  bool tangents_generated = false;

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// What a keep-going import (ImportOptions::keep_going) dropped or repaired, one entry per node it
// concerns:
// - a primitive whose data is unusable (a bad accessor, a non-finite position, an index out of
//   range, Draco data that does not decode, no triangles, ...): dropped; one problem per node
//   that instances its mesh (node and mesh set), or one with node -1 when no node places it;
// - a node whose world transform is not finite (NaN or infinity in its TRS or matrix, or in an
//   ancestor's): its meshes are not imported; one problem for it and one for each such node
//   under it (node set), whether it has a mesh or not; likewise a node whose mesh does not exist;
// - a base colour texture that does not load (its image does not decode or its file is missing,
//   or the texture does not exist): the material keeps its factor, base_color_texture = -1; one
//   problem per node whose imported meshes use the material (node and material set), or one with
//   node -1 when none does. So a consumer finds all of a node's problems by its index alone.
struct ImportProblem {
  int node = -1;      // the node it concerns (-1: the file as a whole, or an unplaced mesh)
  int mesh = -1;      // glTF mesh index, -1 when not about a mesh
  int material = -1;  // material index, -1 when not about a material
  // What is wrong, as the throwing import would have said it without the leading "<file>: "
  // (Scene::source names the file), e.g. "mesh 4 'lost' primitive 0 has a non-finite vertex
  // position".
  std::string reason;
};

struct ImportOptions {
  // false (default): any problem throws Error, as import_scene(path, ctx) does. true: a problem
  // confined to a primitive, a node or a texture is recorded in Scene::problems and the rest is
  // imported.
  bool keep_going = false;
};

struct Scene {
  std::string source;  // the file it came from
  std::vector<Mesh> meshes;
  // World-space meshes that only block light: rays stop on them (shadows, and a bounce ends
  // there, as on a black surface), but they have no vertices of their own and nothing is baked
  // or rendered for them. prt-bake scene puts an object's static surroundings here. Every count,
  // bound and per-vertex output (vertex_count, bounds, ...) is about `meshes` only.
  std::vector<Mesh> occluders;
  std::vector<Material> materials;
  std::vector<Image> images;
  std::vector<Node> nodes;
  std::vector<Skin> skins;
  std::vector<Animation> animations;
  // What a keep-going import set aside (ImportProblem); always empty otherwise.
  std::vector<ImportProblem> problems;

  // Vertices are numbered by concatenating meshes in order: this is "the order of the imported
  // mesh" used by every per-vertex output (e.g. prt-bake reference --vertex-out).
  std::size_t vertex_count() const;
  std::size_t triangle_count() const;
  // World-space bounds of all mesh positions.
  void bounds(glm::vec3& lo, glm::vec3& hi) const;
  // Linear RGB albedo of a mesh vertex: material base colour x vertex colour x texture (sampled
  // at the vertex UV, sRGB decoded), clamped to [0,1].
  glm::vec3 vertex_albedo(const Mesh& mesh, std::size_t vertex) const;
};

// Recomputes a mesh's world-space normals, area-weighted from positions and indices (vertices
// no triangle touches get +Y), and flags them generated.
void generate_normals(Mesh& mesh);
// Recomputes world-space tangents from TEXCOORD_0 (per-triangle dP/du accumulated by area,
// orthogonalised against the normal; w = +1 when cross(n, t) points to decreasing v, glTF's
// convention), and flags them generated. Clears them when the mesh has no UVs or normals.
void generate_tangents(Mesh& mesh);

// Appends `other` to `scene`: its meshes, materials, images, nodes (as further roots), skins,
// animations and problems, with every index into them shifted (a node's glTF mesh index past
// the largest of `scene`). How a scene is assembled from parts, e.g. a character placed in a
// level.
void append_scene(Scene& scene, const Scene& other);

// Reads .gltf / .glb (with KHR_draco_mesh_compression) or .obj, chosen by the file extension.
// Throws Error naming the file and what is wrong. Warnings (e.g. generated normals) go to ctx.
Scene import_scene(const std::string& path, const Context& ctx);
// The same, with options. With keep_going, a glTF file's broken primitives, nodes and base
// colour textures are recorded in Scene::problems (each also a warning through ctx) and the rest
// is imported. What concerns the file as a whole still throws: it cannot be read, its JSON or GLB
// container is broken, it is not glTF 2.0 or requires an unsupported extension, a buffer is
// missing or short, the node graph is not a tree, a skin or an animation (or an accessor they
// use) is broken. When every mesh is broken the scene comes back with no meshes and its problems;
// a file with no problems and no meshes still throws. An OBJ file is read as without options.
Scene import_scene(const std::string& path, const Context& ctx, const ImportOptions& options);

}  // namespace prt::bake
