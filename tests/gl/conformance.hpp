// SPDX-License-Identifier: MIT
// Backend conformance, shared by every technique's cases (tests/<t>/gl/<t>_conformance.cpp) and
// the runner (conformance_test.cpp, one table row per technique): the same asset shaded by the
// scalar reference, by the SIMD backend once per instruction set the CPU has (forced with
// simd_isa_limit) and by GL, each within the technique's tolerance of the reference, which is
// itself first checked against the exact double sum. Every case prints one summary line.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "support/gl_test_util.hpp"

namespace prt_conformance {

// Vertices of every conformance asset: a prime, so no backend's blocking divides it.
constexpr uint32_t kVertices = 10007;

// One test: its name (after the technique's, e.g. "Order6Rgb16Bit") and body.
struct Case {
  std::string name;
  std::function<void()> run;
};

// Per vertex and channel: the exact value and the magnitude the tolerance scales with.
struct Truth {
  std::vector<double> value, magnitude;
};

// The one-line summary of a case: what was compared (with the largest |error| / tolerance seen)
// and what was skipped and why.
struct Summary {
  std::string text;
  explicit Summary(std::string what) : text(std::move(what) + ":") {}
  void note(const std::string& backend, double worst) {
    char line[128];
    std::snprintf(line, sizeof line, " %s (max err/tol %.3g)", backend.c_str(), worst);
    text += line;
  }
  void skip(const std::string& backend, const std::string& why) {
    text += " [skipped " + backend + ": " + why + "]";
  }
  void print(const char* technique) const {
    std::printf("conformance %s %s\n", technique, text.c_str());
    ::testing::Test::RecordProperty("backends", text);
  }
};

// Calls run(context, name) once per SIMD instruction set this CPU has, in a context limited to
// it; notes the ones it skips (not compiled, not usable, or above the CPU) in the summary.
inline void for_each_simd_isa(Summary& summary,
                              const std::function<void(prt_context*, const std::string&)>& run) {
  for (prt_simd_isa isa : {PRT_SIMD_ISA_SSE41, PRT_SIMD_ISA_AVX2, PRT_SIMD_ISA_AVX512}) {
    const std::string name = std::string("simd/") + prt_simd_isa_name(isa);
    const prt::ContextPtr ctx = prt_test::limited_context(PRT_BACKEND_AUTO, isa);
    prt_backend_info info = prt::sized<prt_backend_info>();
    ASSERT_EQ(prt_backend_get_info(ctx.get(), PRT_BACKEND_SIMD, &info), PRT_OK);
    if (!info.compiled || !info.usable || info.isa != isa) {
      summary.skip(name, !info.compiled || !info.usable
                             ? std::string(info.note)
                             : "this CPU tops out at " + std::string(prt_simd_isa_name(info.isa)));
      continue;
    }
    run(ctx.get(), name);
  }
}

}  // namespace prt_conformance
