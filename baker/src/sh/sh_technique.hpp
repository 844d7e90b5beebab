// SPDX-License-Identifier: MIT
// Technique `sh` behind the baker's Technique interface (private to the baker): the trade lives
// in its own file.
#pragma once

#include <memory>
#include <vector>

#include "prt/baker/technique.hpp"

namespace prt::bake {

// prt-bake trade sh (sh_trade.cpp).
std::unique_ptr<TechniqueTrade> make_sh_trade();

// prt-bake scene (sh_scene.cpp): the settings ladder and the shading through the runtime.
std::vector<Rung> sh_scene_ladder(int bounces);
std::vector<glm::vec3> sh_scene_shade(const std::vector<std::uint8_t>& blob,
                                      const io::EnvMap& light, const Context& ctx);

}  // namespace prt::bake
