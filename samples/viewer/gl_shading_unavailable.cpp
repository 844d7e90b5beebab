// SPDX-License-Identifier: MIT
// --backend gl in a build without the headless GL helper (PRT_ENABLE_GL=OFF).
#include "vertex_shading.hpp"

namespace prt::view {

ShadingRun shade_vertices_gl(const BlobScene&, const ViewTechnique&, int) {
  throw ViewerError(
      "backend gl: this prt-view was built without GL (PRT_ENABLE_GL=OFF or no headless EGL "
      "helper); use --backend auto, cpu or simd");
}

}  // namespace prt::view
