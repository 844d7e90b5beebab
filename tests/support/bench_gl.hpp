// SPDX-License-Identifier: MIT
// What the GL shading benchmarks of every technique share: the process's one headless GL context
// and the number of threads Mesa's llvmpipe shades on, whose memory roofline applies there.
#pragma once

#include <cstdlib>
#include <string>
#include <thread>

#include "headless_gl.h"

namespace prt_bench {

// The headless context, made on first use (benchmarks run on the main thread) and destroyed by
// the caller's main while nothing made on it is left.
class SharedGl {
 public:
  headless_gl* get() {
    if (!tried_) {
      tried_ = true;
      char error[1024];
      gl_ = headless_gl_create(error, sizeof error);
      if (gl_)
        renderer_ = headless_gl_renderer(gl_);
      else
        missing_ = std::string("no headless GL: ") + error;
    }
    return gl_;
  }
  void destroy() {
    headless_gl_destroy(gl_);
    gl_ = nullptr;
  }
  const std::string& renderer() const { return renderer_; }
  // Why there is no context ("" when there is one or none was asked for).
  const std::string& missing() const { return missing_; }

 private:
  headless_gl* gl_ = nullptr;
  bool tried_ = false;
  std::string renderer_, missing_;
};

// llvmpipe's threads (LP_NUM_THREADS, default: all cores) as the triad thread count measured
// beside it: 1 or 2.
inline int llvmpipe_threads() {
  const char* env = std::getenv("LP_NUM_THREADS");
  const int threads = env ? std::atoi(env) : int(std::thread::hardware_concurrency());
  return threads <= 1 ? 1 : 2;
}

}  // namespace prt_bench
