// SPDX-License-Identifier: MIT
// prt-view's `pose` technique: the character at its bind pose (the mesh the blob stores, which
// is what prt_pose_skin gives there), the map projected to SH by the runtime and turned about
// +Y, shaded with prt_pose_shade. Posing, clips and the comparison with the baked frames are
// the character sample's (samples/character); GL shading is not offered yet.
#pragma once

#include <memory>

#include "view_technique.hpp"

namespace prt::view {

std::unique_ptr<ViewTechnique> make_pose_view();

}  // namespace prt::view
