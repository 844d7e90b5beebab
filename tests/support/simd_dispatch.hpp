// SPDX-License-Identifier: MIT
// The backend dispatch every technique's CPU shade entry follows, checked on one asset: AUTO
// shades as SIMD where SIMD is usable, as the scalar reference where the context's backend or ISA
// limit or the build rules SIMD out, and SIMD is then refused; GL is never shaded by the CPU
// entry. Each technique's SIMD test gives its blob and how to shade all of it.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <vector>

#include "support/blob_test_util.hpp"
#include "support/limited_context.hpp"
#include "support/mesh_blob.hpp"

namespace prt_test {

// Shades every vertex of `asset` on `backend` into `out` (sized by the caller's technique).
using ShadeAll =
    std::function<prt_result(const prt_asset* asset, prt_backend backend, std::vector<float>* out)>;

// The asset in a context with the given limits.
class DispatchRun {
 public:
  DispatchRun(const Bytes& blob, const ShadeAll& shade, prt_backend limit, prt_simd_isa isa)
      : context_(limited_context(limit, isa)), asset_(context_.get(), blob), shade_(shade) {
    EXPECT_EQ(asset_.result, PRT_OK) << prt_context_last_message(context_.get());
  }
  prt_context* context() const { return context_.get(); }
  std::vector<float> shade(prt_backend backend, prt_result expected = PRT_OK) const {
    std::vector<float> out;
    EXPECT_EQ(shade_(asset_.asset, backend, &out), expected) << prt_backend_name(backend);
    return out;
  }

 private:
  prt::ContextPtr context_;
  LoadedAsset asset_;
  ShadeAll shade_;
};

inline bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), 4 * a.size()) == 0;
}

// In a context without limits where SIMD is usable (the caller checks): the context picks SIMD,
// and AUTO gives SIMD's bits. Returns whether AUTO's bits are also the scalar reference's.
inline bool expect_auto_shades_as_simd(const Bytes& blob, const ShadeAll& shade) {
  const DispatchRun run(blob, shade, PRT_BACKEND_AUTO, PRT_SIMD_ISA_AUTO);
  EXPECT_EQ(prt_context_backend(run.context()), PRT_BACKEND_SIMD);
  const std::vector<float> automatic = run.shade(PRT_BACKEND_AUTO);
  EXPECT_TRUE(same_bits(automatic, run.shade(PRT_BACKEND_SIMD)));
  return same_bits(automatic, run.shade(PRT_BACKEND_CPU));
}

// In a context limited to the CPU backend: SIMD is refused, AUTO gives the scalar reference's
// bits.
inline void expect_cpu_limit_refuses_simd(const Bytes& blob, const ShadeAll& shade) {
  const DispatchRun run(blob, shade, PRT_BACKEND_CPU, PRT_SIMD_ISA_AUTO);
  run.shade(PRT_BACKEND_SIMD, PRT_ERROR_UNSUPPORTED_BACKEND);
  EXPECT_TRUE(same_bits(run.shade(PRT_BACKEND_AUTO), run.shade(PRT_BACKEND_CPU)));
}

// In a context whose ISA limit is NONE: SIMD is refused.
inline void expect_isa_limit_none_refuses_simd(const Bytes& blob, const ShadeAll& shade) {
  const DispatchRun run(blob, shade, PRT_BACKEND_AUTO, PRT_SIMD_ISA_NONE);
  run.shade(PRT_BACKEND_SIMD, PRT_ERROR_UNSUPPORTED_BACKEND);
}

// In a build without SIMD (the caller checks): the context picks the CPU, SIMD is refused and
// AUTO gives the scalar reference's bits.
inline void expect_compiled_out_simd_unsupported(const Bytes& blob, const ShadeAll& shade) {
  const DispatchRun run(blob, shade, PRT_BACKEND_AUTO, PRT_SIMD_ISA_AUTO);
  EXPECT_EQ(prt_context_backend(run.context()), PRT_BACKEND_CPU);
  run.shade(PRT_BACKEND_SIMD, PRT_ERROR_UNSUPPORTED_BACKEND);
  EXPECT_TRUE(same_bits(run.shade(PRT_BACKEND_AUTO), run.shade(PRT_BACKEND_CPU)));
}

// The CPU entry refuses GL (the GL backend has entry points of its own).
inline void expect_gl_not_shaded_here(const Bytes& blob, const ShadeAll& shade) {
  const DispatchRun run(blob, shade, PRT_BACKEND_AUTO, PRT_SIMD_ISA_AUTO);
  run.shade(PRT_BACKEND_GL, PRT_ERROR_UNSUPPORTED_BACKEND);
}

}  // namespace prt_test
