// SPDX-License-Identifier: MIT
#include "prt/baker/context.hpp"

#include <thread>

namespace prt::bake {
namespace {

LogLevel log_level(io::MessageLevel level) {
  switch (level) {
    case io::MessageLevel::Debug:
      return LogLevel::Debug;
    case io::MessageLevel::Warning:
      return LogLevel::Warning;
  }
  return LogLevel::Warning;
}

}  // namespace

unsigned Context::thread_count() const {
  if (threads > 0) return threads;
  unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? hw : 1;
}

io::MessageHook Context::io_messages() const {
  if (!log) return {};
  return
      [log = log](io::MessageLevel level, const std::string& text) { log(log_level(level), text); };
}

}  // namespace prt::bake
