// SPDX-License-Identifier: MIT
// An environment map (read by prt_io, any of its three mappings) as the runtime's environment
// image (prt/prt_env.h), the one description every technique's light is made from.
#pragma once

#include <prt/prt.h>

#include <cstdint>
#include <string>
#include <vector>

#include "prt/io/envmap.hpp"

namespace prt::view {

// `map`, which must carry no rotation of its own (throws ViewerError otherwise), as an
// environment image turned by `rotation` (9 row-major floats, or nullptr): lat-long maps as they
// are; cross and probe maps resampled (EnvMap::radiance, bilinear) to six cube faces as
// prt_env.h documents them, stored in *faces (back to back), which the image points into.
prt_env_image environment_image(const prt::io::EnvMap& map, const float* rotation,
                                std::vector<float>* faces);

// How environment_image describes `map`: "lat-long" or "cube faces of N".
std::string environment_image_layout(const prt::io::EnvMap& map);

// Edge length of the cube faces a cross or probe map is resampled to: the cross's own face
// size; for a probe of width W, W/2 (a cube texel at a face centre then spans about the solid
// angle of a probe texel near its centre, (2/F)^2 ~ (2 pi/W)^2 / 2.5, so no detail is lost).
std::uint32_t cube_face_size(const prt::io::EnvMap& map);

// Throws ViewerError "<call> failed: <result>" unless result is PRT_OK.
void check_runtime(prt_result result, const char* call);

}  // namespace prt::view
