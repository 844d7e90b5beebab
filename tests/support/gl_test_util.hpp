// SPDX-License-Identifier: MIT
// Shared by the GL tests: the headless context (or a stated skip), loader wrappers (hiding an
// entry point, lying about the version or the SSBO limit), and the float-rounding tolerances every
// backend is held to (sh and wavelet).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <prt/prt.hpp>

#include "headless_gl.h"
#include "sh/sh_blob_test_util.hpp"
#include "support/counting_allocator.hpp"
#include "support/gl_state.hpp"
#include "support/limited_context.hpp"
#include "wavelet/wavelet_blob_test_util.hpp"

namespace prt_test {

// The headless GL context of one test (each test runs in its own process under ctest).
struct HeadlessGl {
  headless_gl* gl = nullptr;
  std::string error;
  HeadlessGl() {
    char text[1024];
    gl = headless_gl_create(text, sizeof text);
    if (!gl) error = text;
  }
  ~HeadlessGl() { headless_gl_destroy(gl); }
  HeadlessGl(const HeadlessGl&) = delete;
  HeadlessGl& operator=(const HeadlessGl&) = delete;
};

inline bool no_gl_allowed() {
  const char* allow = std::getenv("PRT_TEST_ALLOW_NO_GL");
  return allow && std::strcmp(allow, "1") == 0;
}

// Creates `name` (a HeadlessGl) or ends the test: a failure, unless PRT_TEST_ALLOW_NO_GL=1 says
// this machine has no EGL/GL, then a skip with the reason.
#define PRT_REQUIRE_GL(name)                                                        \
  ::prt_test::HeadlessGl name;                                                      \
  if (!name.gl) {                                                                   \
    if (::prt_test::no_gl_allowed())                                                \
      GTEST_SKIP() << "no headless GL (PRT_TEST_ALLOW_NO_GL=1): " << name.error;    \
    FAIL() << "no headless GL 4.3 context: " << name.error                          \
           << " (set PRT_TEST_ALLOW_NO_GL=1 to skip on machines without EGL/Mesa)"; \
  }

using ContextPtr = prt::ContextPtr;
using ShaderPtr = prt::GlShShaderPtr;
using WaveletShaderPtr = prt::GlWaveletShaderPtr;

// A light with the spread of a real environment's projection: a bright sky term, a "sun"
// (the SH projection of a delta light, which excites every band) and a small random rest.
inline std::vector<float> realistic_light(uint32_t order, uint32_t seed) {
  const uint32_t n2 = order * order;
  std::vector<float> sun(n2), light(3 * size_t(n2));
  const float sun_dir[3] = {0.3f, 0.8f, -0.5f};
  EXPECT_EQ(prt_sh_eval(order, sun_dir, sun.data()), PRT_OK);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const float sun_rgb[3] = {9.0f, 8.0f, 6.5f}, sky_rgb[3] = {1.2f, 1.5f, 2.1f};
  for (uint32_t k = 0; k < n2; ++k)
    for (uint32_t c = 0; c < 3; ++c)
      light[3 * k + c] =
          sun_rgb[c] * sun[k] + (k == 0 ? sky_rgb[c] * 3.5449077f : 0.0f) + 0.05f * unit(rng);
  return light;
}

// Exact (double) radiance of vertex v, channel ch, from the stored q/offset/scale, and the sum of
// the magnitudes of its terms when evaluated as sum_j offset_j L_j + sum_j q_j (scale_j L_j).
struct Expected {
  double value, magnitude;
};
inline Expected expected_radiance(const Transfer& t, const std::vector<float>& light, uint32_t v,
                                  uint32_t ch) {
  const uint32_t n2 = t.order * t.order, base = (t.channels == 3 ? ch : 0u) * n2;
  Expected e{0.0, 0.0};
  for (uint32_t k = 0; k < n2; ++k) {
    const uint32_t j = base + k;
    const double l = light[3 * size_t(k) + ch];
    const double scaled = double(t.scale[j]) * double(t.q[size_t(v) * t.coefficients() + j]);
    e.value += (double(t.offset[j]) + scaled) * l;
    e.magnitude += (std::fabs(double(t.offset[j])) + std::fabs(scaled)) * std::fabs(l);
  }
  return e;
}

// The tolerance every backend is held to, from the standard forward error bound of a float dot
// product (Higham, Accuracy and Stability of Numerical Algorithms, §3.1): sum_j a_j b_j evaluated
// with n float products and additions in any order (any blocking or lane split) errs by at most
// gamma_n sum_j |a_j b_j|, gamma_n = n u / (1 - n u), u = 2^-24. A backend dequantises
// (offset + scale q: 2 roundings) or folds (scale L: 1 rounding) before the order² products and
// order² + 1 additions, and rounds to float at the end, so n = order² + 8 covers it, with
// S = sum_j (|offset_j| + |scale_j q_j|) |L_j| (the terms as the backends see them; S >=
// sum_j |t_j L_j|). The bound is doubled so that it also holds between two float evaluations
// (a backend against the scalar reference, which rounds too); `tiny` absorbs flushed denormals.
// Typical errors are about sqrt(n) u S, far inside.
inline double tolerance(uint32_t order, double magnitude) {
  const double u = std::ldexp(1.0, -24), n = double(order) * order + 8.0;
  return 2.0 * (n * u / (1.0 - n * u)) * magnitude + 1e-30;
}

// Loader wrappers: the real loader with one name hidden, or with glGetIntegerv/glGetInteger64v
// answering chosen values.
struct LoaderOverride {
  headless_gl* gl = nullptr;
  const char* hidden = nullptr;
  static void* get(void* user, const char* name) {
    auto* self = static_cast<LoaderOverride*>(user);
    if (self->hidden && std::strcmp(name, self->hidden) == 0) return nullptr;
    return headless_gl_get_proc(self->gl, name);
  }
};

// The tolerance of a `wavelet` shade against the exact double sum (wvlt_reference_shade), from
// the same bound: every backend computes vs * sum_j q_j (L_j bs_j) with the prepared light
// rounded once (L bs), one product per pair (q is an exact 8-bit integer), pairs - 1 additions
// in any order (stored order, blocked, lane split, fused or not) and one final product by vs, so
// the computed value errs by at most gamma_n sum_j |q_j bs_j vs L_j| with n = pairs + 3; n =
// pairs + 4 leaves a margin for a final conversion. Doubled, as above, so that it also holds
// between two float backends; `tiny` absorbs flushed denormals.
inline double wavelet_tolerance(size_t pairs, double magnitude) {
  const double u = std::ldexp(1.0, -24), n = double(pairs) + 4.0;
  return 2.0 * (n * u / (1.0 - n * u)) * magnitude + 1e-30;
}

// The prepared light computed here, independently of prt_wavelet_prepare_light:
// prepared[j] = float(L[j] * bs[band(j)]) with the band from the test util's own formula.
inline std::vector<float> wavelet_prepared(const WvltTransfer& t, const std::vector<float>& light) {
  std::vector<float> prepared(light.size());
  for (uint32_t j = 0; j < t.coefficients(); ++j)
    for (uint32_t c = 0; c < 4; ++c)
      prepared[4 * size_t(j) + c] =
          c == 3 ? 0.0f : float(double(light[4 * size_t(j) + c]) * t.band_scale[t.band(j)]);
  return prepared;
}

// A loader that lies about the context: user = "version" answers GL 3.3, user = "ssbo" a
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE of 1024 bytes; everything else is the real entry point.
inline void old_version_get_integerv(unsigned pname, int* data) {
  gl_function<gl_names::GetIntegervFn>("glGetIntegerv")(pname, data);
  if (pname == 0x821B) *data = 3;  // GL_MAJOR_VERSION
  if (pname == 0x821C) *data = 3;  // GL_MINOR_VERSION
}
inline void small_ssbo_get_integer64v(unsigned pname, int64_t* data) {
  gl_function<gl_names::GetInteger64vFn>("glGetInteger64v")(pname, data);
  if (pname == 0x90DE) *data = 1024;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
}
inline void* lying_loader(void* user, const char* name) {
  const char* lie = static_cast<const char*>(user);
  if (std::strcmp(lie, "version") == 0 && std::strcmp(name, "glGetIntegerv") == 0)
    return as_address(&old_version_get_integerv);
  if (std::strcmp(lie, "ssbo") == 0 && std::strcmp(name, "glGetInteger64v") == 0)
    return as_address(&small_ssbo_get_integer64v);
  return headless_gl_get_proc(nullptr, name);
}

}  // namespace prt_test
