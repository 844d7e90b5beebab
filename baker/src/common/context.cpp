// SPDX-License-Identifier: MIT
#include "prt/baker/context.hpp"

#include <thread>

namespace prt::bake {

unsigned Context::thread_count() const {
  if (threads > 0) return threads;
  unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? hw : 1;
}

}  // namespace prt::bake
