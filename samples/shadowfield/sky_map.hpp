// SPDX-License-Identifier: MIT
// The maps the app writes for the framework and the reference tool to read: the scenes' built-in
// sky, and a map turned as the environment is turned.
#pragma once

#include <string>

#include "prt/io/envmap.hpp"

namespace prt::shadowfield_app {

// The built-in sky of the scenes (`builtin:sky`, prt/io/demo_sky.hpp) as a lat-long .hdr at
// `path`; returns the path. Throws prt::io::Error when it cannot be written.
std::string write_builtin_sky(const std::string& path);

// `map` turned by `degrees` about +Y, resampled to a lat-long .hdr at `path`; returns the path.
std::string write_turned_map(const prt::io::EnvMap& map, double degrees, const std::string& path);

}  // namespace prt::shadowfield_app
