// SPDX-License-Identifier: MIT
// The environment maps a sample lights its scene with: the ones given on the command line and
// the ones dropped on the window, one of them current, turned about world +Y by a rotation the
// slider, a right-drag or the auto-spin changes. Each map is also a lat-long GL texture for the
// background.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gl.hpp"
#include "prt/io/envmap.hpp"

namespace prt::sample {

// The name of the built-in sky (prt/io/demo_sky.hpp), for runs without a map of their own.
inline constexpr const char* kBuiltinSky = "builtin:sky";

class Environments {
 public:
  // Loads `path` (prt_io: .hdr lat-long, cross or probe, `mapping` "auto" detects it; kBuiltinSky
  // is the built-in sky) and makes it current. Throws prt::io::Error naming the file.
  void add(const std::string& path, const std::string& mapping = "auto");
  void select(std::size_t index);

  bool empty() const { return maps_.empty(); }
  std::size_t size() const { return maps_.size(); }
  std::size_t current_index() const { return current_; }
  const prt::io::EnvMap& current() const { return maps_.at(current_)->map; }
  const std::string& current_path() const { return maps_.at(current_)->path; }
  const std::string& path(std::size_t index) const { return maps_.at(index)->path; }

  double rotation_degrees() const { return rotation_; }
  void set_rotation_degrees(double degrees);
  // Degrees per second of auto-spin (0: off).
  double spin_degrees_per_second = 0.0;
  // Advances the auto-spin by `seconds`.
  void advance(double seconds);

  // Changes whenever the light changes (another map, another rotation): what a sample compares
  // to know when to prepare its technique's light again.
  std::uint64_t light_version() const { return version_; }

  // The current map as a lat-long RGB float texture (made on first use, on the current context).
  GLuint texture();
  // Deletes the textures (while the context is current).
  void release_textures();

 private:
  struct Entry {
    std::string path;
    prt::io::EnvMap map;
    GlTexture texture;
  };
  std::vector<std::unique_ptr<Entry>> maps_;
  std::size_t current_ = 0;
  double rotation_ = 0.0;
  std::uint64_t version_ = 0;
};

}  // namespace prt::sample
