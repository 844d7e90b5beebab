// SPDX-License-Identifier: MIT
// Technique `sh` behind the baker's Technique interface (private to the baker): the trade lives
// in its own file.
#pragma once

#include <memory>

#include "prt/baker/technique.hpp"

namespace prt::bake {

// prt-bake trade sh (sh_trade.cpp).
std::unique_ptr<TechniqueTrade> make_sh_trade();

}  // namespace prt::bake
