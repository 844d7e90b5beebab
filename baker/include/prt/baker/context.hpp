// SPDX-License-Identifier: MIT
// The baker's injected context: logging, progress, cancellation and thread count.
// The baker library never prints by itself and holds no global state; the prt-bake command
// supplies a context that prints to the terminal.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "prt/io/error.hpp"

namespace prt::bake {

enum class LogLevel { Debug, Info, Warning, Error };

// Every failure the baker reports is an Error whose message names the file (where there is one)
// and what is wrong with it, e.g. "bunny.glb: accessor 3 reads past the end of buffer 0". It is
// prt_io's error type, so one catch takes the failures of both (an unreadable .hdr included).
using Error = io::Error;

struct Context {
  // Receives every diagnostic. Empty: diagnostics are dropped.
  std::function<void(LogLevel, const std::string&)> log;
  // Called from long work with the fraction done in [0,1]; return false to cancel (the work then
  // throws Error("cancelled")). Called from one thread at a time. Empty: no progress.
  std::function<bool(double fraction, const std::string& stage)> progress;
  // Worker threads for parallel work; 0 = all hardware threads.
  unsigned threads = 0;

  void message(LogLevel level, const std::string& text) const {
    if (log) log(level, text);
  }
  void info(const std::string& text) const { message(LogLevel::Info, text); }
  void warn(const std::string& text) const { message(LogLevel::Warning, text); }
  // The hook prt_io's readers (io::load_envmap) report through: their messages go to log at the
  // same level.
  io::MessageHook io_messages() const;
  // Resolved thread count (>= 1).
  unsigned thread_count() const;
};

}  // namespace prt::bake
