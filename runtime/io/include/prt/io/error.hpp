// SPDX-License-Identifier: MIT
// How prt_io reports: every failure is an Error whose message names the file (where there is
// one) and what is wrong with it, e.g. "sky.hdr: truncated .hdr: the pixel data ends in scanline
// 12"; what a reader has to say that is not a failure (texels it replaced, values no real scene
// has) goes to a MessageHook the caller supplies. prt_io never prints by itself.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

namespace prt::io {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class MessageLevel { Debug, Warning };

// Receives a reader's messages, from the calling thread. Empty: they are dropped.
using MessageHook = std::function<void(MessageLevel level, const std::string& text)>;

}  // namespace prt::io
