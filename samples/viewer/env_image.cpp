// SPDX-License-Identifier: MIT
#include "env_image.hpp"

#include <prt/prt.hpp>

#include <algorithm>

#include "blob_scene.hpp"

namespace prt::view {

void check_runtime(prt_result result, const char* call) {
  if (result != PRT_OK) {
    throw ViewerError(std::string(call) + " failed: " + prt_result_string(result));
  }
}

std::uint32_t cube_face_size(const prt::io::EnvMap& map) {
  if (map.mapping() == prt::io::EnvMapping::VerticalCross) {
    return static_cast<std::uint32_t>(map.face_size());
  }
  return static_cast<std::uint32_t>(std::max(8, map.width() / 2));
}

std::string environment_image_layout(const prt::io::EnvMap& map) {
  if (map.mapping() == prt::io::EnvMapping::LatLong) return "lat-long";
  return "cube faces of " + std::to_string(cube_face_size(map));
}

prt_env_image environment_image(const prt::io::EnvMap& map, const float* rotation,
                                std::vector<float>* faces) {
  if (map.rotated()) throw ViewerError("environment_image: the map must not be rotated");
  if (map.mapping() == prt::io::EnvMapping::LatLong)
    return prt::latlong_env(static_cast<std::uint32_t>(map.width()),
                            static_cast<std::uint32_t>(map.height()), map.pixels().data(), 3,
                            rotation);
  const std::uint32_t face_size = cube_face_size(map);
  faces->clear();
  for (const std::vector<float>& face : prt::io::resample_to_cube(map, static_cast<int>(face_size)))
    faces->insert(faces->end(), face.begin(), face.end());
  return prt::cube_env(face_size, faces->data(), 3, rotation);
}

}  // namespace prt::view
