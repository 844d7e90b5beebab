// SPDX-License-Identifier: MIT
#include "env_light.hpp"

#include <prt/prt.h>

#include <algorithm>
#include <glm/glm.hpp>
#include <string>

#include "blob_scene.hpp"

namespace prt::view {
namespace {

void check(prt_result result, const char* what) {
  if (result != PRT_OK) {
    throw ViewerError(std::string(what) + " failed: " + prt_result_string(result));
  }
}

}  // namespace

std::uint32_t cube_face_size(const prt::io::EnvMap& map) {
  if (map.mapping() == prt::io::EnvMapping::VerticalCross) {
    return static_cast<std::uint32_t>(map.face_size());
  }
  return static_cast<std::uint32_t>(std::max(8, map.width() / 2));
}

std::vector<float> project_environment(const prt::io::EnvMap& map, std::uint32_t order) {
  if (map.rotated()) throw ViewerError("project_environment: the map must not be rotated");
  std::vector<float> coefficients(3u * order * order);
  if (map.mapping() == prt::io::EnvMapping::LatLong) {
    const auto width = static_cast<std::uint32_t>(map.width());
    check(prt_sh_project_latlong(order, width, static_cast<std::uint32_t>(map.height()),
                                 map.pixels().data(), 3u * width, coefficients.data()),
          "prt_sh_project_latlong");
    return coefficients;
  }
  const std::uint32_t face_size = cube_face_size(map);
  const std::vector<std::vector<float>> faces =
      prt::io::resample_to_cube(map, static_cast<int>(face_size));
  const float* face_pointers[6];
  for (int f = 0; f < 6; ++f) face_pointers[f] = faces[f].data();
  check(prt_sh_project_cube(order, face_size, face_pointers, coefficients.data()),
        "prt_sh_project_cube");
  return coefficients;
}

std::vector<float> wavelet_light(const prt::io::EnvMap& map, const prt_asset* asset,
                                 const prt_wavelet_info& info, double degrees,
                                 std::uint32_t light_coefficients) {
  if (map.rotated()) throw ViewerError("wavelet_light: the map must not be rotated");
  float rotation[9];
  prt::io::rotation_about_y_row_major(degrees, rotation);
  std::vector<float> light(4u * info.coefficient_count);
  if (map.mapping() == prt::io::EnvMapping::LatLong) {
    check(prt_wavelet_resample_latlong(
              info.param, info.size, map.pixels().data(), static_cast<std::uint32_t>(map.width()),
              static_cast<std::uint32_t>(map.height()), rotation, light.data()),
          "prt_wavelet_resample_latlong");
  } else {
    const std::uint32_t face_size = cube_face_size(map);
    const std::vector<std::vector<float>> faces =
        prt::io::resample_to_cube(map, static_cast<int>(face_size));
    std::vector<float> packed;
    packed.reserve(6u * 3u * face_size * face_size);
    for (const std::vector<float>& face : faces)
      packed.insert(packed.end(), face.begin(), face.end());
    check(prt_wavelet_resample_cube(info.param, info.size, packed.data(), face_size, rotation,
                                    light.data()),
          "prt_wavelet_resample_cube");
  }
  check(prt_wavelet_transform_light(info.param, info.size, light.data()),
        "prt_wavelet_transform_light");
  check(prt_wavelet_select_light(info.param, info.size, light_coefficients, light.data()),
        "prt_wavelet_select_light");
  check(prt_wavelet_prepare_light(asset, light.data(), light.data()), "prt_wavelet_prepare_light");
  return light;
}

void rotate_environment(std::vector<float>* coefficients, std::uint32_t order, double degrees) {
  float rotation[9];
  prt::io::rotation_about_y_row_major(degrees, rotation);
  check(prt_sh_rotate(order, rotation, coefficients->data(), coefficients->data(), 3),
        "prt_sh_rotate");
}

}  // namespace prt::view
