// SPDX-License-Identifier: MIT
// Floating-point mode for threads that trace rays (private header).
#pragma once

#if defined(__SSE__) || defined(_M_X64)
#include <pmmintrin.h>
#include <xmmintrin.h>
#define PRT_HAVE_MXCSR 1
#endif

namespace prt::bake::render {

// Embree wants flush-to-zero and denormals-are-zero in every tracing thread (speed, and no
// warnings); the previous mode is restored on leaving the scope, since TBB workers are shared.
class TracingThreadScope {
 public:
  TracingThreadScope() {
#ifdef PRT_HAVE_MXCSR
    saved_ = _mm_getcsr();
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
#endif
  }
  ~TracingThreadScope() {
#ifdef PRT_HAVE_MXCSR
    _mm_setcsr(saved_);
#endif
  }
  TracingThreadScope(const TracingThreadScope&) = delete;
  TracingThreadScope& operator=(const TracingThreadScope&) = delete;

 private:
  unsigned int saved_ = 0;
};

}  // namespace prt::bake::render
