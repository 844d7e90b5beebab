// SPDX-License-Identifier: MIT
// What the prt-bake commands share: the terminal context (log lines on stderr, a progress line
// when stderr is a TTY).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <mutex>

#include "command.hpp"

namespace prt::bake::cli {
namespace {

const char* level_prefix(LogLevel level) {
  switch (level) {
    case LogLevel::Debug:
      return "debug: ";
    case LogLevel::Info:
      return "";
    case LogLevel::Warning:
      return "warning: ";
    case LogLevel::Error:
      return "error: ";
  }
  return "";
}

struct TerminalState {
  std::mutex mutex;
  bool progress_shown = false;  // a progress line is on screen and must be cleared first
  std::chrono::steady_clock::time_point last_draw{};
};

}  // namespace

Context CommandEnv::context() const {
  auto state = std::make_shared<TerminalState>();
  const bool quiet_mode = quiet;
  const bool tty = isatty(fileno(stderr)) != 0;
  Context ctx;
  ctx.threads = threads;
  ctx.log = [state, quiet_mode](LogLevel level, const std::string& text) {
    if (quiet_mode && level != LogLevel::Error) return;
    if (level == LogLevel::Debug) return;
    std::lock_guard<std::mutex> lock(state->mutex);
    if (state->progress_shown) std::fputs("\r\033[K", stderr);
    state->progress_shown = false;
    std::fprintf(stderr, "%s%s\n", level_prefix(level), text.c_str());
  };
  if (tty && !quiet_mode) {
    ctx.progress = [state](double fraction, const std::string& stage) {
      std::lock_guard<std::mutex> lock(state->mutex);
      auto now = std::chrono::steady_clock::now();
      if (fraction < 1.0 && now - state->last_draw < std::chrono::milliseconds(100)) return true;
      state->last_draw = now;
      std::fprintf(stderr, "\r\033[K%s %5.1f%%", stage.c_str(), 100.0 * fraction);
      state->progress_shown = fraction < 1.0;
      if (fraction >= 1.0) std::fputc('\n', stderr);
      std::fflush(stderr);
      return true;
    };
  }
  return ctx;
}

}  // namespace prt::bake::cli
