// SPDX-License-Identifier: MIT
// A technique's live parameters (view_technique.hpp) as ImGui controls.
#pragma once

#include <vector>

#include "view_technique.hpp"

namespace prt::view {

// One control per parameter (an int slider, a float slider or a check box); true when one
// changed (the caller then prepares the light again). `id` keeps two blobs' controls apart.
bool live_parameter_panel(const std::vector<LiveParameter>& parameters, const char* id);

}  // namespace prt::view
