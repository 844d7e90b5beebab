// SPDX-License-Identifier: MIT
// glTF 2.0 → Scene: images, materials, the node hierarchy (with its extras.prt hints), skins,
// animations and one Mesh per primitive instance (a primitive reached through two nodes gives
// two meshes), in world space.
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/gtx/matrix_decompose.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include "gltf_model.hpp"
#include "import_detail.hpp"
#include "prt/baker/animation.hpp"

namespace prt::bake::detail {
namespace {

// ---- images and materials -------------------------------------------------------------------

Image convert_image(const tinygltf::Image& source, std::size_t index) {
  Image image;
  image.name = source.name.empty() ? source.uri : source.name;
  if (source.width <= 0 || source.height <= 0 || source.component < 1 || source.component > 4 ||
      (source.bits != 8 && source.bits != 16)) {
    image.name += " (image " + std::to_string(index) + " not decoded)";
    return image;
  }
  const std::size_t pixels = static_cast<std::size_t>(source.width) * source.height;
  const std::size_t bytes_per_channel = source.bits / 8;
  if (source.image.size() < pixels * source.component * bytes_per_channel) return image;
  image.width = source.width;
  image.height = source.height;
  image.rgba.assign(pixels * 4, 255);
  for (std::size_t p = 0; p < pixels; ++p) {
    for (int c = 0; c < source.component; ++c) {
      const std::size_t at = (p * source.component + c) * bytes_per_channel;
      // 16-bit PNG data is stored little-endian by tinygltf: keep the high byte.
      const std::uint8_t value = bytes_per_channel == 1 ? source.image[at] : source.image[at + 1];
      if (source.component <= 2 && c == 0) {
        image.rgba[p * 4] = image.rgba[p * 4 + 1] = image.rgba[p * 4 + 2] = value;  // grey
      } else if (source.component == 2) {
        image.rgba[p * 4 + 3] = value;  // grey + alpha
      } else {
        image.rgba[p * 4 + c] = value;
      }
    }
  }
  return image;
}

double number_at(const tinygltf::Value& array, int i, double fallback) {
  if (!array.IsArray() || i >= static_cast<int>(array.ArrayLen())) return fallback;
  const tinygltf::Value& v = array.Get(i);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

// KHR_texture_transform on the base colour texture: uv' = T * R * S * uv.
glm::mat3 texture_transform(const tinygltf::ExtensionMap& extensions, int* texcoord) {
  const auto it = extensions.find("KHR_texture_transform");
  if (it == extensions.end() || !it->second.IsObject()) return glm::mat3(1.0f);
  const tinygltf::Value& ext = it->second;
  const tinygltf::Value offset = ext.Get("offset"), scale = ext.Get("scale");
  const tinygltf::Value rotation = ext.Get("rotation");
  const float r = rotation.IsNumber() ? static_cast<float>(rotation.GetNumberAsDouble()) : 0.0f;
  if (ext.Has("texCoord") && ext.Get("texCoord").IsInt())
    *texcoord = ext.Get("texCoord").Get<int>();
  glm::mat3 t(1.0f), rot(1.0f), s(1.0f);
  t[2] = glm::vec3(number_at(offset, 0, 0.0), number_at(offset, 1, 0.0), 1.0f);
  rot[0] = glm::vec3(std::cos(r), std::sin(r), 0.0f);  // columns, as in the extension's GLSL
  rot[1] = glm::vec3(-std::sin(r), std::cos(r), 0.0f);
  s[0][0] = static_cast<float>(number_at(scale, 0, 1.0));
  s[1][1] = static_cast<float>(number_at(scale, 1, 1.0));
  return t * rot * s;
}

// ---- extras.prt and KHR_materials_sheen ------------------------------------------------------
// Hints for `prt-bake scene` (docs/pipeline.md). A malformed hint is the artist's slip, not a
// broken file: it is reported and ignored so the rest of the scene still imports.

// "<file>: node 3 'cape'": who a warning is about.
std::string subject(const std::string& file, const char* kind, std::size_t index,
                    const std::string& name) {
  return file + ": " + kind + " " + std::to_string(index) + " '" + name + "'";
}

// The object under extras.prt, or null when there is none (extras without "prt" are the file's
// business, not ours) or it is not an object (then a warning).
const tinygltf::Value* prt_extras(const tinygltf::Value& extras, const std::string& who,
                                  const Context& ctx) {
  if (!extras.Has("prt")) return nullptr;
  const tinygltf::Value& prt = extras.Get("prt");
  if (!prt.IsObject()) {
    ctx.warn(who + ": extras.prt should be an object; ignored");
    return nullptr;
  }
  return &prt;
}

void wrong_type(const std::string& who, const std::string& key, const char* expected,
                const Context& ctx) {
  ctx.warn(who + ": extras.prt." + key + " should be " + expected + "; ignored");
}

void unknown_key(const std::string& who, const std::string& key, const char* known,
                 const Context& ctx) {
  ctx.warn(who + ": extras.prt has the unknown key '" + key + "' (known: " + known + "); ignored");
}

// The shortest text that reads back as the same number ("4", "0.5", "1e+20"), independent of
// the C locale, so a setting reaches the technique's option parser as the artist wrote it.
std::string number_text(const tinygltf::Value& value) {
  if (value.IsInt()) return std::to_string(value.Get<int>());
  char text[32];
  const auto end = std::to_chars(text, text + sizeof(text), value.GetNumberAsDouble()).ptr;
  return std::string(text, end);
}

// extras.prt.settings: each entry becomes an option and its argument, {"rays_per_vertex": 64}
// -> {"--rays-per-vertex", "64"}, in tinygltf's (alphabetical) key order.
void read_settings(const tinygltf::Value& settings, const std::string& who, const Context& ctx,
                   std::vector<std::pair<std::string, std::string>>& out) {
  if (!settings.IsObject()) return wrong_type(who, "settings", "an object", ctx);
  for (const std::string& key : settings.Keys()) {
    const tinygltf::Value& value = settings.Get(key);
    std::string option = "--" + key;
    std::replace(option.begin(), option.end(), '_', '-');
    if (key.empty()) {
      ctx.warn(who + ": extras.prt.settings has an empty key; ignored");
    } else if (value.IsNumber()) {
      out.emplace_back(option, number_text(value));
    } else if (value.IsString()) {
      out.emplace_back(option, value.Get<std::string>());
    } else if (value.IsBool()) {
      out.emplace_back(option, value.Get<bool>() ? "true" : "false");
    } else {
      wrong_type(who, "settings." + key, "a number, string or boolean", ctx);
    }
  }
}

void read_node_hints(const tinygltf::Value& extras, const std::string& who, const Context& ctx,
                     Node::Hints& hints) {
  const tinygltf::Value* prt = prt_extras(extras, who, ctx);
  if (!prt) return;
  for (const std::string& key : prt->Keys()) {
    const tinygltf::Value& value = prt->Get(key);
    if (key == "dynamic" || key == "skip") {
      if (!value.IsBool()) {
        wrong_type(who, key, "true or false", ctx);
      } else {
        (key == "dynamic" ? hints.dynamic : hints.skip) = value.Get<bool>();
      }
    } else if (key == "technique") {
      if (!value.IsString()) {
        wrong_type(who, key, "a string", ctx);
      } else {
        hints.technique = value.Get<std::string>();
      }
    } else if (key == "settings") {
      read_settings(value, who, ctx, hints.settings);
    } else {
      unknown_key(who, key, "dynamic, technique, settings, skip", ctx);
    }
  }
}

void read_material_extras(const tinygltf::Value& extras, const std::string& who, const Context& ctx,
                          Material& material) {
  const tinygltf::Value* prt = prt_extras(extras, who, ctx);
  if (!prt) return;
  for (const std::string& key : prt->Keys()) {
    const tinygltf::Value& value = prt->Get(key);
    if (key != "cloth") {
      unknown_key(who, key, "cloth", ctx);
    } else if (!value.IsBool()) {
      wrong_type(who, key, "true or false", ctx);
    } else {
      material.cloth = value.Get<bool>();
    }
  }
}

// KHR_materials_sheen's factors (the extension's defaults: black, roughness 0). Its textures
// would modulate them per texel; only the factors are carried, so say so once.
void read_sheen(const tinygltf::ExtensionMap& extensions, const std::string& who,
                const Context& ctx, Material& material) {
  const auto it = extensions.find("KHR_materials_sheen");
  if (it == extensions.end() || !it->second.IsObject()) return;
  const tinygltf::Value& sheen = it->second;
  material.sheen = true;
  const tinygltf::Value& color = sheen.Get("sheenColorFactor");
  if (color.IsArray() && color.ArrayLen() == 3 && color.Get(0).IsNumber() &&
      color.Get(1).IsNumber() && color.Get(2).IsNumber()) {
    for (int c = 0; c < 3; ++c) {
      material.sheen_color[c] = static_cast<float>(color.Get(c).GetNumberAsDouble());
    }
  } else if (sheen.Has("sheenColorFactor")) {
    ctx.warn(who + ": KHR_materials_sheen sheenColorFactor is not three numbers; black used");
  }
  const tinygltf::Value& roughness = sheen.Get("sheenRoughnessFactor");
  if (roughness.IsNumber()) {
    material.sheen_roughness = static_cast<float>(roughness.GetNumberAsDouble());
  } else if (sheen.Has("sheenRoughnessFactor")) {
    ctx.warn(who + ": KHR_materials_sheen sheenRoughnessFactor is not a number; 0 used");
  }
  std::string textures;
  for (const char* name : {"sheenColorTexture", "sheenRoughnessTexture"}) {
    if (sheen.Has(name)) textures += (textures.empty() ? "" : " and ") + std::string(name);
  }
  if (!textures.empty()) {
    ctx.warn(who + ": KHR_materials_sheen " + textures +
             " ignored; the sheen colour and roughness factors are used");
  }
}

Material convert_material(const tinygltf::Model& model, const tinygltf::Material& source,
                          const std::string& who, const Context& ctx) {
  Material material;
  material.name = source.name;
  read_sheen(source.extensions, who, ctx, material);
  read_material_extras(source.extras, who, ctx, material);
  const auto& pbr = source.pbrMetallicRoughness;
  for (int c = 0; c < 4 && c < static_cast<int>(pbr.baseColorFactor.size()); ++c) {
    material.base_color[c] = static_cast<float>(pbr.baseColorFactor[c]);
  }
  material.double_sided = source.doubleSided;
  const int texture = pbr.baseColorTexture.index;
  if (texture >= 0 && static_cast<std::size_t>(texture) < model.textures.size()) {
    const int image = model.textures[texture].source;
    if (image >= 0 && static_cast<std::size_t>(image) < model.images.size()) {
      material.base_color_texture = image;
      material.base_color_texcoord = pbr.baseColorTexture.texCoord;
      material.base_color_uv_transform =
          texture_transform(pbr.baseColorTexture.extensions, &material.base_color_texcoord);
    }
  }
  return material;
}

// ---- nodes -----------------------------------------------------------------------------------

Node convert_node(const tinygltf::Node& source) {
  Node node;
  node.name = source.name;
  node.mesh = source.mesh;
  node.skin = source.skin;
  node.children = source.children;
  if (source.matrix.size() == 16) {
    double m[16];
    std::copy(source.matrix.begin(), source.matrix.end(), m);
    node.local = glm::mat4(glm::make_mat4(m));
    glm::vec3 skew;
    glm::vec4 perspective;
    glm::decompose(node.local, node.scale, node.rotation, node.translation, skew, perspective);
  } else {
    if (source.translation.size() == 3) {
      node.translation =
          glm::vec3(source.translation[0], source.translation[1], source.translation[2]);
    }
    if (source.rotation.size() == 4) {  // glTF stores x, y, z, w
      node.rotation = glm::normalize(glm::quat(
          static_cast<float>(source.rotation[3]), static_cast<float>(source.rotation[0]),
          static_cast<float>(source.rotation[1]), static_cast<float>(source.rotation[2])));
    }
    if (source.scale.size() == 3) {
      node.scale = glm::vec3(source.scale[0], source.scale[1], source.scale[2]);
    }
    node.local = glm::translate(glm::mat4(1.0f), node.translation) * glm::mat4_cast(node.rotation) *
                 glm::scale(glm::mat4(1.0f), node.scale);
  }
  return node;
}

void link_nodes(std::vector<Node>& nodes, const std::string& file) {
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (int child : nodes[i].children) {
      if (child < 0 || static_cast<std::size_t>(child) >= nodes.size()) {
        throw Error(file + ": node " + std::to_string(i) + " has a child " + std::to_string(child) +
                    " that does not exist");
      }
      if (nodes[child].parent >= 0 || static_cast<std::size_t>(child) == i) {
        throw Error(file + ": node " + std::to_string(child) +
                    " has more than one parent (the node graph is not a tree)");
      }
      nodes[child].parent = static_cast<int>(i);
    }
  }
  // World transforms, parents first; a cycle leaves nodes unvisited.
  std::vector<bool> done(nodes.size(), false);
  std::function<void(int)> visit = [&](int n) {
    nodes[n].world =
        nodes[n].parent >= 0 ? nodes[nodes[n].parent].world * nodes[n].local : nodes[n].local;
    done[n] = true;
    for (int child : nodes[n].children) visit(child);
  };
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].parent < 0) visit(static_cast<int>(i));
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!done[i]) throw Error(file + ": node " + std::to_string(i) + " is part of a cycle");
  }
}

// ---- skins and animations ---------------------------------------------------------------------

Skin convert_skin(const tinygltf::Model& model, const tinygltf::Skin& source, std::size_t index,
                  const std::string& file) {
  Skin skin;
  skin.name = source.name;
  skin.skeleton = source.skeleton;
  const std::string id = "skin " + std::to_string(index);
  for (int joint : source.joints) {
    if (joint < 0 || static_cast<std::size_t>(joint) >= model.nodes.size()) {
      throw Error(file + ": " + id + " names joint node " + std::to_string(joint) +
                  ", which does not exist");
    }
  }
  if (skin.skeleton >= static_cast<int>(model.nodes.size())) {
    throw Error(file + ": " + id + " has a skeleton node that does not exist");
  }
  skin.joints = source.joints;
  skin.inverse_bind.assign(skin.joints.size(), glm::mat4(1.0f));
  if (source.inverseBindMatrices >= 0) {
    const AccessorData data = read_accessor(model, source.inverseBindMatrices, true, file,
                                            id + " inverseBindMatrices", {16});
    if (data.count < skin.joints.size()) {
      throw Error(file + ": " + id + " has " + std::to_string(data.count) +
                  " inverse bind matrices for " + std::to_string(skin.joints.size()) + " joints");
    }
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      skin.inverse_bind[j] = glm::mat4(glm::make_mat4(data.element(j)));
    }
  }
  return skin;
}

AnimationChannel::Path channel_path(const std::string& path, bool* known) {
  *known = true;
  if (path == "translation") return AnimationChannel::Path::Translation;
  if (path == "rotation") return AnimationChannel::Path::Rotation;
  if (path == "scale") return AnimationChannel::Path::Scale;
  if (path == "weights") return AnimationChannel::Path::Weights;
  *known = false;
  return AnimationChannel::Path::Translation;
}

Animation convert_animation(const tinygltf::Model& model, const tinygltf::Animation& source,
                            std::size_t index, const std::string& file, const Context& ctx) {
  Animation animation;
  animation.name = source.name;
  const std::string id = "animation " + std::to_string(index);
  for (std::size_t c = 0; c < source.channels.size(); ++c) {
    const tinygltf::AnimationChannel& channel = source.channels[c];
    const std::string what = id + " channel " + std::to_string(c);
    bool known = false;
    AnimationChannel out;
    out.path = channel_path(channel.target_path, &known);
    if (!known) {
      ctx.warn(file + ": " + what + " animates '" + channel.target_path + "'; ignored");
      continue;
    }
    if (channel.target_node < 0 ||
        static_cast<std::size_t>(channel.target_node) >= model.nodes.size()) {
      throw Error(file + ": " + what + " targets a node that does not exist");
    }
    if (channel.sampler < 0 ||
        static_cast<std::size_t>(channel.sampler) >= source.samplers.size()) {
      throw Error(file + ": " + what + " uses a sampler that does not exist");
    }
    const tinygltf::AnimationSampler& sampler = source.samplers[channel.sampler];
    out.node = channel.target_node;
    if (sampler.interpolation == "STEP") {
      out.interpolation = AnimationChannel::Interpolation::Step;
    } else if (sampler.interpolation == "CUBICSPLINE") {
      out.interpolation = AnimationChannel::Interpolation::CubicSpline;
    } else {
      out.interpolation = AnimationChannel::Interpolation::Linear;
    }
    const AccessorData times =
        read_accessor(model, sampler.input, true, file, what + " input", {1});
    const AccessorData values = read_accessor(model, sampler.output, true, file, what + " output");
    out.times.assign(times.values.begin(), times.values.end());
    out.values.assign(values.values.begin(), values.values.end());
    const std::size_t keys = out.times.size();
    const std::size_t per_key =
        out.interpolation == AnimationChannel::Interpolation::CubicSpline ? 3 : 1;
    if (keys == 0 || out.values.size() % (keys * per_key) != 0) {
      throw Error(file + ": " + what + ": " + std::to_string(out.values.size()) +
                  " output values do not fit " + std::to_string(keys) + " keyframes");
    }
    out.components = static_cast<int>(out.values.size() / (keys * per_key));
    const int expected = out.path == AnimationChannel::Path::Rotation ? 4 : 3;
    if (out.path != AnimationChannel::Path::Weights && out.components != expected) {
      throw Error(file + ": " + what + " has " + std::to_string(out.components) +
                  " components per key, expected " + std::to_string(expected));
    }
    if (!std::is_sorted(out.times.begin(), out.times.end())) {
      throw Error(file + ": " + what + ": keyframe times are not ascending");
    }
    animation.duration = std::max(animation.duration, out.times.back());
    animation.channels.push_back(std::move(out));
  }
  return animation;
}

// Marks the nodes a translation, rotation or scale channel moves, and everything under them (a
// weights channel only deforms the mesh in place). The tree is checked acyclic by link_nodes.
void mark_animated(Scene& scene) {
  std::function<void(int)> mark = [&](int n) {
    if (scene.nodes[n].animated) return;  // its subtree is already marked
    scene.nodes[n].animated = true;
    for (int child : scene.nodes[n].children) mark(child);
  };
  for (const Animation& animation : scene.animations) {
    for (const AnimationChannel& channel : animation.channels) {
      if (channel.path != AnimationChannel::Path::Weights) mark(channel.node);
    }
  }
}

// ---- meshes ------------------------------------------------------------------------------------

std::vector<std::uint32_t> triangle_indices(const std::vector<std::uint32_t>& raw, int mode) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return raw;
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i + 2 < raw.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {  // keep the winding of every other triangle
      out.insert(out.end(), {raw[i], raw[i + 1 + i % 2], raw[i + 2 - i % 2]});
    } else {  // TRIANGLE_FAN
      out.insert(out.end(), {raw[i + 1], raw[i + 2], raw[0]});
    }
  }
  return out;
}

template <typename T, int N>
std::vector<T> to_vectors(const AccessorData& data) {
  std::vector<T> out(data.count, T(0));
  for (std::size_t i = 0; i < data.count; ++i) {
    for (int c = 0; c < N && c < data.components; ++c) {
      out[i][c] = static_cast<typename T::value_type>(data.element(i)[c]);
    }
  }
  return out;
}

struct PrimitiveRef {
  int mesh, primitive;
  std::string what;  // "mesh 0 'Fox' primitive 0"
};

// Reads the primitive's attributes (mesh-local) and indices.
Mesh read_primitive(const tinygltf::Model& model, const PrimitiveRef& ref,
                    const std::string& file) {
  const tinygltf::Primitive& primitive = model.meshes[ref.mesh].primitives[ref.primitive];
  const auto attribute = [&](const char* name) {
    const auto it = primitive.attributes.find(name);
    return it == primitive.attributes.end() ? -1 : it->second;
  };
  Mesh mesh;
  mesh.name = model.meshes[ref.mesh].name;
  if (model.meshes[ref.mesh].primitives.size() > 1)
    mesh.name += "#" + std::to_string(ref.primitive);
  const int position = attribute("POSITION");
  if (position < 0) throw Error(file + ": " + ref.what + " has no POSITION attribute");
  mesh.local_positions = to_vectors<glm::vec3, 3>(
      read_accessor(model, position, true, file, ref.what + " POSITION", {3}));
  const std::size_t n = mesh.local_positions.size();
  auto read = [&](const char* name, std::vector<int> components) {
    return read_accessor(model, attribute(name), true, file, ref.what + " " + name, components);
  };
  if (attribute("NORMAL") >= 0) mesh.local_normals = to_vectors<glm::vec3, 3>(read("NORMAL", {3}));
  if (attribute("TANGENT") >= 0) mesh.tangents = to_vectors<glm::vec4, 4>(read("TANGENT", {4}));
  if (attribute("TEXCOORD_0") >= 0) {
    mesh.texcoords0 = to_vectors<glm::vec2, 2>(read("TEXCOORD_0", {2}));
  }
  if (attribute("COLOR_0") >= 0) {
    const AccessorData colors = read("COLOR_0", {3, 4});
    mesh.colors0 = to_vectors<glm::vec4, 4>(colors);
    if (colors.components == 3) {
      for (glm::vec4& c : mesh.colors0) c.a = 1.0f;
    }
  }
  if (attribute("JOINTS_0") >= 0 && attribute("WEIGHTS_0") >= 0) {
    const AccessorData joints =
        read_accessor(model, attribute("JOINTS_0"), false, file, ref.what + " JOINTS_0", {4});
    mesh.joints0.resize(joints.count);
    for (std::size_t i = 0; i < joints.count; ++i) {
      for (int c = 0; c < 4; ++c) {
        const double j = joints.element(i)[c];
        if (j < 0 || j > 65535) throw Error(file + ": " + ref.what + " JOINTS_0 out of range");
        mesh.joints0[i][c] = static_cast<std::uint16_t>(j);
      }
    }
    mesh.weights0 = to_vectors<glm::vec4, 4>(read("WEIGHTS_0", {4}));
  }
  const auto check_count = [&](std::size_t size, const char* name) {
    if (size != 0 && size != n) {
      throw Error(file + ": " + ref.what + ": " + name + " has " + std::to_string(size) +
                  " entries but POSITION has " + std::to_string(n));
    }
  };
  check_count(mesh.local_normals.size(), "NORMAL");
  check_count(mesh.tangents.size(), "TANGENT");
  check_count(mesh.texcoords0.size(), "TEXCOORD_0");
  check_count(mesh.colors0.size(), "COLOR_0");
  check_count(mesh.joints0.size(), "JOINTS_0");
  check_count(mesh.weights0.size(), "WEIGHTS_0");
  std::vector<std::uint32_t> raw;
  if (primitive.indices >= 0) {
    const AccessorData indices =
        read_accessor(model, primitive.indices, false, file, ref.what + " indices", {1});
    raw.resize(indices.count);
    for (std::size_t i = 0; i < indices.count; ++i) {
      const double v = indices.values[i];
      if (v < 0 || v >= static_cast<double>(n)) {
        throw Error(file + ": " + ref.what + ": index " +
                    std::to_string(static_cast<long long>(v)) + " at position " +
                    std::to_string(i) + " is out of range (" + std::to_string(n) + " vertices)");
      }
      raw[i] = static_cast<std::uint32_t>(v);
    }
  } else {
    raw.resize(n);
    for (std::size_t i = 0; i < n; ++i) raw[i] = static_cast<std::uint32_t>(i);
  }
  mesh.indices = triangle_indices(raw, primitive.mode);
  if (mesh.local_normals.size() != 0) mesh.normals = mesh.local_normals;
  return mesh;
}

// World placement: the node's transform, or for a skinned mesh each vertex blended by its joints
// at their rest (node default) transforms.
void place_in_world(Mesh& mesh, const Scene& scene, const glm::mat4& node_world) {
  const bool skinned = mesh.skin >= 0;
  std::vector<glm::mat4> joints;
  if (skinned) {
    std::vector<glm::mat4> rest_world;
    for (const Node& node : scene.nodes) rest_world.push_back(node.world);
    joints = joint_matrices(scene.skins[mesh.skin], rest_world);
  }
  const std::size_t n = mesh.local_positions.size();
  mesh.positions.resize(n);
  if (!mesh.local_normals.empty()) mesh.normals.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::mat4 m =
        skinned ? blend_joints(mesh.joints0[i], mesh.weights0[i], joints, node_world) : node_world;
    mesh.positions[i] = glm::vec3(m * glm::vec4(mesh.local_positions[i], 1.0f));
    const glm::mat3 linear(m);
    if (!mesh.local_normals.empty()) {
      mesh.normals[i] = glm::inverseTranspose(linear) * mesh.local_normals[i];
    }
    if (!mesh.tangents.empty()) {
      const glm::vec3 t = linear * glm::vec3(mesh.tangents[i]);
      const float len = glm::length(t);
      const float sign = glm::determinant(linear) < 0.0f ? -1.0f : 1.0f;
      mesh.tangents[i] = glm::vec4(len > 0.0f ? t / len : t, mesh.tangents[i].w * sign);
    }
  }
  // A mirroring transform turns the winding around: glTF asks to flip it back.
  if (!skinned && glm::determinant(glm::mat3(node_world)) < 0.0f) {
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
    }
  }
}

// One primitive of a node's mesh, read, placed in the world and completed; Error when unusable.
Mesh import_primitive(const tinygltf::Model& model, const Scene& scene, int node_index,
                      const PrimitiveRef& ref, const std::string& file, const Context& ctx) {
  const Node& node = scene.nodes[node_index];
  const tinygltf::Primitive& primitive = model.meshes[ref.mesh].primitives[ref.primitive];
  Mesh mesh = read_primitive(model, ref, file);
  mesh.node = node_index;
  if (primitive.material >= 0) {
    if (static_cast<std::size_t>(primitive.material) >= scene.materials.size()) {
      throw Error(file + ": " + ref.what + " uses material " + std::to_string(primitive.material) +
                  ", which does not exist");
    }
    mesh.material = primitive.material;
  }
  if (node.skin >= 0 && !mesh.joints0.empty()) {
    if (static_cast<std::size_t>(node.skin) >= scene.skins.size()) {
      throw Error(file + ": node " + std::to_string(node_index) +
                  " uses a skin that does not exist");
    }
    mesh.skin = node.skin;
  }
  if (!primitive.targets.empty()) {
    ctx.info(file + ": " + ref.what + " has morph targets; the base shape is imported");
  }
  place_in_world(mesh, scene, node.world);
  validate_mesh(mesh, file, ref.what);
  complete_mesh_attributes(mesh);
  if (mesh.normals_generated) {
    ctx.warn(file + ": " + ref.what + " has no NORMAL; generated area-weighted normals");
  }
  return mesh;
}

// ---- keep-going ------------------------------------------------------------------------------

std::string node_name(const Scene& scene, int node) {
  return "node " + std::to_string(node) + " '" + scene.nodes[node].name + "'";
}

// Records what a keep-going import set aside, and warns of it with what was done about it.
void record(Scene& scene, ImportProblem problem, const std::string& done, const Context& ctx) {
  std::string who;  // the node, unless the reason starts by naming it
  if (problem.node >= 0 && problem.reason.rfind(node_name(scene, problem.node), 0) != 0)
    who = node_name(scene, problem.node) + ": ";
  ctx.warn(scene.source + ": " + who + problem.reason + "; " + done);
  scene.problems.push_back(std::move(problem));
}

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) return false;
    }
  }
  return true;
}

// Why a node's world transform is not finite: its own transform, an ancestor's (the topmost one
// it inherits from), or a product that overflows.
std::string non_finite_reason(const Scene& scene, int node) {
  if (!finite(scene.nodes[node].local)) {
    return node_name(scene, node) +
           " has a non-finite transform (a NaN or infinity in its translation, rotation, scale or "
           "matrix)";
  }
  int origin = scene.nodes[node].parent;
  if (origin < 0 || finite(scene.nodes[origin].world)) {
    return node_name(scene, node) + " has a non-finite world transform (it overflows)";
  }
  while (scene.nodes[origin].parent >= 0 && !finite(scene.nodes[scene.nodes[origin].parent].world))
    origin = scene.nodes[origin].parent;
  return node_name(scene, node) + " inherits a non-finite transform from " +
         node_name(scene, origin);
}

// Keep-going: why material m's base colour texture cannot be used; empty when it can, or when
// the material has none.
std::string texture_problem(const tinygltf::Model& model, const Scene& scene, std::size_t m,
                            const std::map<int, std::string>& undecoded) {
  const tinygltf::Material& material = model.materials[m];
  const int texture = material.pbrMetallicRoughness.baseColorTexture.index;
  if (texture < 0) return "";
  const std::string what = "material " + std::to_string(m) + " '" + material.name +
                           "' base colour texture " + std::to_string(texture);
  if (static_cast<std::size_t>(texture) >= model.textures.size()) return what + " does not exist";
  const int image = model.textures[texture].source;
  if (image < 0 || static_cast<std::size_t>(image) >= model.images.size()) {
    return what + " has no image that exists";
  }
  if (scene.images[image].width > 0 && scene.images[image].height > 0) return "";
  const tinygltf::Image& source = model.images[image];
  const std::string name = "image " + std::to_string(image) + " '" +
                           (source.name.empty() ? source.uri : source.name) + "'";
  const auto why = undecoded.find(image);
  if (why != undecoded.end()) return what + ": " + name + " does not decode (" + why->second + ")";
  return what + ": " + name +
         " did not load (its file is missing or empty, or its pixel format is not supported)";
}

// ---- the node tree -----------------------------------------------------------------------------

struct MeshImport {
  const tinygltf::Model& model;
  const std::string& file;
  const Context& ctx;
  const BrokenParts* keep_going;  // null: every problem throws
  std::set<int> reached_meshes;   // the glTF meshes that nodes of the scene refer to
};

void add_node_meshes(MeshImport& in, int node_index, Scene& scene) {
  const tinygltf::Model& model = in.model;
  const std::string& file = in.file;
  const Node& node = scene.nodes[node_index];
  const bool mesh_exists = static_cast<std::size_t>(node.mesh) < model.meshes.size();
  if (node.mesh >= 0 && mesh_exists) in.reached_meshes.insert(node.mesh);
  if (in.keep_going && !finite(node.world)) {
    record(scene, {node_index, -1, -1, non_finite_reason(scene, node_index)},
           node.mesh >= 0 ? "its meshes are not imported" : "it has no mesh", in.ctx);
  } else if (node.mesh >= 0 && !mesh_exists) {
    const std::string what = "node " + std::to_string(node_index) + " refers to mesh " +
                             std::to_string(node.mesh) + ", which does not exist";
    if (!in.keep_going) throw Error(file + ": " + what);
    record(scene, {node_index, -1, -1, what}, "no mesh imported for it", in.ctx);
  } else if (node.mesh >= 0) {
    const tinygltf::Mesh& source = model.meshes[node.mesh];
    for (std::size_t p = 0; p < source.primitives.size(); ++p) {
      const tinygltf::Primitive& primitive = source.primitives[p];
      PrimitiveRef ref{node.mesh, static_cast<int>(p),
                       "mesh " + std::to_string(node.mesh) + " '" + source.name + "' primitive " +
                           std::to_string(p)};
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES &&
          primitive.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          primitive.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        in.ctx.warn(file + ": " + ref.what + " draws points or lines (mode " +
                    std::to_string(primitive.mode) + "); skipped, only triangles are imported");
        continue;
      }
      if (!in.keep_going) {
        scene.meshes.push_back(import_primitive(model, scene, node_index, ref, file, in.ctx));
        continue;
      }
      const auto broken = in.keep_going->primitives.find({ref.mesh, ref.primitive});
      if (broken != in.keep_going->primitives.end()) {
        record(scene, {node_index, ref.mesh, -1, broken->second}, "primitive skipped", in.ctx);
        continue;
      }
      try {
        scene.meshes.push_back(import_primitive(model, scene, node_index, ref, file, in.ctx));
      } catch (const Error& e) {
        record(scene, {node_index, ref.mesh, -1, without_path(e.what(), file)}, "primitive skipped",
               in.ctx);
      }
    }
  }
  for (int child : node.children) add_node_meshes(in, child, scene);
}

}  // namespace

Scene import_gltf(const std::string& path, const Context& ctx, const ImportOptions& options) {
  BrokenParts broken;
  BrokenParts* const keep_going = options.keep_going ? &broken : nullptr;
  const tinygltf::Model model = load_gltf_model(path, ctx, keep_going);
  Scene scene;
  scene.source = path;
  for (std::size_t i = 0; i < model.images.size(); ++i) {
    scene.images.push_back(convert_image(model.images[i], i));
  }
  std::map<int, std::string> texture_problems;  // keep-going: material -> reason
  for (std::size_t i = 0; i < model.materials.size(); ++i) {
    const tinygltf::Material& material = model.materials[i];
    scene.materials.push_back(
        convert_material(model, material, subject(path, "material", i, material.name), ctx));
    if (!keep_going) continue;
    std::string reason = texture_problem(model, scene, i, broken.images);
    if (reason.empty()) continue;
    scene.materials.back().base_color_texture = -1;
    texture_problems[int(i)] = std::move(reason);
  }
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    scene.nodes.push_back(convert_node(model.nodes[i]));
    read_node_hints(model.nodes[i].extras, subject(path, "node", i, model.nodes[i].name), ctx,
                    scene.nodes.back().hints);
  }
  link_nodes(scene.nodes, path);
  for (std::size_t i = 0; i < model.skins.size(); ++i) {
    scene.skins.push_back(convert_skin(model, model.skins[i], i, path));
  }
  for (std::size_t i = 0; i < model.animations.size(); ++i) {
    scene.animations.push_back(convert_animation(model, model.animations[i], i, path, ctx));
  }
  mark_animated(scene);

  // The default scene's root nodes, or every root node when the file names no scene.
  std::vector<int> roots;
  if (model.defaultScene >= 0 &&
      static_cast<std::size_t>(model.defaultScene) < model.scenes.size()) {
    roots = model.scenes[model.defaultScene].nodes;
  } else if (model.scenes.size() == 1) {
    roots = model.scenes[0].nodes;
  } else {
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
      if (scene.nodes[i].parent < 0) roots.push_back(static_cast<int>(i));
    }
  }
  MeshImport in{model, path, ctx, keep_going, {}};
  for (int root : roots) {
    if (root < 0 || static_cast<std::size_t>(root) >= scene.nodes.size()) {
      throw Error(path + ": the scene lists node " + std::to_string(root) +
                  ", which does not exist");
    }
    add_node_meshes(in, root, scene);
  }
  if (keep_going) {
    for (const auto& [which, reason] : broken.primitives) {
      if (in.reached_meshes.count(which.first)) continue;
      record(scene, {-1, which.first, -1, reason},
             "not imported (no node of the scene places its mesh)", ctx);
    }
    // A texture problem is the problem of every node whose meshes use the material.
    for (const auto& [material, reason] : texture_problems) {
      std::set<int> nodes;
      for (const Mesh& mesh : scene.meshes) {
        if (mesh.material == material) nodes.insert(mesh.node);
      }
      if (nodes.empty()) nodes.insert(-1);
      for (int node : nodes) {
        record(scene, {node, -1, material, reason},
               "the material's base colour factor is used without it", ctx);
      }
    }
    std::set<int> textured;  // images a base colour texture refers to
    for (const tinygltf::Material& material : model.materials) {
      const int texture = material.pbrMetallicRoughness.baseColorTexture.index;
      if (texture >= 0 && static_cast<std::size_t>(texture) < model.textures.size())
        textured.insert(model.textures[texture].source);
    }
    for (const auto& [image, why] : broken.images) {
      if (textured.count(image)) continue;
      ctx.warn(path + ": image " + std::to_string(image) + " does not decode (" + why +
               "); no base colour texture uses it");
    }
  }
  // With keep-going, a scene whose every mesh is broken comes back empty, with its problems.
  if (scene.meshes.empty() && scene.problems.empty()) {
    throw Error(path + ": the scene has no triangle meshes (empty mesh, no triangles)");
  }
  return scene;
}

}  // namespace prt::bake::detail
