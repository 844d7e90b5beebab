// SPDX-License-Identifier: MIT
// Technique `wavelet` behind the baker's Technique interface (private to the baker): the trade
// lives in its own files.
#pragma once

#include <memory>
#include <vector>

#include "prt/baker/technique.hpp"

namespace prt::bake {

// prt-bake trade wavelet (wavelet_trade.cpp).
std::unique_ptr<TechniqueTrade> make_wavelet_trade();

// prt-bake scene (wavelet_scene.cpp): the settings ladder and the shading through the runtime.
std::vector<Rung> wavelet_scene_ladder(int bounces);
std::vector<glm::vec3> wavelet_scene_shade(const std::vector<std::uint8_t>& blob,
                                      const io::EnvMap& light, const Context& ctx);

}  // namespace prt::bake
