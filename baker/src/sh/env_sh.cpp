// SPDX-License-Identifier: MIT
// SH projection of environment maps through EnvMap::texel (exact texel solid angles) and the
// runtime's prt_sh_eval, so the baker and the runtime share one basis.
#include "prt/baker/sh/env_sh.hpp"

#include <prt/prt_sh.h>

#include <cstdio>
#include <nlohmann/json.hpp>

namespace prt::bake {

std::vector<float> EnvSh::to_float() const {
  return std::vector<float>(rgb.begin(), rgb.end());
}

EnvSh project_env_sh(const io::EnvMap& map, std::uint32_t order) {
  if (order == 0 || order > PRT_SH_MAX_ORDER) {
    throw Error("SH order " + std::to_string(order) + " is outside 1.." +
                std::to_string(PRT_SH_MAX_ORDER));
  }
  EnvSh sh;
  sh.order = order;
  sh.rgb.assign(std::size_t(order) * order * 3, 0.0);
  std::vector<float> basis(std::size_t(order) * order);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      glm::vec3 dir;
      float solid_angle = 0.0f;
      if (!map.texel(x, y, &dir, &solid_angle)) continue;
      const glm::dvec3 radiance = glm::dvec3(map.texel_value(x, y)) * double(solid_angle);
      if (radiance == glm::dvec3(0.0)) continue;
      const float d[3] = {dir.x, dir.y, dir.z};
      if (prt_sh_eval(order, d, basis.data()) != PRT_OK) continue;  // zero direction: none
      for (std::size_t i = 0; i < basis.size(); ++i) {
        for (int c = 0; c < 3; ++c) sh.rgb[i * 3 + c] += radiance[c] * double(basis[i]);
      }
    }
  }
  return sh;
}

std::string env_sh_json(const io::EnvMap& map, const EnvSh& sh) {
  nlohmann::ordered_json j;
  j["source"] = map.source();
  j["mapping"] = io::env_mapping_name(map.mapping());
  j["width"] = map.width();
  j["height"] = map.height();
  j["order"] = sh.order;
  j["frame"] =
      "SH axes x = world +X, y = world -Z, z = world +Y (polar axis = glTF +Y up); world = glTF "
      "frame (+Y up, front -Z)";
  j["convention"] =
      "real orthonormal SH without the Condon-Shortley phase (Y_1,-1 ~ y, Y_1,0 ~ z, Y_1,1 ~ x); "
      "coefficient (l, m) at index l*(l+1)+m; radiance projection L_lm = integral of L(w) "
      "Y_lm(w) dw (a constant radiance L gives L_00 = sqrt(4 pi) L)";
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (std::uint32_t i = 0; i < sh.order * sh.order; ++i) {
    rows.push_back({sh.at(i, 0), sh.at(i, 1), sh.at(i, 2)});
  }
  j["coefficients"] = rows;
  return j.dump(1);
}

}  // namespace prt::bake
