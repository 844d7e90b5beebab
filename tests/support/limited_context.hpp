// SPDX-License-Identifier: MIT
// Contexts that allow only some backends, for the tests that pin one: the SIMD tests force each
// instruction set through the ISA limit, the GL tests refuse GL through the backend limit.
// Contexts ignore PRT_BACKEND / PRT_SIMD_ISA in the environment unless asked, so the limits
// given here are the only ones.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include <prt/prt.hpp>

namespace prt_test {

// A context that allows backends up to `backend` and SIMD instruction sets up to `isa`, with the
// caller's allocator (nullptr: the default one).
inline prt::ContextPtr limited_context(prt_backend backend = PRT_BACKEND_AUTO,
                                       prt_simd_isa isa = PRT_SIMD_ISA_AUTO,
                                       const prt_allocator* allocator = nullptr) {
  prt_context_desc desc = prt::sized<prt_context_desc>();
  desc.backend_limit = backend;
  desc.simd_isa_limit = isa;
  desc.allocator = allocator;
  auto [context, made] = prt::create_context(&desc);
  EXPECT_EQ(made, PRT_OK);
  return std::move(context);
}

// Whether `context` can shade with SIMD (compiled in, the CPU has an instruction set, allowed).
inline bool simd_usable(prt_context* context) {
  prt_backend_info info = prt::sized<prt_backend_info>();
  return prt_backend_get_info(context, PRT_BACKEND_SIMD, &info) == PRT_OK && info.usable;
}

// A test of one SIMD instruction set (the parameter), forced through the context's ISA limit:
// skipped where SIMD is compiled out or the CPU lacks that set.
class SimdIsaTest : public ::testing::TestWithParam<prt_simd_isa> {
 protected:
  void SetUp() override {
    prt_backend_info info = prt::sized<prt_backend_info>();
    ASSERT_EQ(prt_backend_get_info(ctx, PRT_BACKEND_SIMD, &info), PRT_OK);
    if (!info.compiled) GTEST_SKIP() << "SIMD compiled out (PRT_ENABLE_SIMD=OFF)";
    if (!info.usable || info.isa != GetParam())
      GTEST_SKIP() << "this CPU lacks " << prt_simd_isa_name(GetParam()) << " (" << info.note
                   << ")";
  }

  prt::ContextPtr context = limited_context(PRT_BACKEND_AUTO, GetParam());
  prt_context* ctx = context.get();
};

// The instruction sets a SimdIsaTest runs for, named in the test names as sse41, avx2 and
// avx512: INSTANTIATE_TEST_SUITE_P(Isa, Suite, prt_test::kSimdIsas, prt_test::isa_test_name).
inline const auto kSimdIsas =
    ::testing::Values(PRT_SIMD_ISA_SSE41, PRT_SIMD_ISA_AVX2, PRT_SIMD_ISA_AVX512);

inline std::string isa_test_name(const ::testing::TestParamInfo<prt_simd_isa>& info) {
  switch (info.param) {
    case PRT_SIMD_ISA_AVX512:
      return "avx512";
    case PRT_SIMD_ISA_AVX2:
      return "avx2";
    default:
      return "sse41";
  }
}

}  // namespace prt_test
