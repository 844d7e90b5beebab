// SPDX-License-Identifier: MIT
// prt-view's `sh` technique: the map projected to SH by the runtime, turned with prt_sh_rotate,
// shaded with prt_sh_shade or prt_gl_sh_*.
#pragma once

#include <memory>

#include "view_technique.hpp"

namespace prt::view {

std::unique_ptr<ViewTechnique> make_sh_view();

}  // namespace prt::view
