// SPDX-License-Identifier: MIT
#include "env_light.hpp"

#include <prt/prt.h>

#include <algorithm>
#include <glm/glm.hpp>
#include <string>

#include "blob_scene.hpp"

namespace prt::view {
namespace {

// Texel direction of face `face` at cube coordinates (s_c, t_c): prt_sh.h's table.
glm::vec3 cube_direction(int face, float s, float t) {
  switch (face) {
    case 0:
      return {1.0f, -t, -s};
    case 1:
      return {-1.0f, -t, s};
    case 2:
      return {s, 1.0f, t};
    case 3:
      return {s, -1.0f, -t};
    case 4:
      return {s, -t, 1.0f};
    default:
      return {-s, -t, -1.0f};
  }
}

void check(prt_result result, const char* what) {
  if (result != PRT_OK) {
    throw ViewerError(std::string(what) + " failed: " + prt_result_string(result));
  }
}

}  // namespace

std::uint32_t cube_face_size(const prt::bake::EnvMap& map) {
  if (map.mapping() == prt::bake::EnvMapping::VerticalCross) {
    return static_cast<std::uint32_t>(map.face_size());
  }
  return static_cast<std::uint32_t>(std::max(8, map.width() / 2));
}

std::vector<std::vector<float>> resample_to_cube(const prt::bake::EnvMap& map,
                                                 std::uint32_t face_size) {
  std::vector<std::vector<float>> faces(6, std::vector<float>(3u * face_size * face_size));
  for (int face = 0; face < 6; ++face) {
    float* out = faces[face].data();
    for (std::uint32_t j = 0; j < face_size; ++j) {
      const float t = 2.0f * (static_cast<float>(j) + 0.5f) / static_cast<float>(face_size) - 1.0f;
      for (std::uint32_t i = 0; i < face_size; ++i) {
        const float s =
            2.0f * (static_cast<float>(i) + 0.5f) / static_cast<float>(face_size) - 1.0f;
        const glm::vec3 value = map.radiance(glm::normalize(cube_direction(face, s, t)));
        for (int c = 0; c < 3; ++c) *out++ = value[c];
      }
    }
  }
  return faces;
}

std::vector<float> project_environment(const prt::bake::EnvMap& map, std::uint32_t order) {
  if (map.rotated()) throw ViewerError("project_environment: the map must not be rotated");
  std::vector<float> coefficients(3u * order * order);
  if (map.mapping() == prt::bake::EnvMapping::LatLong) {
    const auto width = static_cast<std::uint32_t>(map.width());
    check(prt_sh_project_latlong(order, width, static_cast<std::uint32_t>(map.height()),
                                 map.pixels().data(), 3u * width, coefficients.data()),
          "prt_sh_project_latlong");
    return coefficients;
  }
  const std::uint32_t face_size = cube_face_size(map);
  const std::vector<std::vector<float>> faces = resample_to_cube(map, face_size);
  const float* face_pointers[6];
  for (int f = 0; f < 6; ++f) face_pointers[f] = faces[f].data();
  check(prt_sh_project_cube(order, face_size, face_pointers, coefficients.data()),
        "prt_sh_project_cube");
  return coefficients;
}

void rotate_environment(std::vector<float>* coefficients, std::uint32_t order, double degrees) {
  float rotation[9];
  prt::bake::rotation_about_y_row_major(degrees, rotation);
  check(prt_sh_rotate(order, rotation, coefficients->data(), coefficients->data(), 3),
        "prt_sh_rotate");
}

}  // namespace prt::view
