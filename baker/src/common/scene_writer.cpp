// SPDX-License-Identifier: MIT
// Writers for the demo assets: a static Scene as binary glTF (through tinygltf) and an EnvMap
// as Radiance .hdr (through stb).
#include <cstring>

#include <stb_image_write.h>
#include <tiny_gltf.h>

#include "prt/baker/demo_scene.hpp"

namespace prt::bake {
namespace {

// Appends raw bytes to buffer 0 (4-byte aligned) and returns a new bufferView index.
int append_view(tinygltf::Model& model, const void* data, std::size_t bytes, int target) {
  auto& buffer = model.buffers[0].data;
  buffer.resize((buffer.size() + 3) & ~std::size_t(3));
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = bytes;
  view.target = target;
  buffer.resize(buffer.size() + bytes);
  std::memcpy(buffer.data() + view.byteOffset, data, bytes);
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size()) - 1;
}

int append_vec3_accessor(tinygltf::Model& model, const std::vector<glm::vec3>& values,
                         bool with_bounds) {
  tinygltf::Accessor accessor;
  accessor.bufferView = append_view(model, values.data(), values.size() * sizeof(glm::vec3),
                                    TINYGLTF_TARGET_ARRAY_BUFFER);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.type = TINYGLTF_TYPE_VEC3;
  accessor.count = values.size();
  if (with_bounds && !values.empty()) {  // glTF requires min/max on POSITION
    glm::vec3 lo = values[0], hi = values[0];
    for (const glm::vec3& v : values) lo = glm::min(lo, v), hi = glm::max(hi, v);
    accessor.minValues = {lo.x, lo.y, lo.z};
    accessor.maxValues = {hi.x, hi.y, hi.z};
  }
  model.accessors.push_back(accessor);
  return int(model.accessors.size()) - 1;
}

int append_index_accessor(tinygltf::Model& model, const std::vector<std::uint32_t>& indices) {
  tinygltf::Accessor accessor;
  accessor.bufferView = append_view(model, indices.data(), indices.size() * sizeof(std::uint32_t),
                                    TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  accessor.type = TINYGLTF_TYPE_SCALAR;
  accessor.count = indices.size();
  model.accessors.push_back(accessor);
  return int(model.accessors.size()) - 1;
}

}  // namespace

void write_glb(const Scene& scene, const std::string& path) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "prtkit";
  model.buffers.resize(1);
  for (const Material& source : scene.materials) {
    tinygltf::Material material;
    material.name = source.name;
    const glm::vec4& c = source.base_color;
    material.pbrMetallicRoughness.baseColorFactor = {c.r, c.g, c.b, c.a};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 1.0;
    model.materials.push_back(material);
  }
  tinygltf::Scene gltf_scene;
  for (const Mesh& source : scene.meshes) {
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.material = source.material;
    primitive.attributes["POSITION"] = append_vec3_accessor(model, source.positions, true);
    if (!source.normals.empty())
      primitive.attributes["NORMAL"] = append_vec3_accessor(model, source.normals, false);
    primitive.indices = append_index_accessor(model, source.indices);
    tinygltf::Mesh mesh;
    mesh.name = source.name;
    mesh.primitives.push_back(primitive);
    model.meshes.push_back(mesh);
    tinygltf::Node node;
    node.name = source.name;
    node.mesh = int(model.meshes.size()) - 1;
    model.nodes.push_back(node);
    gltf_scene.nodes.push_back(int(model.nodes.size()) - 1);
  }
  model.scenes.push_back(gltf_scene);
  model.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&model, path, /*embedImages=*/true, /*embedBuffers=*/true,
                                   /*prettyPrint=*/false, /*writeBinary=*/true))
    throw Error(path + ": cannot write the glTF file");
}

void write_envmap_hdr(const io::EnvMap& env, const std::string& path) {
  if (!stbi_write_hdr(path.c_str(), env.width(), env.height(), 3, env.pixels().data()))
    throw Error(path + ": cannot write the .hdr file");
}

}  // namespace prt::bake
