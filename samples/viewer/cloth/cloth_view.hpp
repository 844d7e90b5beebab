// SPDX-License-Identifier: MIT
// prt-view's `cloth` technique: the blob's mesh drawn as one of its fabrics, shaded per vertex
// with prt_cloth_shade from the vertex's normal (VNRM), its warp (VTAN) and the direction to the
// eye, under spherical-Gaussian lobes fitted to the map by the runtime (prt_cloth_fit_light) and
// turned about +Y. The fabric and the lobe count are live parameters; per-pixel shading and GL
// are not offered yet (GL reports PRT_ERROR_UNSUPPORTED_BACKEND).
#pragma once

#include <memory>

#include "view_technique.hpp"

namespace prt::view {

std::unique_ptr<ViewTechnique> make_cloth_view();

}  // namespace prt::view
