// SPDX-License-Identifier: MIT
// cloth_simd_math.h over arrays (cloth_simd_math_lanes.hpp). Compiled with -mavx2 -mfma.
#include "cloth_simd_math_lanes.hpp"

#include <algorithm>
#include <cstring>

extern "C" {
#include "cloth_simd_math.h"
}

namespace prt_simdmath_test {
namespace {

__m256 apply(Unary f, __m256 x) {
  __m256 s, c;
  switch (f) {
    case Unary::kExp:
      return prt_v8_exp(x);
    case Unary::kExpNeg:
      return prt_v8_exp_neg(x);
    case Unary::kLog:
      return prt_v8_log(x);
    case Unary::kSin:
      prt_v8_sincos(x, &s, &c);
      return s;
    case Unary::kCos:
      prt_v8_sincos(x, &s, &c);
      return c;
    case Unary::kAsin:
      return prt_v8_asin(x);
    case Unary::kAcos:
      return prt_v8_acos(x);
    case Unary::kErfc:
      return prt_v8_erfc(x);
    case Unary::kNormalCdf:
      return prt_v8_normal_cdf(x);
    case Unary::kQuantile:
      return prt_v8_normal_quantile(x);
  }
  return x;
}

// The switch hoisted out of the loop, so that each function runs in a loop of its own (the
// benchmark times these loops).
template <Unary F>
void unary_loop(const float* x, float* out, std::size_t n) {
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) _mm256_storeu_ps(out + i, apply(F, _mm256_loadu_ps(x + i)));
  if (i == n) return;
  float in[8] = {0}, res[8];
  std::memcpy(in, x + i, (n - i) * sizeof(float));
  _mm256_storeu_ps(res, apply(F, _mm256_loadu_ps(in)));
  std::memcpy(out + i, res, (n - i) * sizeof(float));
}

__m256 apply(Binary f, __m256 a, __m256 b, __m256 mask) {
  switch (f) {
    case Binary::kAtan2:
      return prt_v8_atan2(a, b);
    case Binary::kNormalCdfDiff:
      return prt_v8_normal_cdf_diff(a, b);
    case Binary::kMin:
      return prt_v8_min(a, b);
    case Binary::kMax:
      return prt_v8_max(a, b);
    case Binary::kSelect:
      return prt_v8_select(_mm256_cmp_ps(mask, _mm256_setzero_ps(), _CMP_NEQ_UQ), a, b);
  }
  return a;
}

template <Binary F>
void binary_loop(const float* a, const float* b, const float* mask, float* out, std::size_t n) {
  const __m256 zero = _mm256_setzero_ps();
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    _mm256_storeu_ps(out + i, apply(F, _mm256_loadu_ps(a + i), _mm256_loadu_ps(b + i),
                                    mask ? _mm256_loadu_ps(mask + i) : zero));
  if (i == n) return;
  float va[8] = {0}, vb[8] = {0}, vm[8] = {0}, res[8];
  std::memcpy(va, a + i, (n - i) * sizeof(float));
  std::memcpy(vb, b + i, (n - i) * sizeof(float));
  if (mask) std::memcpy(vm, mask + i, (n - i) * sizeof(float));
  _mm256_storeu_ps(res, apply(F, _mm256_loadu_ps(va), _mm256_loadu_ps(vb), _mm256_loadu_ps(vm)));
  std::memcpy(out + i, res, (n - i) * sizeof(float));
}

}  // namespace

bool cpu_has_avx2_fma() {
  return __builtin_cpu_supports("avx2") != 0 && __builtin_cpu_supports("fma") != 0;
}

void eval_unary(Unary f, const float* x, float* out, std::size_t n) {
  switch (f) {
#define PRT_CASE(name)                  \
  case Unary::name:                     \
    unary_loop<Unary::name>(x, out, n); \
    return;
    PRT_CASE(kExp)
    PRT_CASE(kExpNeg)
    PRT_CASE(kLog)
    PRT_CASE(kSin)
    PRT_CASE(kCos)
    PRT_CASE(kAsin)
    PRT_CASE(kAcos)
    PRT_CASE(kErfc)
    PRT_CASE(kNormalCdf)
    PRT_CASE(kQuantile)
#undef PRT_CASE
  }
}

void eval_binary(Binary f, const float* a, const float* b, const float* mask, float* out,
                 std::size_t n) {
  switch (f) {
#define PRT_CASE(name)                             \
  case Binary::name:                               \
    binary_loop<Binary::name>(a, b, mask, out, n); \
    return;
    PRT_CASE(kAtan2)
    PRT_CASE(kNormalCdfDiff)
    PRT_CASE(kMin)
    PRT_CASE(kMax)
    PRT_CASE(kSelect)
#undef PRT_CASE
  }
}

void eval_sincos(const float* x, float* s, float* c, std::size_t n) {
  __m256 vs, vc;
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    prt_v8_sincos(_mm256_loadu_ps(x + i), &vs, &vc);
    _mm256_storeu_ps(s + i, vs);
    _mm256_storeu_ps(c + i, vc);
  }
  if (i == n) return;
  float in[8] = {0}, rs[8], rc[8];
  std::memcpy(in, x + i, (n - i) * sizeof(float));
  prt_v8_sincos(_mm256_loadu_ps(in), &vs, &vc);
  _mm256_storeu_ps(rs, vs);
  _mm256_storeu_ps(rc, vc);
  std::memcpy(s + i, rs, (n - i) * sizeof(float));
  std::memcpy(c + i, rc, (n - i) * sizeof(float));
}

void eval_abs(const float* x, float* out, std::size_t n) {
  for (std::size_t i = 0; i < n; i += 8) {
    const std::size_t m = std::min<std::size_t>(8, n - i);
    float in[8] = {0}, res[8];
    std::memcpy(in, x + i, m * sizeof(float));
    _mm256_storeu_ps(res, prt_v8_abs(_mm256_loadu_ps(in)));
    std::memcpy(out + i, res, m * sizeof(float));
  }
}

}  // namespace prt_simdmath_test
