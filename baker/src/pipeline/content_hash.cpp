// SPDX-License-Identifier: MIT
// Cache keys of the content pipeline (content_hash.hpp).
#include "content_hash.hpp"

#include <xxhash.h>

#include <cstdio>
#include <fstream>
#include <set>

#include "prt/baker/context.hpp"

namespace prt::bake {

ContentHash::ContentHash() : state_(XXH3_createState()) {
  if (!state_ || XXH3_128bits_reset(static_cast<XXH3_state_t*>(state_)) != XXH_OK)
    throw Error("content hash: cannot start a hash");
}

ContentHash::~ContentHash() {
  XXH3_freeState(static_cast<XXH3_state_t*>(state_));
}

ContentHash& ContentHash::bytes(const void* data, std::size_t size) {
  if (size > 0) XXH3_128bits_update(static_cast<XXH3_state_t*>(state_), data, size);
  return *this;
}

ContentHash& ContentHash::text(const std::string& value) {
  this->value(value.size());
  return bytes(value.data(), value.size());
}

std::string ContentHash::hex() const {
  const XXH128_hash_t h = XXH3_128bits_digest(static_cast<XXH3_state_t*>(state_));
  char out[33];
  std::snprintf(out, sizeof out, "%016llx%016llx", static_cast<unsigned long long>(h.high64),
                static_cast<unsigned long long>(h.low64));
  return out;
}

namespace {

void hash_mesh(ContentHash& hash, const Mesh& mesh) {
  hash.text(mesh.name).value(mesh.material).value(mesh.skin);
  hash.values(mesh.positions).values(mesh.normals).values(mesh.tangents);
  hash.values(mesh.local_positions).values(mesh.local_normals);
  hash.values(mesh.texcoords0).values(mesh.colors0).values(mesh.joints0).values(mesh.weights0);
  hash.values(mesh.indices);
}

void hash_material(ContentHash& hash, const Material& m) {
  hash.text(m.name).value(m.base_color).value(m.base_color_texture).value(m.base_color_texcoord);
  hash.value(m.base_color_uv_transform).value(m.double_sided);
  hash.value(m.sheen).value(m.sheen_color).value(m.sheen_roughness).value(m.cloth);
}

void hash_node(ContentHash& hash, const Node& node) {
  hash.text(node.name).value(node.world).value(node.skin).value(node.animated);
  hash.value(node.hints.dynamic).text(node.hints.technique).value(node.hints.skip);
  hash.value(node.hints.settings.size());
  for (const auto& [key, value] : node.hints.settings) hash.text(key).text(value);
}

// The node, its ancestors, and for a skinned node its joints and theirs: the nodes whose
// transforms place or pose the object.
std::set<int> placing_nodes(const Scene& scene, int node) {
  std::set<int> nodes;
  const auto add_with_ancestors = [&](int n) {
    for (; n >= 0 && nodes.insert(n).second; n = scene.nodes.at(std::size_t(n)).parent) {
    }
  };
  add_with_ancestors(node);
  const int skin = scene.nodes.at(std::size_t(node)).skin;
  if (skin >= 0 && std::size_t(skin) < scene.skins.size()) {
    for (const int joint : scene.skins[std::size_t(skin)].joints) add_with_ancestors(joint);
  }
  return nodes;
}

void hash_channel(ContentHash& hash, const AnimationChannel& channel) {
  hash.value(channel.node).value(channel.path).value(channel.interpolation);
  hash.value(channel.components).values(channel.times).values(channel.values);
}

// The skin and every animation channel that moves a placing node: what poses and moves it.
void hash_motion(ContentHash& hash, const Scene& scene, int node) {
  const std::set<int> nodes = placing_nodes(scene, node);
  for (const int n : nodes) {
    const Node& placing = scene.nodes[std::size_t(n)];
    hash.value(n).value(placing.parent).value(placing.local).value(placing.world);
  }
  const int skin = scene.nodes.at(std::size_t(node)).skin;
  if (skin >= 0 && std::size_t(skin) < scene.skins.size()) {
    const Skin& s = scene.skins[std::size_t(skin)];
    hash.values(s.joints).values(s.inverse_bind).value(s.skeleton);
  }
  for (std::size_t a = 0; a < scene.animations.size(); ++a) {
    const Animation& animation = scene.animations[a];
    for (const AnimationChannel& channel : animation.channels) {
      if (!nodes.count(channel.node)) continue;
      hash.value(a).text(animation.name).value(animation.duration);
      hash_channel(hash, channel);
    }
  }
}

}  // namespace

void hash_object_scene(ContentHash& hash, const Scene& scene, int node) {
  hash_node(hash, scene.nodes.at(static_cast<std::size_t>(node)));
  hash_motion(hash, scene, node);
  hash.value(scene.meshes.size());
  for (const Mesh& mesh : scene.meshes) hash_mesh(hash, mesh);
  hash.value(scene.occluders.size());
  for (const Mesh& occluder : scene.occluders)
    hash.values(occluder.positions).values(occluder.indices);
  hash.value(scene.materials.size());
  for (const Material& material : scene.materials) hash_material(hash, material);
  hash.value(scene.images.size());
  for (const Image& image : scene.images) {
    hash.text(image.name).value(image.width).value(image.height).values(image.rgba);
  }
}

std::string file_hash(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(path + ": cannot read");
  ContentHash hash;
  std::vector<char> buffer(1 << 16);
  while (file.read(buffer.data(), std::streamsize(buffer.size())) || file.gcount() > 0) {
    hash.bytes(buffer.data(), std::size_t(file.gcount()));
  }
  return hash.hex();
}

}  // namespace prt::bake
