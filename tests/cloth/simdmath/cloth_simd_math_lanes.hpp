// SPDX-License-Identifier: MIT
// The functions of runtime/src/cloth/cloth_simd_math.h over arrays, from
// cloth_simd_math_lanes.cpp, the only file compiled with -mavx2 -mfma: callers check
// cpu_has_avx2_fma() first.
#pragma once

#include <cstddef>

namespace prt_simdmath_test {

// The unary functions of the header.
enum class Unary { kExp, kExpNeg, kLog, kSin, kCos, kAsin, kAcos, kErfc, kNormalCdf, kQuantile };
// The lane-wise basics (b is the second operand; select picks a where mask's lane is non-zero).
enum class Binary { kAtan2, kNormalCdfDiff, kMin, kMax, kSelect };

bool cpu_has_avx2_fma();

// out[i] = f(x[i]) for i < n, eight lanes at a time (the last group padded).
void eval_unary(Unary f, const float* x, float* out, std::size_t n);
// out[i] = f(a[i], b[i]); atan2 takes (y, x) = (a, b), the CDF difference Phi(b) - Phi(a); select
// reads mask[i] (null otherwise).
void eval_binary(Binary f, const float* a, const float* b, const float* mask, float* out,
                 std::size_t n);
// s[i], c[i] = sin x[i], cos x[i] from one prt_v8_sincos call per group.
void eval_sincos(const float* x, float* s, float* c, std::size_t n);
// out[i] = |x[i]| by prt_v8_abs.
void eval_abs(const float* x, float* out, std::size_t n);

}  // namespace prt_simdmath_test
