/* SPDX-License-Identifier: MIT */
/* Backend query: which backends are compiled in and usable; SIMD ISA detection at run time. */
#include "internal.h"

#if !defined(PRT_NO_SIMD) && (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#include <cpuid.h>

/* Whether the OS saves the AVX-512 state on a context switch: XCR0 bits 1-2 (SSE, AVX) and 5-7
 * (opmask, upper halves of zmm0-15, zmm16-31), read by XGETBV once CPUID says OSXSAVE. */
static int os_saves_avx512(void) {
  unsigned eax, ebx, ecx, edx, xcr0_low, xcr0_high;
  if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx) || !(ecx & (1u << 27))) return 0;
  __asm__ volatile("xgetbv" : "=a"(xcr0_low), "=d"(xcr0_high) : "c"(0));
  (void)xcr0_high;
  return (xcr0_low & 0xE6u) == 0xE6u;
}
#endif

prt_simd_isa prt_internal_detect_simd_isa(void) {
#if defined(PRT_NO_SIMD)
  return PRT_SIMD_ISA_NONE;
#elif (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
  __builtin_cpu_init();
  /* gcc returns a non-zero bit mask, not 1, for a supported feature. */
  if (__builtin_cpu_supports("avx2") != 0 && __builtin_cpu_supports("fma") != 0) {
    if (__builtin_cpu_supports("avx512f") != 0 && __builtin_cpu_supports("avx512bw") != 0 &&
        __builtin_cpu_supports("avx512dq") != 0 && __builtin_cpu_supports("avx512vl") != 0 &&
        __builtin_cpu_supports("avx512vnni") != 0 && os_saves_avx512())
      return PRT_SIMD_ISA_AVX512;
    return PRT_SIMD_ISA_AVX2;
  }
  if (__builtin_cpu_supports("sse4.1") != 0) return PRT_SIMD_ISA_SSE41;
  return PRT_SIMD_ISA_NONE;
#else
  return PRT_SIMD_ISA_NONE;
#endif
}

#if !defined(PRT_NO_SIMD) || defined(PRT_HAS_GL)
static int backend_allowed(const prt_context* context, prt_backend backend) {
  return context->backend_limit == PRT_BACKEND_AUTO || backend <= context->backend_limit;
}
#endif

/* Fills *out (every field) for a concrete backend; PRT_ERROR_INVALID_ARGUMENT otherwise. */
static prt_result describe(const prt_context* context, prt_backend backend, prt_backend_info* out) {
  out->struct_size = sizeof *out;
  out->backend = backend;
  out->isa = PRT_SIMD_ISA_NONE;
  out->name = prt_backend_name(backend);
  switch (backend) {
    case PRT_BACKEND_CPU:
      out->compiled = 1;
      out->usable = 1; /* the reference is never limited away */
      out->note = "scalar reference";
      return PRT_OK;
    case PRT_BACKEND_SIMD:
#if defined(PRT_NO_SIMD)
      out->compiled = 0;
      out->usable = 0;
      out->note = "compiled out (PRT_ENABLE_SIMD=OFF)";
#else
      out->compiled = 1;
      out->usable = 0;
      if (!backend_allowed(context, backend)) {
        out->note = "disabled by the context's backend limit";
      } else if (context->simd_isa < PRT_SIMD_ISA_SSE41) {
        out->note = "no SSE4.1 on this CPU, or disabled by the SIMD ISA limit";
      } else {
        out->usable = 1;
        out->isa = context->simd_isa;
        out->note = prt_simd_isa_name(context->simd_isa);
      }
#endif
      return PRT_OK;
    case PRT_BACKEND_GL:
#if defined(PRT_HAS_GL)
      /* Usable means "allowed": whether the application has a GL 4.3+ context is only known
       * when it calls prt_gl_sh_create with its loader. */
      out->compiled = 1;
      out->usable = (uint32_t)backend_allowed(context, backend);
      out->note = out->usable ? "usable with the application's GL 4.3+ context"
                              : "disabled by the context's backend limit";
#else
      out->compiled = 0;
      out->usable = 0;
      out->note = "compiled out (PRT_ENABLE_GL=OFF)";
#endif
      return PRT_OK;
    case PRT_BACKEND_AUTO:
      break;
  }
  out->name = "unknown";
  out->compiled = out->usable = 0;
  out->note = "not a concrete backend";
  return PRT_ERROR_INVALID_ARGUMENT;
}

prt_result prt_backend_get_info(const prt_context* context, prt_backend backend,
                                prt_backend_info* out) {
  prt_backend_info info;
  prt_result r;
  if (!context || !out || !prt_internal_struct_size_ok(out, PRT_BACKEND_INFO_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  r = describe(context, backend, &info);
  prt_internal_write_struct(out, &info, sizeof info);
  return r;
}

prt_simd_isa prt_internal_simd_isa(const prt_context* context) {
  prt_backend_info info;
  if (describe(context, PRT_BACKEND_SIMD, &info) != PRT_OK || !info.usable)
    return PRT_SIMD_ISA_NONE;
  return info.isa;
}

prt_backend prt_context_backend(const prt_context* context) {
  if (context && prt_internal_simd_isa(context) != PRT_SIMD_ISA_NONE) return PRT_BACKEND_SIMD;
  return PRT_BACKEND_CPU;
}

const char* prt_backend_name(prt_backend backend) {
  switch (backend) {
    case PRT_BACKEND_AUTO:
      return "auto";
    case PRT_BACKEND_CPU:
      return "cpu";
    case PRT_BACKEND_SIMD:
      return "simd";
    case PRT_BACKEND_GL:
      return "gl";
  }
  return "unknown";
}

const char* prt_simd_isa_name(prt_simd_isa isa) {
  switch (isa) {
    case PRT_SIMD_ISA_AUTO:
      return "auto";
    case PRT_SIMD_ISA_NONE:
      return "none";
    case PRT_SIMD_ISA_SSE41:
      return "sse4.1";
    case PRT_SIMD_ISA_AVX2:
      return "avx2";
    case PRT_SIMD_ISA_AVX512:
      return "avx512";
  }
  return "unknown";
}
