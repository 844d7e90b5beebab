// SPDX-License-Identifier: MIT
// Writes small glTF files for tests: one binary buffer, accessors over it, and the JSON around
// it, saved as .glb, as .gltf with a data URI, or as .gltf with an external .bin.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace prt::bake {

class GltfBuilder {
 public:
  enum Component {
    kByte = 5120,
    kUByte = 5121,
    kShort = 5122,
    kUShort = 5123,
    kUInt = 5125,
    kFloat = 5126
  };

  GltfBuilder() {
    doc["asset"] = {{"version", "2.0"}, {"generator", "prtkit tests"}};
    doc["buffers"] = nlohmann::json::array({nlohmann::json::object()});
    doc["bufferViews"] = nlohmann::json::array();
    doc["accessors"] = nlohmann::json::array();
  }

  // Appends raw bytes as a new bufferView (4-byte aligned); returns its index.
  int add_view(const void* data, std::size_t bytes, int stride = 0) {
    while (bin.size() % 4) bin.push_back('\0');
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
    if (stride) view["byteStride"] = stride;
    bin.append(static_cast<const char*>(data), bytes);
    doc["bufferViews"].push_back(view);
    return static_cast<int>(doc["bufferViews"].size()) - 1;
  }

  int add_accessor(int view, Component component, std::size_t count, const char* type,
                   bool normalized = false, std::size_t offset = 0) {
    nlohmann::json accessor = {
        {"bufferView", view}, {"componentType", component}, {"count", count}, {"type", type}};
    if (normalized) accessor["normalized"] = true;
    if (offset) accessor["byteOffset"] = offset;
    doc["accessors"].push_back(accessor);
    return static_cast<int>(doc["accessors"].size()) - 1;
  }

  // A tightly packed array as a view plus an accessor.
  template <typename T>
  int add_array(const std::vector<T>& values, Component component, const char* type,
                bool normalized = false) {
    const int view = add_view(values.data(), values.size() * sizeof(T));
    const std::size_t per_element = std::string(type) == "SCALAR" ? 1
                                    : std::string(type) == "MAT4" ? 16
                                                                  : std::string(type)[3] - '0';
    return add_accessor(view, component, values.size() / per_element, type, normalized);
  }

  // A scene of one node per mesh given (all roots), mesh i holding the given primitive.
  void add_mesh(const nlohmann::json& primitive) {
    doc["meshes"].push_back({{"primitives", nlohmann::json::array({primitive})}});
  }
  void single_node_scene() {
    doc["nodes"] = nlohmann::json::array({{{"mesh", 0}}});
    doc["scenes"] = nlohmann::json::array({{{"nodes", {0}}}});
    doc["scene"] = 0;
  }

  std::string glb() const {
    nlohmann::json d = doc;
    d["buffers"][0]["byteLength"] = bin.size();
    std::string json = d.dump();
    while (json.size() % 4) json += ' ';
    std::string data = bin;
    while (data.size() % 4) data += '\0';
    std::string out;
    const std::uint32_t total = static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + data.size());
    append_u32(out, 0x46546C67u);  // "glTF"
    append_u32(out, 2);
    append_u32(out, total);
    append_u32(out, static_cast<std::uint32_t>(json.size()));
    append_u32(out, 0x4E4F534Au);  // "JSON"
    out += json;
    append_u32(out, static_cast<std::uint32_t>(data.size()));
    append_u32(out, 0x004E4942u);  // "BIN\0"
    out += data;
    return out;
  }

  std::string gltf_with_data_uri() const {
    nlohmann::json d = doc;
    if (bin.empty()) {  // nothing to store: no buffer at all
      d.erase("buffers");
      return d.dump(1);
    }
    d["buffers"][0]["byteLength"] = bin.size();
    d["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bin);
    return d.dump(1);
  }

  std::string gltf_with_external_buffer(const std::string& bin_name) const {
    nlohmann::json d = doc;
    d["buffers"][0]["byteLength"] = bin.size();
    d["buffers"][0]["uri"] = bin_name;
    return d.dump(1);
  }

  nlohmann::json doc;
  std::string bin;

 private:
  static void append_u32(std::string& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
  }
  static std::string base64(const std::string& in) {
    static const char* kTable = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
      const std::uint32_t v =
          std::uint8_t(in[i]) << 16 | std::uint8_t(in[i + 1]) << 8 | std::uint8_t(in[i + 2]);
      for (int k = 3; k >= 0; --k) out += kTable[(v >> (6 * k)) & 63];
    }
    if (i + 1 == in.size()) {
      const std::uint32_t v = std::uint8_t(in[i]) << 16;
      out += kTable[(v >> 18) & 63];
      out += kTable[(v >> 12) & 63];
      out += "==";
    } else if (i + 2 == in.size()) {
      const std::uint32_t v = std::uint8_t(in[i]) << 16 | std::uint8_t(in[i + 1]) << 8;
      out += kTable[(v >> 18) & 63];
      out += kTable[(v >> 12) & 63];
      out += kTable[(v >> 6) & 63];
      out += '=';
    }
    return out;
  }
};

// A right triangle in the XY plane (normal +Z): positions, NORMAL, indices.
inline GltfBuilder triangle_builder(std::vector<std::uint16_t> indices = {0, 1, 2}) {
  GltfBuilder b;
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  const int p = b.add_array(positions, GltfBuilder::kFloat, "VEC3");
  const int n = b.add_array(normals, GltfBuilder::kFloat, "VEC3");
  const int i = b.add_array(indices, GltfBuilder::kUShort, "SCALAR");
  b.add_mesh({{"attributes", {{"POSITION", p}, {"NORMAL", n}}}, {"indices", i}});
  b.single_node_scene();
  return b;
}

}  // namespace prt::bake
