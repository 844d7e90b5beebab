// SPDX-License-Identifier: MIT
#include "env_light.hpp"

#include <prt/prt.hpp>

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

namespace {

// The map as the runtime's environment image: the lat-long pixels as they are, or six cube faces
// resampled into *faces (back to back).
prt_env_image environment_image(const prt::io::EnvMap& map, const float* rotation,
                                std::vector<float>* faces) {
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

}  // namespace

std::vector<float> project_environment(const prt::io::EnvMap& map, std::uint32_t order) {
  if (map.rotated()) throw ViewerError("project_environment: the map must not be rotated");
  std::vector<float> coefficients(3u * order * order), faces;
  const prt_env_image env = environment_image(map, nullptr, &faces);
  check(prt_sh_project(order, &env, coefficients.data()), "prt_sh_project");
  return coefficients;
}

std::vector<float> wavelet_light(const prt::io::EnvMap& map, const prt_asset* asset,
                                 const prt_wavelet_info& info, double degrees,
                                 std::uint32_t light_coefficients,
                                 std::vector<std::uint8_t>* zero_blocks) {
  if (map.rotated()) throw ViewerError("wavelet_light: the map must not be rotated");
  float rotation[9];
  prt::io::rotation_about_y_row_major(degrees, rotation);
  std::vector<float> light(4u * info.coefficient_count), faces;
  const prt_env_image env = environment_image(map, rotation, &faces);
  check(prt_wavelet_resample(info.param, info.size, &env, light.data()), "prt_wavelet_resample");
  check(prt_wavelet_transform_light(info.param, info.size, light.data()),
        "prt_wavelet_transform_light");
  check(prt_wavelet_select_light(info.param, info.size, light_coefficients, light.data()),
        "prt_wavelet_select_light");
  zero_blocks->assign(info.block_count, 0);
  check(prt_wavelet_prepare_light(asset, light.data(), light.data(), zero_blocks->data()),
        "prt_wavelet_prepare_light");
  return light;
}

void rotate_environment(std::vector<float>* coefficients, std::uint32_t order, double degrees) {
  float rotation[9];
  prt::io::rotation_about_y_row_major(degrees, rotation);
  check(prt_sh_rotate(order, rotation, coefficients->data(), coefficients->data(), 3),
        "prt_sh_rotate");
}

}  // namespace prt::view
