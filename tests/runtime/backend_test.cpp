// SPDX-License-Identifier: MIT
// Backend query: compiled-in set, CPU detection (checked against /proc/cpuinfo), forced limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <prt/prt.hpp>

namespace {

prt_context* make(prt_backend limit = PRT_BACKEND_AUTO, prt_simd_isa isa = PRT_SIMD_ISA_AUTO,
                  uint32_t flags = 0) {
  prt_context_desc desc = prt::sized<prt_context_desc>();
  desc.backend_limit = limit;
  desc.simd_isa_limit = isa;
  desc.flags = flags;
  prt_context* ctx = nullptr;
  EXPECT_EQ(prt_context_create(&desc, &ctx), PRT_OK);
  return ctx;
}

prt_backend_info info(prt_context* ctx, prt_backend backend) {
  prt_backend_info i = prt::sized<prt_backend_info>();
  EXPECT_EQ(prt_backend_get_info(ctx, backend, &i), PRT_OK);
  return i;
}

// The best ISA according to the kernel's CPU flags, independent of the runtime's detection.
prt_simd_isa isa_from_proc_cpuinfo() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("flags", 0) != 0) continue;
    std::istringstream words(line.substr(line.find(':') + 1));
    bool avx2 = false, fma = false, sse41 = false;
    int avx512 = 0;  // F, BW, VL and VNNI: the kernel lists them only where the OS saves the state
    for (std::string w; words >> w;) {
      avx2 |= w == "avx2";
      fma |= w == "fma";
      sse41 |= w == "sse4_1";
      avx512 += w == "avx512f" || w == "avx512bw" || w == "avx512vl" || w == "avx512_vnni";
    }
    if (avx2 && fma) return avx512 == 4 ? PRT_SIMD_ISA_AVX512 : PRT_SIMD_ISA_AVX2;
    return sse41 ? PRT_SIMD_ISA_SSE41 : PRT_SIMD_ISA_NONE;
  }
  return PRT_SIMD_ISA_AUTO;  // unknown
}

TEST(Backend, CpuAlwaysUsable) {
  prt_context* ctx = make(PRT_BACKEND_CPU);
  const prt_backend_info cpu = info(ctx, PRT_BACKEND_CPU);
  EXPECT_EQ(cpu.compiled, 1u);
  EXPECT_EQ(cpu.usable, 1u);
  EXPECT_STREQ(cpu.name, "cpu");
  EXPECT_EQ(prt_context_backend(ctx), PRT_BACKEND_CPU);
  EXPECT_EQ(info(ctx, PRT_BACKEND_SIMD).usable, 0u) << "forced below SIMD";
  EXPECT_EQ(info(ctx, PRT_BACKEND_GL).usable, 0u) << "forced below GL";
  prt_context_destroy(ctx);
  ctx = make(PRT_BACKEND_SIMD);
  EXPECT_EQ(info(ctx, PRT_BACKEND_GL).usable, 0u) << "forced below GL";
  prt_context_destroy(ctx);
  ctx = make(PRT_BACKEND_GL);
  EXPECT_EQ(info(ctx, PRT_BACKEND_GL).usable, uint32_t(PRT_TEST_GL_COMPILED));
  prt_context_destroy(ctx);
}

TEST(Backend, CompiledSetMatchesBuildOptions) {
  prt_context* ctx = make();
  EXPECT_EQ(info(ctx, PRT_BACKEND_SIMD).compiled, uint32_t(PRT_TEST_SIMD_COMPILED));
  const prt_backend_info gl = info(ctx, PRT_BACKEND_GL);
  EXPECT_EQ(gl.compiled, uint32_t(PRT_TEST_GL_COMPILED));
  // GL is "usable with the application's GL context" whenever compiled and not limited away.
  EXPECT_EQ(gl.usable, uint32_t(PRT_TEST_GL_COMPILED));
  EXPECT_NE(prt_context_backend(ctx), PRT_BACKEND_GL) << "AUTO never picks GL";
  prt_backend_info i = prt::sized<prt_backend_info>();
  EXPECT_EQ(prt_backend_get_info(ctx, PRT_BACKEND_AUTO, &i), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_backend_get_info(ctx, PRT_BACKEND_CPU, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  prt_context_destroy(ctx);
}

TEST(Backend, SimdDetectionAgreesWithProcCpuinfo) {
  if (!PRT_TEST_SIMD_COMPILED) GTEST_SKIP() << "SIMD compiled out";
  const prt_simd_isa expected = isa_from_proc_cpuinfo();
  if (expected == PRT_SIMD_ISA_AUTO) GTEST_SKIP() << "no /proc/cpuinfo flags";
  prt_context* ctx = make();
  const prt_backend_info simd = info(ctx, PRT_BACKEND_SIMD);
  if (expected == PRT_SIMD_ISA_NONE) {
    EXPECT_EQ(simd.usable, 0u);
  } else {
    EXPECT_EQ(simd.usable, 1u);
    EXPECT_EQ(simd.isa, expected);
    EXPECT_STREQ(simd.note, prt_simd_isa_name(expected));
    EXPECT_EQ(prt_context_backend(ctx), PRT_BACKEND_SIMD);
  }
  prt_context_destroy(ctx);
}

TEST(Backend, IsaLimitForcesALowerInstructionSet) {
  if (!PRT_TEST_SIMD_COMPILED || isa_from_proc_cpuinfo() < PRT_SIMD_ISA_SSE41)
    GTEST_SKIP() << "no SIMD here";
  prt_context* ctx = make(PRT_BACKEND_AUTO, PRT_SIMD_ISA_SSE41);
  EXPECT_EQ(info(ctx, PRT_BACKEND_SIMD).isa, PRT_SIMD_ISA_SSE41);
  prt_context_destroy(ctx);
  if (isa_from_proc_cpuinfo() >= PRT_SIMD_ISA_AVX2) {
    // A limit above the CPU is no limit; AVX2 below AVX-512 is one.
    ctx = make(PRT_BACKEND_AUTO, PRT_SIMD_ISA_AVX512);
    EXPECT_EQ(info(ctx, PRT_BACKEND_SIMD).isa, isa_from_proc_cpuinfo());
    prt_context_destroy(ctx);
    ctx = make(PRT_BACKEND_AUTO, PRT_SIMD_ISA_AVX2);
    EXPECT_EQ(info(ctx, PRT_BACKEND_SIMD).isa, PRT_SIMD_ISA_AVX2);
    prt_context_destroy(ctx);
  }
  ctx = make(PRT_BACKEND_AUTO, PRT_SIMD_ISA_NONE);
  EXPECT_EQ(info(ctx, PRT_BACKEND_SIMD).usable, 0u);
  EXPECT_EQ(prt_context_backend(ctx), PRT_BACKEND_CPU);
  prt_context_destroy(ctx);
}

struct Warnings {
  int count = 0;
  static void sink(void* user, prt_result, prt_severity severity, const char*) {
    if (severity == PRT_SEVERITY_WARNING) ++static_cast<Warnings*>(user)->count;
  }
};

// The variables count only for a context created with PRT_CONTEXT_READ_ENVIRONMENT.
TEST(Backend, EnvironmentVariablesLowerTheLimitsWhenAskedTo) {
  const uint32_t simd_here =
      uint32_t(PRT_TEST_SIMD_COMPILED && isa_from_proc_cpuinfo() >= PRT_SIMD_ISA_SSE41);
  setenv("PRT_BACKEND", "cpu", 1);
  prt_context* ctx = make(PRT_BACKEND_AUTO, PRT_SIMD_ISA_AUTO, PRT_CONTEXT_READ_ENVIRONMENT);
  EXPECT_EQ(prt_context_backend(ctx), PRT_BACKEND_CPU);
  EXPECT_EQ(info(ctx, PRT_BACKEND_SIMD).usable, 0u);
  prt_context_destroy(ctx);
  ctx = make();  // the default ignores the environment
  EXPECT_EQ(info(ctx, PRT_BACKEND_SIMD).usable, simd_here);
  prt_context_destroy(ctx);
  unsetenv("PRT_BACKEND");

  if (simd_here) {
    setenv("PRT_SIMD_ISA", "sse4.1", 1);
    ctx = make(PRT_BACKEND_AUTO, PRT_SIMD_ISA_AUTO, PRT_CONTEXT_READ_ENVIRONMENT);
    EXPECT_EQ(info(ctx, PRT_BACKEND_SIMD).isa, PRT_SIMD_ISA_SSE41);
    prt_context_destroy(ctx);
    ctx = make();
    EXPECT_EQ(info(ctx, PRT_BACKEND_SIMD).isa, isa_from_proc_cpuinfo());
    prt_context_destroy(ctx);
    // Every name is known (no warning); avx512 on a CPU without it leaves the CPU's best.
    for (const char* name : {"avx2", "avx512"}) {
      Warnings seen;
      prt_context_desc desc = prt::sized<prt_context_desc>();
      desc.message = &Warnings::sink;
      desc.message_user = &seen;
      desc.flags = PRT_CONTEXT_READ_ENVIRONMENT;
      setenv("PRT_SIMD_ISA", name, 1);
      ASSERT_EQ(prt_context_create(&desc, &ctx), PRT_OK);
      EXPECT_EQ(seen.count, 0) << name;
      EXPECT_EQ(info(ctx, PRT_BACKEND_SIMD).isa,
                std::string(name) == "avx2" ? std::min(PRT_SIMD_ISA_AVX2, isa_from_proc_cpuinfo())
                                            : isa_from_proc_cpuinfo())
          << name;
      prt_context_destroy(ctx);
    }
    unsetenv("PRT_SIMD_ISA");
  }

  Warnings warnings;
  prt_context_desc desc = prt::sized<prt_context_desc>();
  desc.message = &Warnings::sink;
  desc.message_user = &warnings;
  setenv("PRT_BACKEND", "quantum", 1);
  ASSERT_EQ(prt_context_create(&desc, &ctx), PRT_OK);
  EXPECT_EQ(warnings.count, 0) << "not read without the flag";
  prt_context_destroy(ctx);
  desc.flags = PRT_CONTEXT_READ_ENVIRONMENT;
  ASSERT_EQ(prt_context_create(&desc, &ctx), PRT_OK);
  EXPECT_EQ(warnings.count, 1) << "an unknown value is reported and ignored";
  prt_context_destroy(ctx);
  unsetenv("PRT_BACKEND");
}

TEST(Backend, Names) {
  EXPECT_STREQ(prt_backend_name(PRT_BACKEND_SIMD), "simd");
  EXPECT_STREQ(prt_backend_name(static_cast<prt_backend>(77)), "unknown");
  EXPECT_STREQ(prt_simd_isa_name(PRT_SIMD_ISA_AVX2), "avx2");
  EXPECT_STREQ(prt_simd_isa_name(PRT_SIMD_ISA_AVX512), "avx512");
}

}  // namespace
