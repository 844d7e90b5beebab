// SPDX-License-Identifier: MIT
// prt-view's `shadowfield` technique: the blob's one rigid object as a scene of one instance in
// its own frame (prt_shadowfield_scene_*), lit by the map projected to SH by the runtime and
// turned about +Y, shaded by prt_shadowfield_shade or prt_gl_shadowfield_*: the direct light
// through the object's self-shadowed transfer, reflected towards the eye (glossy objects depend
// on it, set_eye). One instance has no other instance to be shadowed by or to light it, so the
// frame has no bounces; the app prt-shadowfield shows a scene of many.
#pragma once

#include <memory>

#include "view_technique.hpp"

namespace prt::view {

std::unique_ptr<ViewTechnique> make_shadowfield_view();

}  // namespace prt::view
