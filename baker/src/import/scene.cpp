// SPDX-License-Identifier: MIT
// Scene queries, the import entry point (dispatch on the file extension) and the mesh
// attribute helpers the importers share.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include "import_detail.hpp"
#include "prt/baker/scene.hpp"

namespace prt::bake {
namespace {

float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Bilinear sample of an RGBA8 image with repeat wrapping (glTF's default sampler), in [0,1].
glm::vec4 sample_repeat(const Image& image, glm::vec2 uv) {
  const float x = uv.x * image.width - 0.5f, y = uv.y * image.height - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float ax = x - fx, ay = y - fy;
  auto wrap = [](int i, int n) { return ((i % n) + n) % n; };
  auto fetch = [&](int i, int j) {
    const std::size_t k =
        (static_cast<std::size_t>(wrap(j, image.height)) * image.width + wrap(i, image.width)) * 4;
    return glm::vec4(image.rgba[k], image.rgba[k + 1], image.rgba[k + 2], image.rgba[k + 3]) /
           255.0f;
  };
  const int i = static_cast<int>(fx), j = static_cast<int>(fy);
  const glm::vec4 top = glm::mix(fetch(i, j), fetch(i + 1, j), ax);
  const glm::vec4 bottom = glm::mix(fetch(i, j + 1), fetch(i + 1, j + 1), ax);
  return glm::mix(top, bottom, ay);
}

std::string lower_extension(const std::string& path) {
  const std::size_t slash = path.find_last_of("/\\");
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

std::size_t Scene::vertex_count() const {
  std::size_t n = 0;
  for (const Mesh& mesh : meshes) n += mesh.vertex_count();
  return n;
}

std::size_t Scene::triangle_count() const {
  std::size_t n = 0;
  for (const Mesh& mesh : meshes) n += mesh.triangle_count();
  return n;
}

void Scene::bounds(glm::vec3& lo, glm::vec3& hi) const {
  lo = glm::vec3(std::numeric_limits<float>::max());
  hi = glm::vec3(std::numeric_limits<float>::lowest());
  for (const Mesh& mesh : meshes) {
    for (const glm::vec3& p : mesh.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  if (lo.x > hi.x) lo = hi = glm::vec3(0.0f);  // no vertices
}

glm::vec3 Scene::vertex_albedo(const Mesh& mesh, std::size_t vertex) const {
  glm::vec4 albedo(1.0f);
  if (mesh.material >= 0 && static_cast<std::size_t>(mesh.material) < materials.size()) {
    const Material& material = materials[mesh.material];
    albedo = material.base_color;
    const bool has_texture = material.base_color_texture >= 0 &&
                             static_cast<std::size_t>(material.base_color_texture) < images.size();
    // Only TEXCOORD_0 is kept by the importers.
    if (has_texture && material.base_color_texcoord == 0 && vertex < mesh.texcoords0.size()) {
      const Image& image = images[material.base_color_texture];
      if (image.width > 0 && image.height > 0) {
        const glm::vec2 uv =
            glm::vec2(material.base_color_uv_transform * glm::vec3(mesh.texcoords0[vertex], 1.0f));
        const glm::vec4 texel = sample_repeat(image, uv);
        albedo *= glm::vec4(srgb_to_linear(texel.r), srgb_to_linear(texel.g),
                            srgb_to_linear(texel.b), texel.a);
      }
    }
  }
  if (vertex < mesh.colors0.size()) albedo *= mesh.colors0[vertex];
  return glm::clamp(glm::vec3(albedo), glm::vec3(0.0f), glm::vec3(1.0f));
}

void generate_normals(Mesh& mesh) {
  mesh.normals = detail::area_weighted_normals(mesh.positions, mesh.indices);
  mesh.normals_generated = true;
}

void generate_tangents(Mesh& mesh) {
  if (mesh.texcoords0.size() != mesh.positions.size() ||
      mesh.normals.size() != mesh.positions.size()) {
    mesh.tangents.clear();
    return;
  }
  mesh.tangents = detail::uv_tangents(mesh.positions, mesh.normals, mesh.texcoords0, mesh.indices);
  mesh.tangents_generated = true;
}

namespace {

int shifted_index(int index, std::size_t by) {
  return index < 0 ? index : index + int(by);
}

}  // namespace

void append_scene(Scene& scene, const Scene& other) {
  const std::size_t nodes = scene.nodes.size(), materials = scene.materials.size();
  const std::size_t images = scene.images.size(), skins = scene.skins.size();
  int gltf_meshes = 0;
  for (const Node& node : scene.nodes) gltf_meshes = std::max(gltf_meshes, node.mesh + 1);
  for (Mesh mesh : other.meshes) {
    mesh.node = shifted_index(mesh.node, nodes);
    mesh.material = shifted_index(mesh.material, materials);
    mesh.skin = shifted_index(mesh.skin, skins);
    scene.meshes.push_back(std::move(mesh));
  }
  for (Material material : other.materials) {
    material.base_color_texture = shifted_index(material.base_color_texture, images);
    scene.materials.push_back(std::move(material));
  }
  scene.images.insert(scene.images.end(), other.images.begin(), other.images.end());
  for (Node node : other.nodes) {
    node.parent = shifted_index(node.parent, nodes);
    for (int& child : node.children) child = shifted_index(child, nodes);
    node.mesh = shifted_index(node.mesh, std::size_t(gltf_meshes));
    node.skin = shifted_index(node.skin, skins);
    scene.nodes.push_back(std::move(node));
  }
  for (Skin skin : other.skins) {
    for (int& joint : skin.joints) joint = shifted_index(joint, nodes);
    skin.skeleton = shifted_index(skin.skeleton, nodes);
    scene.skins.push_back(std::move(skin));
  }
  for (Animation animation : other.animations) {
    for (AnimationChannel& channel : animation.channels)
      channel.node = shifted_index(channel.node, nodes);
    scene.animations.push_back(std::move(animation));
  }
  for (ImportProblem problem : other.problems) {
    problem.node = shifted_index(problem.node, nodes);
    problem.mesh = shifted_index(problem.mesh, std::size_t(gltf_meshes));
    problem.material = shifted_index(problem.material, materials);
    scene.problems.push_back(std::move(problem));
  }
}

Scene import_scene(const std::string& path, const Context& ctx) {
  return import_scene(path, ctx, ImportOptions{});
}

Scene import_scene(const std::string& path, const Context& ctx, const ImportOptions& options) {
  const std::string ext = lower_extension(path);
  if (ext == "gltf" || ext == "glb") return detail::import_gltf(path, ctx, options);
  if (ext == "obj") return detail::import_obj(path, ctx);
  throw Error(path + ": unknown scene file extension '" + ext + "' (expected .gltf, .glb or .obj)");
}

namespace detail {

std::vector<glm::vec3> area_weighted_normals(const std::vector<glm::vec3>& positions,
                                             const std::vector<std::uint32_t>& indices) {
  std::vector<glm::dvec3> sum(positions.size(), glm::dvec3(0.0));
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::dvec3 a(positions[indices[t]]), b(positions[indices[t + 1]]),
        c(positions[indices[t + 2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);  // length = 2 x area: area weighting
    for (int k = 0; k < 3; ++k) sum[indices[t + k]] += n;
  }
  std::vector<glm::vec3> normals(positions.size());
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double len = glm::length(sum[i]);
    normals[i] = len > 0.0 ? glm::vec3(sum[i] / len) : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  return normals;
}

namespace {

glm::vec3 any_orthogonal(const glm::vec3& n) {
  const glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(n, glm::cross(axis, n)));
}

}  // namespace

std::vector<glm::vec4> uv_tangents(const std::vector<glm::vec3>& positions,
                                   const std::vector<glm::vec3>& normals,
                                   const std::vector<glm::vec2>& texcoords,
                                   const std::vector<std::uint32_t>& indices) {
  std::vector<glm::dvec3> tan(positions.size(), glm::dvec3(0.0));
  std::vector<glm::dvec3> bitan(positions.size(), glm::dvec3(0.0));
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::uint32_t i0 = indices[t], i1 = indices[t + 1], i2 = indices[t + 2];
    const glm::dvec3 e1 = glm::dvec3(positions[i1]) - glm::dvec3(positions[i0]);
    const glm::dvec3 e2 = glm::dvec3(positions[i2]) - glm::dvec3(positions[i0]);
    const glm::dvec2 d1 = glm::dvec2(texcoords[i1]) - glm::dvec2(texcoords[i0]);
    const glm::dvec2 d2 = glm::dvec2(texcoords[i2]) - glm::dvec2(texcoords[i0]);
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-20) continue;
    // Weighting the unnormalised dP/du by |det| gives area weighting in UV space; the sign of
    // det carries the orientation.
    const glm::dvec3 dpdu = (e1 * d2.y - e2 * d1.y) / det;
    const glm::dvec3 dpdv = (e2 * d1.x - e1 * d2.x) / det;
    const double area = glm::length(glm::cross(e1, e2));
    const double su = glm::length(dpdu), sv = glm::length(dpdv);
    if (su <= 0.0 || sv <= 0.0) continue;
    for (std::uint32_t i : {i0, i1, i2}) {
      tan[i] += dpdu / su * area;
      bitan[i] += dpdv / sv * area;
    }
  }
  std::vector<glm::vec4> tangents(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const glm::dvec3 n(normals[i]);
    glm::dvec3 t = tan[i] - n * glm::dot(n, tan[i]);
    const double len = glm::length(t);
    if (len < 1e-12) {
      tangents[i] = glm::vec4(any_orthogonal(normals[i]), 1.0f);
      continue;
    }
    t /= len;
    // glTF: bitangent = cross(normal, tangent) * w points to image up, i.e. decreasing v.
    const double handedness = glm::dot(glm::cross(n, t), -bitan[i]) < 0.0 ? -1.0 : 1.0;
    tangents[i] = glm::vec4(glm::vec3(t), static_cast<float>(handedness));
  }
  return tangents;
}

void validate_mesh(const Mesh& mesh, const std::string& file, const std::string& what) {
  const std::size_t n = mesh.positions.size();
  if (mesh.indices.size() % 3 != 0) {
    throw Error(file + ": " + what + " has " + std::to_string(mesh.indices.size()) +
                " indices, not a multiple of 3");
  }
  if (mesh.indices.empty() || n == 0) throw Error(file + ": " + what + " is empty (no triangles)");
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= n) {
      throw Error(file + ": " + what + ": index " + std::to_string(mesh.indices[i]) +
                  " at position " + std::to_string(i) + " is out of range (" + std::to_string(n) +
                  " vertices)");
    }
  }
  auto check = [&](std::size_t size, const char* name) {
    if (size != 0 && size != n) {
      throw Error(file + ": " + what + ": " + name + " has " + std::to_string(size) +
                  " entries for " + std::to_string(n) + " vertices");
    }
  };
  check(mesh.normals.size(), "NORMAL");
  check(mesh.tangents.size(), "TANGENT");
  check(mesh.texcoords0.size(), "TEXCOORD_0");
  check(mesh.colors0.size(), "COLOR_0");
  check(mesh.joints0.size(), "JOINTS_0");
  check(mesh.weights0.size(), "WEIGHTS_0");
  for (const glm::vec3& p : mesh.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      throw Error(file + ": " + what + " has a non-finite vertex position");
    }
  }
}

void complete_mesh_attributes(Mesh& mesh) {
  if (mesh.local_positions.empty()) mesh.local_positions = mesh.positions;
  if (mesh.normals.empty()) {
    mesh.normals = area_weighted_normals(mesh.positions, mesh.indices);
    mesh.local_normals = area_weighted_normals(mesh.local_positions, mesh.indices);
    mesh.normals_generated = true;
  } else {
    // Normalise what the file gave (and repair zero normals with the generated ones).
    std::vector<glm::vec3> fallback;
    for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
      const float len = glm::length(mesh.normals[i]);
      if (len > 1e-20f && std::isfinite(len)) {
        mesh.normals[i] /= len;
      } else {
        if (fallback.empty()) fallback = area_weighted_normals(mesh.positions, mesh.indices);
        mesh.normals[i] = fallback[i];
      }
    }
    if (mesh.local_normals.empty()) mesh.local_normals = mesh.normals;
  }
  if (mesh.tangents.empty() && !mesh.texcoords0.empty()) {
    mesh.tangents = uv_tangents(mesh.positions, mesh.normals, mesh.texcoords0, mesh.indices);
    mesh.tangents_generated = true;
  }
}

}  // namespace detail
}  // namespace prt::bake
