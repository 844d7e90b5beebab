// SPDX-License-Identifier: MIT
// Technique `wavelet` behind the baker's Technique interface (private to the baker): the trade
// lives in its own files.
#pragma once

#include <memory>

#include "prt/baker/technique.hpp"

namespace prt::bake {

// prt-bake trade wavelet (wavelet_trade.cpp).
std::unique_ptr<TechniqueTrade> make_wavelet_trade();

}  // namespace prt::bake
