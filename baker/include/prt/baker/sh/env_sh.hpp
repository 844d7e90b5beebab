// SPDX-License-Identifier: MIT
// SH projection of an environment map in any mapping (lat-long, vertical cross, angular probe),
// in the runtime's SH convention (prt/prt_sh.h: frame x = +X, y = -Z, z = +Y of the world, real
// orthonormal basis without the Condon-Shortley phase, index l*(l+1)+m).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "prt/baker/context.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake {

// Radiance SH coefficients of an environment: L_lm = sum over the mapping's texels of
// radiance(texel) * Y_lm(centre direction) * solid angle (EnvMap::texel), accumulated in double.
struct EnvSh {
  std::uint32_t order = 0;
  std::vector<double> rgb;  // order*order*3, coefficient-major: c0.r c0.g c0.b c1.r ...

  double at(std::uint32_t index, int channel) const { return rgb[index * 3u + channel]; }
  // The coefficients as floats, in the layout the runtime's prt_sh_* functions use.
  std::vector<float> to_float() const;
};

// Throws Error when order is 0 or above PRT_SH_MAX_ORDER.
EnvSh project_env_sh(const io::EnvMap& map, std::uint32_t order);

// The projection as JSON text: source, mapping, size, order, frame, convention and
// "coefficients": [[r, g, b], ...] in index order (what `prt-bake env-sh` prints).
std::string env_sh_json(const io::EnvMap& map, const EnvSh& sh);

}  // namespace prt::bake
