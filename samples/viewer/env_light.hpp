// SPDX-License-Identifier: MIT
// The light the viewer shades with: an environment map (read by prt_io, any of its three
// mappings) turned into the technique's light by the RUNTIME, as a game would do it:
// projected to SH then rotated (`sh`), or resampled with the rotation onto the wavelet cube,
// transformed, selected and prepared (`wavelet`).
#pragma once

#include <prt/prt.h>

#include <cstdint>
#include <vector>

#include "prt/io/envmap.hpp"

namespace prt::view {

// order² RGB coefficients, coefficient-major, of `map`, which must carry no rotation (turn the
// coefficients instead, rotate_environment; throws ViewerError otherwise) by prt_sh_project:
// lat-long maps directly; cross and probe maps resampled (EnvMap::radiance, bilinear) to six
// cube faces as prt_env.h documents them. Throws ViewerError when the runtime refuses.
std::vector<float> project_environment(const prt::io::EnvMap& map, std::uint32_t order);

// Edge length of the cube faces a cross or probe map is resampled to: the cross's own face
// size; for a probe of width W, W/2 (a cube texel at a face centre then spans about the solid
// angle of a probe texel near its centre, (2/F)^2 ~ (2 pi/W)^2 / 2.5, so no detail is lost).
std::uint32_t cube_face_size(const prt::io::EnvMap& map);

// Rotates coefficients in place about world +Y by `degrees` with prt_sh_rotate (light from d
// comes from R d, R = [[c,0,s],[0,1,0],[-s,0,c]]).
void rotate_environment(std::vector<float>* coefficients, std::uint32_t order, double degrees);

// The `wavelet` light of `map` (no rotation of its own) for `asset`: resampled onto the asset's
// parameterisation turned by `degrees` about +Y (prt_wavelet_resample of the same environment
// image prt_sh_project takes), Haar-transformed, `light_coefficients` detail coefficients kept
// by area-weighted selection (plus the scaling ones), and prepared (band scales folded in):
// info.coefficient_count RGBA quadruples, and the blocks of zero light in *zero_blocks
// (info.block_count bytes). Throws ViewerError when the runtime refuses.
std::vector<float> wavelet_light(const prt::io::EnvMap& map, const prt_asset* asset,
                                 const prt_wavelet_info& info, double degrees,
                                 std::uint32_t light_coefficients,
                                 std::vector<std::uint8_t>* zero_blocks);

}  // namespace prt::view
