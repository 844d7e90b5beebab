// SPDX-License-Identifier: MIT
// What the techniques' shard payloads share (TechniqueBake::bake_shard and merge_shards; private
// to the baker): values written one after another in the host's byte order (shards are merged
// by the same baker that wrote them), read back with a check of every length, and the checks
// every merge makes before it trusts a part: the settings it was baked with, the scene it was
// baked from, and ranges that cover the units once, in order.
#pragma once

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/scene.hpp"

namespace prt::bake {

class ShardPayloadWriter {
 public:
  template <typename T>
  void put(const T& value) {
    put_array(&value, 1);
  }
  template <typename T>
  void put_array(const T* values, std::size_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(values);
    bytes_.insert(bytes_.end(), bytes, bytes + n * sizeof(T));
  }
  template <typename T>
  void put_vector(const std::vector<T>& values) {
    put_array(values.data(), values.size());
  }
  std::vector<std::uint8_t> bytes() && { return std::move(bytes_); }

 private:
  std::vector<std::uint8_t> bytes_;
};

// Reads a payload; `who` names it in errors ("sh merge: shard 2").
class ShardPayloadReader {
 public:
  ShardPayloadReader(const std::vector<std::uint8_t>& bytes, std::string who)
      : bytes_(bytes), who_(std::move(who)) {}
  template <typename T>
  T get() {
    T value;
    get_array(&value, 1);
    return value;
  }
  template <typename T>
  void get_array(T* values, std::size_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (n == 0) return;  // an empty range: `values` may be null, which memcpy must not see
    if (n > (bytes_.size() - at_) / sizeof(T)) throw Error(who_ + ": the payload is truncated");
    std::memcpy(static_cast<void*>(values), bytes_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
  }
  // Checks the length before allocating, so a damaged count cannot ask for terabytes.
  template <typename T>
  std::vector<T> get_vector(std::size_t n) {
    if (n > (bytes_.size() - at_) / sizeof(T)) throw Error(who_ + ": the payload is truncated");
    std::vector<T> values(n);
    get_array(values.data(), n);
    return values;
  }
  // Error when bytes are left over.
  void finish() const {
    if (at_ != bytes_.size())
      throw Error(who_ + ": the payload has " + std::to_string(bytes_.size() - at_) +
                  " bytes more than its header says");
  }
  const std::string& who() const { return who_; }

 private:
  const std::vector<std::uint8_t>& bytes_;
  std::string who_;
  std::size_t at_ = 0;
};

inline std::string shard_value_text(const std::string& value) {
  return value;
}
inline std::string shard_value_text(const char* value) {
  return value;
}
template <typename T, typename = std::enable_if_t<std::is_integral_v<T>>>
std::string shard_value_text(T value) {
  return std::to_string(value);
}
// The shortest decimal that reads back as the value, so two values that differ never print alike.
inline std::string shard_value_text(double value) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}
inline std::string shard_value_text(const glm::vec3& value) {
  char text[64];
  char* end = text;
  for (int c = 0; c < 3; ++c) {
    if (c > 0) *end++ = ',';
    end = std::to_chars(end, text + sizeof text, value[c]).ptr;
  }
  return std::string(text, end);
}

// Collects what a part's settings differ in from the merge's, named as the options spell them.
class ShardSettingsDiff {
 public:
  template <typename T>
  void compare(const std::string& name, const T& part, const T& merge) {
    if (part == merge) return;
    if (!text_.empty()) text_ += ", ";
    text_ += name + " " + shard_value_text(part) + " (this merge: " + shard_value_text(merge) + ")";
  }
  // Error "<who> was baked with other settings: --order 4 (this merge: 6)" when any differs.
  void check(const std::string& who) const {
    if (!text_.empty()) throw Error(who + " was baked with other settings: " + text_);
  }

 private:
  std::string text_;
};

// FNV-1a over the scene's geometry and every vertex's material albedo: a part baked from another
// scene is refused even when it has as many vertices.
inline std::uint64_t shard_scene_fingerprint(const Scene& scene) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  const auto add = [&h](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    for (std::size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 0x100000001b3ull;
  };
  for (const Mesh& mesh : scene.meshes) {
    const std::uint64_t sizes[3] = {mesh.positions.size(), mesh.normals.size(),
                                    mesh.indices.size()};
    add(sizes, sizeof sizes);
    add(mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
    add(mesh.normals.data(), mesh.normals.size() * sizeof(glm::vec3));
    add(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const glm::vec3 albedo = scene.vertex_albedo(mesh, v);
      add(&albedo, sizeof albedo);
    }
  }
  return h;
}

// One part's range of units, and the unit count of the bake it was baked for.
struct ShardPartRange {
  std::size_t first = 0, count = 0, units = 0;
};

// Error unless the parts, in order, cover units [0, units) once each and were each baked for
// `units` units. `technique` and `unit` name them: "sh", "vertices".
inline void check_shard_ranges(const std::string& technique, const std::string& unit,
                               const std::vector<ShardPartRange>& parts, std::size_t units) {
  const std::string who = technique + " merge: ";
  if (parts.empty()) throw Error(who + "no shards to merge");
  const auto span = [&unit](std::size_t first, std::size_t end) {
    return unit + " [" + std::to_string(first) + ", " + std::to_string(end) + ")";
  };
  std::size_t next = 0;  // the first unit no earlier part covers
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const ShardPartRange& p = parts[i];
    const std::string part = "shard " + std::to_string(i);
    if (p.units != units) {
      throw Error(who + part + " was baked for " + std::to_string(p.units) + " " + unit +
                  ", the scene has " + std::to_string(units));
    }
    if (p.first > units || p.count > units - p.first) {
      throw Error(who + part + " has " + span(p.first, p.first + p.count) + ", beyond the " +
                  std::to_string(units) + " of the scene");
    }
    if (p.first > next) {
      throw Error(who + span(next, p.first) + " are in no shard (a part before " + part +
                  " is missing)");
    }
    if (p.first < next) {
      throw Error(who + part + " (" + span(p.first, p.first + p.count) +
                  ") overlaps the shards before it, which end at " + std::to_string(next));
    }
    next = p.first + p.count;
  }
  if (next < units) {
    throw Error(who + span(next, units) + " are in no shard (a part after shard " +
                std::to_string(parts.size() - 1) + " is missing)");
  }
}

}  // namespace prt::bake
