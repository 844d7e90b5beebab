// SPDX-License-Identifier: MIT
// The content pipeline's cache keys: a 128-bit hash (XXH3) of everything a result depends on,
// fed field by field with each field's length, so that no two different inputs run together.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "prt/baker/scene.hpp"

namespace prt::bake {

class ContentHash {
 public:
  ContentHash();
  ~ContentHash();
  ContentHash(const ContentHash&) = delete;
  ContentHash& operator=(const ContentHash&) = delete;

  ContentHash& bytes(const void* data, std::size_t size);
  ContentHash& text(const std::string& value);
  template <typename T>
  ContentHash& value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    return bytes(&v, sizeof v);
  }
  template <typename T>
  ContentHash& values(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    value(v.size());
    return bytes(v.data(), v.size() * sizeof(T));
  }
  // 32 lower-case hex digits.
  std::string hex() const;

 private:
  void* state_;
};

// Everything of an object's scene that a bake reads: meshes (every attribute), the occluders
// around it (positions and triangles), materials and the
// images they use, the node's own facts (transform, skin, hints), and what places, poses and
// moves it: its ancestors, its skin's joints and theirs, and the animation channels of those.
void hash_object_scene(ContentHash& hash, const Scene& scene, int node);

// The file's bytes (a light), or Error when it cannot be read.
std::string file_hash(const std::string& path);

}  // namespace prt::bake
