// SPDX-License-Identifier: MIT
// Loading glTF through tinygltf, with the checks tinygltf 2.7.0 does not make (or makes after it
// has already indexed out of bounds, as in its Draco path) done first, and accessor reads that
// validate every byte they touch.
#include "gltf_model.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "prt/io/file.hpp"

namespace prt::bake::detail {
namespace {

using Json = nlohmann::json;

std::uint32_t read_u32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
         std::uint32_t(p[3]) << 24;
}

struct GlbChunks {
  std::string json;
  std::size_t bin_size = 0;
  bool has_bin = false;
};

// GLB layout: 12-byte header (magic, version, length), then chunks (length, type, data).
GlbChunks split_glb(const std::string& path, const std::vector<unsigned char>& bytes) {
  const std::size_t size = bytes.size();
  if (size < 12) {
    throw Error(path + ": truncated .glb: " + std::to_string(size) +
                " bytes, smaller than the 12-byte header");
  }
  if (std::memcmp(bytes.data(), "glTF", 4) != 0) {
    throw Error(path + ": not a binary glTF file (bad magic; expected 'glTF')");
  }
  const std::uint32_t version = read_u32(&bytes[4]), length = read_u32(&bytes[8]);
  if (version != 2) {
    throw Error(path + ": unsupported .glb container version " + std::to_string(version));
  }
  if (length > size) {
    throw Error(path + ": truncated .glb: the header says " + std::to_string(length) +
                " bytes but the file has " + std::to_string(size));
  }
  if (size < 20) throw Error(path + ": truncated .glb: no JSON chunk");
  const std::uint32_t json_length = read_u32(&bytes[12]), json_type = read_u32(&bytes[16]);
  if (json_type != 0x4E4F534Au) throw Error(path + ": .glb: the first chunk is not JSON");
  if (20 + std::size_t(json_length) > length) {
    throw Error(path + ": truncated .glb: the JSON chunk (" + std::to_string(json_length) +
                " bytes) runs past the end of the file");
  }
  GlbChunks chunks;
  chunks.json.assign(reinterpret_cast<const char*>(&bytes[20]), json_length);
  const std::size_t bin_header = 20 + std::size_t(json_length);
  if (bin_header + 8 <= length) {
    const std::uint32_t bin_length = read_u32(&bytes[bin_header]);
    const std::uint32_t bin_type = read_u32(&bytes[bin_header + 4]);
    if (bin_type == 0x004E4942u) {
      if (bin_header + 8 + std::size_t(bin_length) > length) {
        throw Error(path + ": truncated .glb: the binary chunk (" + std::to_string(bin_length) +
                    " bytes) runs past the end of the file");
      }
      chunks.has_bin = true;
      chunks.bin_size = bin_length;
    }
  } else if (bin_header != length) {
    throw Error(path + ": truncated .glb: a chunk header is cut off");
  }
  return chunks;
}

std::string base_dir_of(const std::string& path) {
  const std::size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

std::string percent_decode(const std::string& uri) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size()) {
      out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

bool is_index(const Json& value, std::size_t count) {
  return value.is_number_integer() && value.get<long long>() >= 0 &&
         static_cast<std::size_t>(value.get<long long>()) < count;
}

std::size_t array_size(const Json& doc, const char* key) {
  const auto it = doc.find(key);
  return it != doc.end() && it->is_array() ? it->size() : 0;
}

void check_required_extensions(const std::string& path, const Json& doc) {
  // KHR_materials_sheen: its factors are read; its textures are ignored with a warning.
  static const std::set<std::string> kSupported = {"KHR_draco_mesh_compression",
                                                   "KHR_texture_transform", "KHR_mesh_quantization",
                                                   "KHR_materials_sheen"};
  const auto it = doc.find("extensionsRequired");
  if (it == doc.end() || !it->is_array()) return;
  for (const Json& name : *it) {
    if (!name.is_string() || !kSupported.count(name.get<std::string>())) {
      throw Error(path + ": requires the glTF extension " + name.dump() +
                  ", which prtkit does not support");
    }
  }
}

void check_buffers(const std::string& path, const Json& doc, const GlbChunks* glb) {
  const auto buffers = doc.find("buffers");
  if (buffers == doc.end() || !buffers->is_array()) return;
  for (std::size_t i = 0; i < buffers->size(); ++i) {
    const Json& buffer = (*buffers)[i];
    const std::string id = "buffer " + std::to_string(i);
    const long long length = buffer.value("byteLength", -1LL);
    if (length < 0) throw Error(path + ": " + id + " has no valid byteLength");
    const auto uri = buffer.find("uri");
    if (uri == buffer.end()) {
      if (i != 0 || !glb) throw Error(path + ": " + id + " has no uri and no GLB binary chunk");
      if (!glb->has_bin || glb->bin_size < std::size_t(length)) {
        throw Error(path + ": truncated .glb: " + id + " needs " + std::to_string(length) +
                    " bytes, the binary chunk has " + std::to_string(glb->bin_size));
      }
      continue;
    }
    if (!uri->is_string()) throw Error(path + ": " + id + " has a non-string uri");
    const std::string text = uri->get<std::string>();
    if (text.rfind("data:", 0) == 0) continue;  // tinygltf decodes and size-checks data URIs
    const std::string file = base_dir_of(path) + "/" + percent_decode(text);
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    if (!in) {
      throw Error(path + ": " + id + " refers to the external file '" + text +
                  "', which is missing (looked for " + file + ")");
    }
    const long long size = static_cast<long long>(in.tellg());
    if (size < length) {
      throw Error(path + ": " + id + " ('" + text + "') has " + std::to_string(size) +
                  " bytes but byteLength says " + std::to_string(length));
    }
  }
}

void check_buffer_views(const std::string& path, const Json& doc) {
  const std::size_t buffer_count = array_size(doc, "buffers");
  const auto views = doc.find("bufferViews");
  if (views == doc.end() || !views->is_array()) return;
  for (std::size_t i = 0; i < views->size(); ++i) {
    const Json& view = (*views)[i];
    const std::string id = "bufferView " + std::to_string(i);
    if (!is_index(view.value("buffer", Json()), buffer_count)) {
      throw Error(path + ": " + id + " refers to a buffer that does not exist");
    }
    const long long offset = view.value("byteOffset", 0LL), length = view.value("byteLength", -1LL);
    const long long buffer_length =
        doc["buffers"][view["buffer"].get<std::size_t>()].value("byteLength", 0LL);
    if (offset < 0 || length < 0 || offset + length > buffer_length) {
      throw Error(path + ": " + id + " (offset " + std::to_string(offset) + ", length " +
                  std::to_string(length) + ") lies outside its buffer of " +
                  std::to_string(buffer_length) + " bytes");
    }
  }
}

// A primitive with KHR_draco_mesh_compression, and "mesh M primitive P" for messages.
struct DracoPrimitive {
  int mesh = -1, primitive = -1;
  std::string id;
};
// Accessor index -> the primitive whose Draco decoding fills it in.
using DracoAccessors = std::map<int, DracoPrimitive>;

// A problem of one primitive: Error("<path>: <what>"), or with keep-going set aside (the first
// reason found for a primitive is kept).
void primitive_fails(const std::string& path, BrokenParts* keep_going, int mesh, int primitive,
                     const std::string& what) {
  if (!keep_going) throw Error(path + ": " + what);
  keep_going->primitives.emplace(std::make_pair(mesh, primitive), what);
}

// tinygltf's Draco path indexes bufferViews and accessors without checking them.
void check_draco_primitives(const std::string& path, const Json& doc, DracoAccessors& draco_out,
                            BrokenParts* keep_going) {
  const std::size_t view_count = array_size(doc, "bufferViews");
  const std::size_t accessor_count = array_size(doc, "accessors");
  const auto meshes = doc.find("meshes");
  if (meshes == doc.end() || !meshes->is_array()) return;
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const Json& mesh = (*meshes)[m];
    if (!mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (std::size_t p = 0; p < mesh["primitives"].size(); ++p) {
      const Json& primitive = mesh["primitives"][p];
      const std::string id = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      const Json* draco = nullptr;
      if (primitive.contains("extensions") && primitive["extensions"].is_object() &&
          primitive["extensions"].contains("KHR_draco_mesh_compression")) {
        draco = &primitive["extensions"]["KHR_draco_mesh_compression"];
      }
      if (!draco) continue;
      const auto fails = [&](const std::string& what) {
        primitive_fails(path, keep_going, int(m), int(p), id + ": " + what);
      };
      if (!draco->is_object() || !is_index(draco->value("bufferView", Json()), view_count)) {
        fails("KHR_draco_mesh_compression has a bad bufferView");
        continue;
      }
      if (!primitive.contains("indices") || !is_index(primitive["indices"], accessor_count)) {
        fails("Draco primitive without a valid indices accessor");
        continue;
      }
      const auto attributes = draco->find("attributes");
      if (attributes == draco->end() || !attributes->is_object()) {
        fails("KHR_draco_mesh_compression has no attributes");
        continue;
      }
      const DracoPrimitive which{int(m), int(p), id};
      DracoAccessors filled{{primitive["indices"].get<int>(), which}};
      bool usable = true;
      for (const auto& [name, unique_id] : attributes->items()) {
        if (!unique_id.is_number_integer() || !primitive.contains("attributes") ||
            !primitive["attributes"].contains(name) ||
            !is_index(primitive["attributes"][name], accessor_count)) {
          fails("Draco attribute " + name + " has no valid accessor in the primitive");
          usable = false;
          break;
        }
        filled[primitive["attributes"][name].get<int>()] = which;
      }
      if (!usable) continue;
      for (const auto& [accessor, filler] : filled) draco_out[accessor] = filler;
    }
  }
}

// The checks tinygltf needs to have been made before it runs; doc receives the parsed JSON.
DracoAccessors precheck(const std::string& path, const std::string& json_text, const GlbChunks* glb,
                        Json& doc, BrokenParts* keep_going) {
  try {
    doc = Json::parse(json_text);
  } catch (const std::exception& e) {
    throw Error(path + ": invalid glTF JSON: " + e.what());
  }
  if (!doc.is_object()) throw Error(path + ": invalid glTF JSON: not an object");
  const std::string version =
      doc.contains("asset") && doc["asset"].is_object() ? doc["asset"].value("version", "") : "";
  if (version.rfind("2.", 0) != 0) {
    throw Error(path + ": not a glTF 2.0 file (asset.version '" + version + "')");
  }
  check_required_extensions(path, doc);
  check_buffers(path, doc, glb);
  check_buffer_views(path, doc);
  DracoAccessors draco;
  check_draco_primitives(path, doc, draco, keep_going);
  return draco;
}

// Draco-filled accessors left without data mean the bitstream did not decode (tinygltf ignores
// the decoder's failure and only notices the missing bufferView later).
void check_draco_decoded(const std::string& path, const tinygltf::Model& model,
                         const DracoAccessors& draco, BrokenParts* keep_going) {
  for (const auto& [accessor, primitive] : draco) {
    if (model.accessors[accessor].bufferView < 0) {
      primitive_fails(path, keep_going, primitive.mesh, primitive.primitive,
                      primitive.id +
                          ": the KHR_draco_mesh_compression data does not decode (corrupt or "
                          "truncated Draco bitstream)");
    }
  }
}

std::string trimmed(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (char& c : text) {
    if (c == '\n') c = ';';
  }
  return text;
}

int component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    case TINYGLTF_COMPONENT_TYPE_DOUBLE:
      return 8;
    default:
      return 0;
  }
}

int type_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

double read_component(const unsigned char* p, int type, bool normalise) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return normalise ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalise ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalise ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalise ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      std::int32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return normalise ? v / 4294967295.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: {
      double v;
      std::memcpy(&v, p, 8);
      return v;
    }
    default:
      return 0.0;
  }
}

// A validated view of `count` elements of `element_size` bytes, `stride` apart.
struct ByteRange {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
};

ByteRange checked_range(const tinygltf::Model& model, int view_index, std::size_t offset,
                        std::size_t count, std::size_t element_size, std::size_t stride,
                        const std::string& file, const std::string& what) {
  if (view_index < 0 || static_cast<std::size_t>(view_index) >= model.bufferViews.size()) {
    throw Error(file + ": " + what + " has a bad bufferView (" + std::to_string(view_index) + ")");
  }
  const tinygltf::BufferView& view = model.bufferViews[view_index];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
    throw Error(file + ": bufferView " + std::to_string(view_index) + " has a bad buffer");
  }
  const std::vector<unsigned char>& buffer = model.buffers[view.buffer].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
    throw Error(file + ": bufferView " + std::to_string(view_index) + " lies outside buffer " +
                std::to_string(view.buffer));
  }
  if (stride == 0) stride = element_size;
  // offset + stride * (count - 1) + element_size <= byteLength, without overflow.
  const std::size_t length = view.byteLength;
  const bool fits = count == 0 || (offset <= length && element_size <= length - offset &&
                                   count - 1 <= (length - offset - element_size) / stride);
  if (!fits) {
    const double needed = double(offset) + double(stride) * double(count - 1) + element_size;
    throw Error(file + ": " + what + " reads past the end of bufferView " +
                std::to_string(view_index) + " (needs " + std::to_string(std::llround(needed)) +
                " bytes, has " + std::to_string(view.byteLength) + ")");
  }
  return {buffer.data() + view.byteOffset + offset, stride};
}

void apply_sparse(const tinygltf::Model& model, const tinygltf::Accessor& accessor, bool normalise,
                  const std::string& file, const std::string& what, AccessorData& out) {
  const auto& sparse = accessor.sparse;
  const std::size_t n = sparse.count > 0 ? static_cast<std::size_t>(sparse.count) : 0;
  const int index_size = component_size(sparse.indices.componentType);
  if (index_size == 0 || index_size > 4) throw Error(file + ": " + what + ": bad sparse indices");
  const ByteRange indices =
      checked_range(model, sparse.indices.bufferView, sparse.indices.byteOffset, n, index_size, 0,
                    file, what + " sparse indices");
  const std::size_t value_size = component_size(accessor.componentType) * out.components;
  const ByteRange values = checked_range(model, sparse.values.bufferView, sparse.values.byteOffset,
                                         n, value_size, 0, file, what + " sparse values");
  const int size = component_size(accessor.componentType);
  for (std::size_t k = 0; k < n; ++k) {
    const double target =
        read_component(indices.data + k * index_size, sparse.indices.componentType, false);
    if (target < 0 || target >= static_cast<double>(out.count)) {
      throw Error(file + ": " + what + ": sparse index " + std::to_string(target) +
                  " is out of range");
    }
    for (int c = 0; c < out.components; ++c) {
      out.values[static_cast<std::size_t>(target) * out.components + c] = read_component(
          values.data + k * value_size + c * size, accessor.componentType, normalise);
    }
  }
}

// Draco-decoded attributes are written tightly packed from offset 0 in the accessor's component
// type, but tinygltf copies Draco's internal stride and offset into the new bufferView.
void fix_draco_views(tinygltf::Model& model) {
  for (const tinygltf::Mesh& mesh : model.meshes) {
    for (const tinygltf::Primitive& primitive : mesh.primitives) {
      if (!primitive.extensions.count("KHR_draco_mesh_compression")) continue;
      for (const auto& [name, accessor_index] : primitive.attributes) {
        if (accessor_index < 0 ||
            static_cast<std::size_t>(accessor_index) >= model.accessors.size())
          continue;
        tinygltf::Accessor& accessor = model.accessors[accessor_index];
        if (accessor.bufferView < 0 ||
            static_cast<std::size_t>(accessor.bufferView) >= model.bufferViews.size())
          continue;
        tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
        if (view.dracoDecoded) continue;  // the compressed view itself: decoding failed
        view.byteOffset = 0;
        view.byteStride = 0;
        accessor.byteOffset = 0;
      }
    }
  }
}

void validate_accessor(const tinygltf::Model& model, std::size_t i, const std::string& file) {
  const tinygltf::Accessor& accessor = model.accessors[i];
  if (accessor.bufferView < 0 && !accessor.sparse.isSparse) {
    throw Error(file + ": accessor " + std::to_string(i) +
                " has no valid bufferView (bad accessor, or a Draco primitive that failed to "
                "decode)");
  }
  read_accessor(model, static_cast<int>(i), false, file, "accessor " + std::to_string(i));
}

void validate_accessors(const tinygltf::Model& model, const std::string& file) {
  for (std::size_t i = 0; i < model.accessors.size(); ++i) validate_accessor(model, i, file);
}

// ---- keep-going ------------------------------------------------------------------------------

// "mesh 0 'Fox' primitive 1", as the importer names a primitive.
std::string primitive_name(const tinygltf::Model& model, int mesh, int primitive) {
  return "mesh " + std::to_string(mesh) + " '" + model.meshes[mesh].name + "' primitive " +
         std::to_string(primitive);
}

// Keep-going validation: an unusable accessor that only primitives use sets those primitives
// aside; one that nothing uses is a warning (none when it belonged to a primitive already set
// aside and emptied); one that a skin or an animation uses throws, as without keep-going.
void validate_accessors(const tinygltf::Model& model, const std::string& file,
                        const std::set<int>& emptied_accessors, const Context& ctx,
                        BrokenParts& keep_going) {
  std::map<int, std::vector<std::pair<int, int>>> primitive_users;
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      const tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
      std::set<int> used;
      if (primitive.indices >= 0) used.insert(primitive.indices);
      for (const auto& [name, accessor] : primitive.attributes) used.insert(accessor);
      for (const auto& target : primitive.targets) {
        for (const auto& [name, accessor] : target) used.insert(accessor);
      }
      for (int accessor : used) primitive_users[accessor].emplace_back(int(m), int(p));
    }
  }
  std::set<int> other_users;
  for (const tinygltf::Skin& skin : model.skins) other_users.insert(skin.inverseBindMatrices);
  for (const tinygltf::Animation& animation : model.animations) {
    for (const tinygltf::AnimationSampler& sampler : animation.samplers) {
      other_users.insert({sampler.input, sampler.output});
    }
  }
  for (std::size_t i = 0; i < model.accessors.size(); ++i) {
    try {
      validate_accessor(model, i, file);
    } catch (const Error& e) {
      const int accessor = int(i);
      if (other_users.count(accessor)) throw;
      const auto users = primitive_users.find(accessor);
      if (users == primitive_users.end()) {
        if (!emptied_accessors.count(accessor)) {
          ctx.warn(std::string(e.what()) + "; nothing uses it: ignored");
        }
        continue;
      }
      for (const auto& [m, p] : users->second) {
        primitive_fails(file, &keep_going, m, p,
                        primitive_name(model, m, p) + ": " + without_path(e.what(), file));
      }
    }
  }
}

// The image loader of a keep-going load: an image whose bytes do not decode is left empty and
// set aside instead of failing the file.
bool load_image_or_set_aside(tinygltf::Image* image, const int index, std::string* /*err*/,
                             std::string* warn, int width, int height, const unsigned char* bytes,
                             int size, void* images) {
  std::string why;
  if (tinygltf::LoadImageData(image, index, &why, warn, width, height, bytes, size, nullptr)) {
    return true;
  }
  (*static_cast<std::map<int, std::string>*>(images))[index] = trimmed(why);
  return true;
}

// Empties, in doc, the primitives set aside and not emptied yet: tinygltf stops at (or, for
// Draco, indexes out of bounds through) what makes them unusable. Adds the accessors they used to
// emptied_accessors; returns whether it emptied any.
bool empty_set_aside(Json& doc, const BrokenParts& keep_going,
                     std::set<std::pair<int, int>>& emptied, std::set<int>& emptied_accessors) {
  bool any = false;
  const auto accessor = [&](const Json& value) {
    if (value.is_number_integer()) emptied_accessors.insert(value.get<int>());
  };
  for (const auto& [which, reason] : keep_going.primitives) {
    if (!emptied.insert(which).second) continue;
    Json& primitive = doc["meshes"][which.first]["primitives"][which.second];
    if (primitive.contains("indices")) accessor(primitive["indices"]);
    if (primitive.contains("attributes") && primitive["attributes"].is_object()) {
      for (const auto& [name, value] : primitive["attributes"].items()) accessor(value);
    }
    if (primitive.contains("targets") && primitive["targets"].is_array()) {
      for (const Json& target : primitive["targets"]) {
        if (!target.is_object()) continue;
        for (const auto& [name, value] : target.items()) accessor(value);
      }
    }
    primitive = Json{{"attributes", Json::object()}};
    any = true;
  }
  return any;
}

// tinygltf stops at the first primitive whose indices accessor has no bufferView (a Draco
// bitstream that did not decode leaves it so). Sets aside the primitives err points at; false
// when it points at none.
bool set_aside_stopping_primitives(const std::string& path, const Json& doc, const std::string& err,
                                   BrokenParts& keep_going) {
  const std::size_t end = err.find("] invalid bufferView");
  const std::size_t begin = err.rfind("accessor[", end);
  if (end == std::string::npos || begin == std::string::npos) return false;
  const std::string number = err.substr(begin + 9, end - begin - 9);
  int accessor = -1;
  const auto [ptr, ec] = std::from_chars(number.data(), number.data() + number.size(), accessor);
  if (ec != std::errc() || ptr != number.data() + number.size()) return false;
  const auto meshes = doc.find("meshes");
  if (meshes == doc.end() || !meshes->is_array()) return false;
  bool any = false;
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const Json& mesh = (*meshes)[m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
      continue;
    const Json& primitives = mesh["primitives"];
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      const Json& primitive = primitives[p];
      if (!primitive.is_object() || !primitive.contains("indices") ||
          primitive["indices"] != accessor)
        continue;
      const bool draco = primitive.contains("extensions") && primitive["extensions"].is_object() &&
                         primitive["extensions"].contains("KHR_draco_mesh_compression");
      const std::string id = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      primitive_fails(path, &keep_going, int(m), int(p),
                      draco ? id + ": the KHR_draco_mesh_compression data does not decode "
                                   "(corrupt or truncated Draco bitstream)"
                            : id + ": its indices accessor " + std::to_string(accessor) +
                                  " has no valid bufferView");
      any = true;
    }
  }
  return any;
}

// The file's bytes with doc as its JSON (for a .glb, the binary chunk kept as it is).
std::vector<unsigned char> with_json(const std::vector<unsigned char>& bytes, bool binary,
                                     const Json& doc) {
  std::string json = doc.dump();
  if (!binary) return std::vector<unsigned char>(json.begin(), json.end());
  while (json.size() % 4) json += ' ';
  const std::size_t old_json = read_u32(&bytes[12]), length = read_u32(&bytes[8]);
  const std::size_t rest = 20 + old_json;  // the binary chunk, when there is one
  const std::size_t tail = length > rest ? length - rest : 0;
  std::vector<unsigned char> out;
  const auto u32 = [&](std::size_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>((v >> (8 * i)) & 0xFF));
  };
  out.insert(out.end(), {'g', 'l', 'T', 'F'});
  u32(2);
  u32(20 + json.size() + tail);
  u32(json.size());
  u32(0x4E4F534Au);  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  out.insert(out.end(), bytes.begin() + rest, bytes.begin() + rest + tail);
  return out;
}

}  // namespace

AccessorData read_accessor(const tinygltf::Model& model, int index, bool normalise,
                           const std::string& file, const std::string& what,
                           const std::vector<int>& allowed_components) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
    throw Error(file + ": " + what + " refers to accessor " + std::to_string(index) +
                ", which does not exist");
  }
  const tinygltf::Accessor& accessor = model.accessors[index];
  const std::string name = what + " (accessor " + std::to_string(index) + ")";
  AccessorData out;
  out.count = accessor.count;
  out.components = type_components(accessor.type);
  const int size = component_size(accessor.componentType);
  if (out.components == 0 || size == 0) {
    throw Error(file + ": " + name + " has an unknown type or component type");
  }
  if (!allowed_components.empty() && std::find(allowed_components.begin(), allowed_components.end(),
                                               out.components) == allowed_components.end()) {
    throw Error(file + ": " + name + " has " + std::to_string(out.components) +
                " components, which this attribute does not allow");
  }
  const bool scale = normalise && accessor.normalized;
  // Only an accessor with no bufferView (all zeros plus sparse values) could claim a huge count
  // that no bytes back.
  constexpr std::size_t kMaxElements = std::size_t(1) << 28;
  if (accessor.bufferView < 0 && out.count > kMaxElements) {
    throw Error(file + ": " + name + " claims " + std::to_string(out.count) +
                " elements without a bufferView");
  }
  // Bounds are checked before anything is allocated.
  ByteRange range{};
  if (accessor.bufferView >= 0) {
    std::size_t stride = 0;
    if (static_cast<std::size_t>(accessor.bufferView) < model.bufferViews.size()) {
      const int s = accessor.ByteStride(model.bufferViews[accessor.bufferView]);
      if (s < 0) throw Error(file + ": " + name + " has an invalid byteStride");
      stride = static_cast<std::size_t>(s);
    }
    const std::size_t element_size = static_cast<std::size_t>(size) * out.components;
    range = checked_range(model, accessor.bufferView, accessor.byteOffset, out.count, element_size,
                          stride, file, name);
  }
  out.values.assign(out.count * out.components, 0.0);
  if (accessor.bufferView >= 0) {
    for (std::size_t i = 0; i < out.count; ++i) {
      const unsigned char* element = range.data + i * range.stride;
      for (int c = 0; c < out.components; ++c) {
        out.values[i * out.components + c] =
            read_component(element + c * size, accessor.componentType, scale);
      }
    }
  }
  if (accessor.sparse.isSparse) apply_sparse(model, accessor, scale, file, name, out);
  return out;
}

std::string without_path(const std::string& message, const std::string& path) {
  const std::string prefix = path + ": ";
  return message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message;
}

tinygltf::Model load_gltf_model(const std::string& path, const Context& ctx,
                                BrokenParts* keep_going) {
  const std::vector<unsigned char> bytes = io::read_file(path);
  // A .glb must be a GLB container; anything else is taken as JSON unless it has GLB's magic.
  const bool glb_name = path.size() >= 4 && (path.compare(path.size() - 4, 4, ".glb") == 0 ||
                                             path.compare(path.size() - 4, 4, ".GLB") == 0);
  const bool binary = glb_name || (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0);
  GlbChunks glb;
  DracoAccessors draco;
  Json doc;
  if (binary) {
    glb = split_glb(path, bytes);
    draco = precheck(path, glb.json, &glb, doc, keep_going);
  } else {
    draco = precheck(path, std::string(bytes.begin(), bytes.end()), nullptr, doc, keep_going);
  }

  tinygltf::TinyGLTF loader;
  if (keep_going) loader.SetImageLoader(&load_image_or_set_aside, &keep_going->images);
  tinygltf::Model model;
  std::string err, warn;
  const std::string base_dir = base_dir_of(path);
  // Keep-going: tinygltf reads the file with the primitives set aside emptied, and what it still
  // stops at is set aside and emptied in turn (each round empties at least one primitive).
  std::vector<unsigned char> edited;
  std::set<std::pair<int, int>> emptied;
  std::set<int> emptied_accessors;
  bool ok = false;
  for (;;) {
    if (keep_going && empty_set_aside(doc, *keep_going, emptied, emptied_accessors)) {
      edited = with_json(bytes, binary, doc);
    }
    const std::vector<unsigned char>& input = edited.empty() ? bytes : edited;
    model = tinygltf::Model();
    err.clear();
    warn.clear();
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, input.data(),
                                              static_cast<unsigned>(input.size()), base_dir)
                : loader.LoadASCIIFromString(&model, &err, &warn,
                                             reinterpret_cast<const char*>(input.data()),
                                             static_cast<unsigned>(input.size()), base_dir);
    if (ok || !keep_going || !set_aside_stopping_primitives(path, doc, err, *keep_going)) break;
  }
  if (!warn.empty()) ctx.warn(path + ": " + trimmed(warn));
  if (!ok) {
    // tinygltf stops at the first Draco index accessor without data; say why.
    for (const auto& [accessor, primitive] : draco) {
      if (err.find("accessor[" + std::to_string(accessor) + "] invalid bufferView") !=
          std::string::npos) {
        throw Error(path + ": " + primitive.id +
                    ": the KHR_draco_mesh_compression data does not decode (corrupt or "
                    "truncated Draco bitstream)");
      }
    }
    throw Error(path + ": " + (err.empty() ? "cannot load glTF" : trimmed(err)));
  }
  check_draco_decoded(path, model, draco, keep_going);
  fix_draco_views(model);
  if (keep_going) {
    validate_accessors(model, path, emptied_accessors, ctx, *keep_going);
  } else {
    validate_accessors(model, path);
  }
  return model;
}

}  // namespace prt::bake::detail
