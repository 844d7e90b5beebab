// SPDX-License-Identifier: MIT
// Wavefront OBJ: v, vt, vn and f (polygons triangulated as fans, negative indices); one Mesh
// per `o` object (groups `g` do not split). The positions declared in an object's block are its
// vertices in file order, so a single-object file keeps the file's vertex numbering; corners that
// use a position with a second (vt, vn) combination get an extra vertex appended. Materials
// (mtllib/usemtl) are ignored with a note: meshes get the default white material; vertex colours
// written as "v x y z r g b" become COLOR_0.
#include <charconv>
#include <cstdlib>
#include <map>
#include <tuple>

#include "import_detail.hpp"
#include "prt/io/file.hpp"

namespace prt::bake::detail {
namespace {

struct Corner {
  long v = -1, vt = -1, vn = -1;  // 0-based, -1 = absent
};

struct ObjObject {
  std::string name;
  long first_position = 0, end_position = 0;  // the v lines declared in this object's block
  std::vector<Corner> corners;                // 3 per triangle
};

struct ObjFile {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> colors;  // per position; white where a `v` line has none
  bool has_colors = false;
  std::vector<glm::vec2> texcoords;
  std::vector<glm::vec3> normals;
  std::vector<ObjObject> objects;
  bool mentions_materials = false;
};

class LineReader {
 public:
  LineReader(const std::string& path, std::size_t line, const char* p, const char* end)
      : path_(path), line_(line), p_(p), end_(end) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path_ + ":" + std::to_string(line_) + ": " + what);
  }
  void skip_space() {
    while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r')) ++p_;
  }
  bool at_end() {
    skip_space();
    return p_ >= end_;
  }
  float number() {
    skip_space();
    // std::from_chars for float is missing in GCC < 11 builds of some distros; strtof is fine
    // because the line is copied into a NUL-terminated buffer.
    char* stop = nullptr;
    const float value = std::strtof(p_, &stop);
    if (stop == p_) fail("expected a number");
    p_ = stop;
    return value;
  }
  // One face corner "v", "v/vt", "v//vn" or "v/vt/vn"; returns the raw (1-based or negative)
  // indices, 0 for absent.
  void corner(long raw[3]) {
    skip_space();
    for (int k = 0; k < 3; ++k) raw[k] = 0;
    for (int k = 0; k < 3; ++k) {
      if (k > 0) {
        if (p_ >= end_ || *p_ != '/') return;
        ++p_;
        if (p_ < end_ && *p_ == '/') continue;  // "v//vn"
      }
      const auto [next, ec] = std::from_chars(p_, end_, raw[k]);
      if (ec != std::errc() || raw[k] == 0) fail("bad face index");
      p_ = next;
    }
  }

 private:
  const std::string& path_;
  std::size_t line_;
  const char* p_;
  const char* end_;
};

long resolve(long raw, std::size_t count, const char* kind, const LineReader& reader) {
  if (raw == 0) return -1;
  const long index = raw > 0 ? raw - 1 : static_cast<long>(count) + raw;
  if (index < 0 || index >= static_cast<long>(count)) {
    reader.fail(std::string("face ") + kind + " index " + std::to_string(raw) +
                " is out of range (" + std::to_string(count) + " defined so far)");
  }
  return index;
}

ObjFile parse_obj(const std::string& path, const std::string& text) {
  ObjFile obj;
  obj.objects.push_back({"", 0, 0, {}});
  std::string line;
  std::size_t line_number = 0, start = 0;
  std::vector<Corner> polygon;
  while (start < text.size()) {
    std::size_t stop = text.find('\n', start);
    if (stop == std::string::npos) stop = text.size();
    line.assign(text, start, stop - start);
    start = stop + 1;
    ++line_number;
    LineReader reader(path, line_number, line.c_str(), line.c_str() + line.size());
    if (reader.at_end()) continue;
    std::size_t key_begin = line.find_first_not_of(" \t");
    std::size_t key_end = line.find_first_of(" \t\r", key_begin);
    if (key_end == std::string::npos) key_end = line.size();
    const std::string key = line.substr(key_begin, key_end - key_begin);
    LineReader args(path, line_number, line.c_str() + key_end, line.c_str() + line.size());
    if (key == "v") {
      const float x = args.number(), y = args.number(), z = args.number();
      obj.positions.emplace_back(x, y, z);
      // "v x y z r g b" (a common extension) carries a vertex colour; "v x y z w" a weight.
      glm::vec3 color(1.0f);
      float extra[3];
      int extras = 0;
      while (extras < 3 && !args.at_end()) extra[extras++] = args.number();
      if (extras == 3) {
        color = glm::vec3(extra[0], extra[1], extra[2]);
        obj.has_colors = true;
      }
      obj.colors.push_back(color);
      obj.objects.back().end_position = static_cast<long>(obj.positions.size());
    } else if (key == "vt") {
      const float u = args.number();
      const float v = args.at_end() ? 0.0f : args.number();
      obj.texcoords.emplace_back(u, v);
    } else if (key == "vn") {
      const float x = args.number(), y = args.number(), z = args.number();
      obj.normals.emplace_back(x, y, z);
    } else if (key == "f") {
      polygon.clear();
      while (!args.at_end()) {
        long raw[3];
        args.corner(raw);
        polygon.push_back({resolve(raw[0], obj.positions.size(), "vertex", args),
                           resolve(raw[1], obj.texcoords.size(), "texcoord", args),
                           resolve(raw[2], obj.normals.size(), "normal", args)});
      }
      if (polygon.size() < 3) args.fail("face with fewer than 3 vertices");
      auto& corners = obj.objects.back().corners;
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {  // fan
        corners.push_back(polygon[0]);
        corners.push_back(polygon[k]);
        corners.push_back(polygon[k + 1]);
      }
    } else if (key == "o") {
      const long next = static_cast<long>(obj.positions.size());
      std::string name = line.substr(key_end);
      name.erase(0, name.find_first_not_of(" \t"));
      while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
      obj.objects.push_back({name, next, next, {}});
    } else if (key == "mtllib" || key == "usemtl") {
      obj.mentions_materials = true;
    }
    // g, s, l, p, comments and the rest do not change the geometry we keep.
  }
  return obj;
}

Mesh build_mesh(const ObjFile& obj, const ObjObject& object) {
  Mesh mesh;
  mesh.name = object.name;
  bool any_texcoord = false, all_normals = true;
  for (const Corner& c : object.corners) {
    any_texcoord |= c.vt >= 0;
    all_normals &= c.vn >= 0;
  }
  // The block's own positions first, in file order; each takes the (vt, vn) of its first corner.
  std::map<std::tuple<long, long, long>, std::uint32_t> slots;
  const long first = object.first_position, end = object.end_position;
  for (long v = first; v < end; ++v) mesh.positions.push_back(obj.positions[v]);
  std::vector<glm::vec2> texcoords(mesh.positions.size(), glm::vec2(0.0f));
  std::vector<glm::vec3> normals(mesh.positions.size(), glm::vec3(0.0f));
  std::vector<bool> claimed(mesh.positions.size(), false);
  for (const Corner& c : object.corners) {
    const auto key = std::make_tuple(c.v, c.vt, c.vn);
    auto found = slots.find(key);
    std::uint32_t slot;
    if (found != slots.end()) {
      slot = found->second;
    } else {
      if (c.v >= first && c.v < end && !claimed[c.v - first]) {
        slot = static_cast<std::uint32_t>(c.v - first);
        claimed[slot] = true;
      } else {
        slot = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.push_back(obj.positions[c.v]);
        texcoords.emplace_back(0.0f);
        normals.emplace_back(0.0f);
      }
      if (c.vt >= 0) texcoords[slot] = obj.texcoords[c.vt];
      if (c.vn >= 0) normals[slot] = obj.normals[c.vn];
      slots.emplace(key, slot);
    }
    mesh.indices.push_back(slot);
  }
  if (any_texcoord) {
    // OBJ's v runs upwards; glTF's (and our images') runs downwards.
    for (glm::vec2& t : texcoords) t.y = 1.0f - t.y;
    mesh.texcoords0 = std::move(texcoords);
  }
  if (all_normals) mesh.normals = std::move(normals);
  if (obj.has_colors) {
    // Slot k < block size is position first + k; appended slots were recorded in `slots`.
    mesh.colors0.assign(mesh.positions.size(), glm::vec4(1.0f));
    for (long v = first; v < end; ++v) mesh.colors0[v - first] = glm::vec4(obj.colors[v], 1.0f);
    for (const auto& [key, slot] : slots) {
      mesh.colors0[slot] = glm::vec4(obj.colors[std::get<0>(key)], 1.0f);
    }
  }
  return mesh;
}

}  // namespace

Scene import_obj(const std::string& path, const Context& ctx) {
  const std::vector<unsigned char> bytes = io::read_file(path);
  const ObjFile obj = parse_obj(path, std::string(bytes.begin(), bytes.end()));

  Scene scene;
  scene.source = path;
  for (const ObjObject& object : obj.objects) {
    if (object.corners.empty()) {
      if (object.end_position > object.first_position && obj.objects.size() > 1) {
        ctx.warn(path + ": object '" + object.name + "' has vertices but no faces; skipped");
      }
      continue;
    }
    Mesh mesh = build_mesh(obj, object);
    validate_mesh(mesh, path, mesh.name.empty() ? "the mesh" : "object '" + mesh.name + "'");
    complete_mesh_attributes(mesh);
    scene.meshes.push_back(std::move(mesh));
  }
  if (scene.meshes.empty()) throw Error(path + ": no faces: the mesh is empty (no triangles)");
  if (obj.mentions_materials) {
    ctx.info(path + ": OBJ materials (mtllib/usemtl) are ignored; meshes use the default white");
  }
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.normals_generated) {
      ctx.info(path + ": " + (mesh.name.empty() ? "faces" : "object '" + mesh.name + "'") +
               " without vertex normals (vn); generated area-weighted normals");
    }
  }
  return scene;
}

}  // namespace prt::bake::detail
