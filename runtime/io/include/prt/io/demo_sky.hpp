// SPDX-License-Identifier: MIT
// The built-in sky: what ./scripts/demo, the tests and the apps light a scene with when no
// downloaded map is at hand. Generated procedurally, so the repository ships no binary map; here
// (not in the baker) so that the baker and the samples make the very same map.
#pragma once

#include "prt/io/envmap.hpp"

namespace prt::io {

// A lat-long sky (width x width/2): a blue-to-white gradient, a darker ground below the horizon
// and a small sun disc that holds most of the power, placed so that a camera looking down -Z sees
// the shadows.
EnvMap make_demo_sky(int width = 512);

}  // namespace prt::io
