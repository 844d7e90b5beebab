/* SPDX-License-Identifier: MIT */
/* Private to the runtime's AVX2 kernels of `cloth`: float x 8 transcendental functions for the
 * shading quadratures, with no libm call, no table and no gather. Only translation units built
 * with -mavx2 -mfma include it (prt_runtime_simd_sources AVX2 in runtime/CMakeLists.txt).
 *
 * Each function reduces its argument the usual way (Cody-Waite by ln 2 or pi/2, exponent split,
 * ratio of the smaller to the larger magnitude) and evaluates a polynomial or rational function
 * whose float coefficients are weighted minimax fits, made for these reductions, of the reduced
 * function (tests/cloth/simdmath/fit_coefficients.py refits them). The accuracy stated on each
 * function is the bound its test (tests/cloth/simdmath) checks against libm in double over dense
 * sweeps of the domain. An ulp is that of the exact result rounded to float. They assume MXCSR's
 * defaults (round to nearest, exceptions masked; with FTZ/DAZ set, denormals count as 0) and may
 * set its sticky status flags. */
#ifndef PRT_RUNTIME_CLOTH_SIMD_MATH_H
#define PRT_RUNTIME_CLOTH_SIMD_MATH_H

#if !defined(__AVX2__) || !defined(__FMA__)
#error "cloth_simd_math.h needs AVX2 and FMA: compile this file with -mavx2 -mfma"
#endif

#include <immintrin.h>
#include <math.h> /* INFINITY only */

/* ---- Lane-wise basics ------------------------------------------------------------------------ */

#define PRT_V8_CONST(c) _mm256_set1_ps(c)

/* |x|, exact (clears the sign bit, NaN stays NaN). */
static inline __m256 prt_v8_abs(__m256 x) {
  return _mm256_andnot_ps(PRT_V8_CONST(-0.0f), x);
}

/* The smaller of a and b, exact; b where either is NaN (vminps). */
static inline __m256 prt_v8_min(__m256 a, __m256 b) {
  return _mm256_min_ps(a, b);
}

/* The larger of a and b, exact; b where either is NaN (vmaxps). */
static inline __m256 prt_v8_max(__m256 a, __m256 b) {
  return _mm256_max_ps(a, b);
}

/* a where mask's lane is set, else b; mask from a comparison (only its sign bits are read). */
static inline __m256 prt_v8_select(__m256 mask, __m256 a, __m256 b) {
  return _mm256_blendv_ps(b, a, mask);
}

/* a b + c with one rounding. */
static inline __m256 prt_v8_fma(__m256 a, __m256 b, __m256 c) {
  return _mm256_fmadd_ps(a, b, c);
}

/* x with the sign bit of x xor that of s. */
static inline __m256 prt_v8_xorsign(__m256 x, __m256 s) {
  return _mm256_xor_ps(x, _mm256_and_ps(s, PRT_V8_CONST(-0.0f)));
}

/* 2^n for integer lanes n in [-126, 127]. */
static inline __m256 prt_v8_pow2i(__m256i n) {
  return _mm256_castsi256_ps(_mm256_slli_epi32(_mm256_add_epi32(n, _mm256_set1_epi32(127)), 23));
}

/* ---- Exponential ----------------------------------------------------------------------------- */

/* e^x = 2^n e^r: n = round(x / ln 2) in *n, r = x - n ln 2 in [-ln2 / 2, ln2 / 2] with ln 2 in two
 * floats (with FMA, n float(ln 2) is subtracted exactly); returns e^r = 1 + r + r^2 P(r). */
static inline __m256 prt_v8_exp_reduced(__m256 x, __m256i* n) {
  const __m256 k = _mm256_round_ps(_mm256_mul_ps(x, PRT_V8_CONST(1.442695022e+00f)),
                                   _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  __m256 r = _mm256_fnmadd_ps(k, PRT_V8_CONST(6.931471825e-01f), x);
  r = _mm256_fnmadd_ps(k, PRT_V8_CONST(-1.904654212e-09f), r);
  __m256 p = PRT_V8_CONST(1.382146846e-03f);
  p = prt_v8_fma(p, r, PRT_V8_CONST(8.368662558e-03f));
  p = prt_v8_fma(p, r, PRT_V8_CONST(4.166825488e-02f));
  p = prt_v8_fma(p, r, PRT_V8_CONST(1.666652113e-01f));
  p = prt_v8_fma(p, r, PRT_V8_CONST(4.999999404e-01f));
  p = prt_v8_fma(p, _mm256_mul_ps(r, r), r);
  *n = _mm256_cvtps_epi32(k);
  return _mm256_add_ps(p, PRT_V8_CONST(1.0f));
}

/* m e^x for x in [-105, 89] (clamped there; NaN stays NaN), m in [0, 2]: the power of two is
 * applied last and in two halves, so that a result in the denormals is rounded once. */
static inline __m256 prt_v8_exp_times(__m256 x, __m256 m) {
  /* Operand order keeps NaN: vmaxps and vminps return their second operand on NaN. */
  x = _mm256_min_ps(PRT_V8_CONST(89.0f), _mm256_max_ps(PRT_V8_CONST(-105.0f), x));
  __m256i n;
  const __m256 p = _mm256_mul_ps(prt_v8_exp_reduced(x, &n), m);
  const __m256i half = _mm256_srai_epi32(n, 1);
  return _mm256_mul_ps(_mm256_mul_ps(p, prt_v8_pow2i(half)),
                       prt_v8_pow2i(_mm256_sub_epi32(n, half)));
}

/* e^x within 2 ulp for x in [-104, 88.72], denormal results included (an ulp there is 2^-149),
 * so 0 below -103.972; +inf above 88.72, NaN for NaN. */
static inline __m256 prt_v8_exp(__m256 x) {
  return prt_v8_exp_times(x, PRT_V8_CONST(1.0f));
}

/* e^x for x in [-87.3, 88] within 2 ulp, one scaling cheaper than prt_v8_exp: x below -87.3
 * (results under FLT_MIN) gives a denormal or 0, and 0 from -87.7 down; NaN for NaN. */
static inline __m256 prt_v8_exp_neg(__m256 x) {
  x = _mm256_min_ps(PRT_V8_CONST(88.0f), _mm256_max_ps(PRT_V8_CONST(-88.0f), x));
  __m256i n;
  const __m256 p = prt_v8_exp_reduced(x, &n);
  /* n = -127 gives the bit pattern of +0. */
  return _mm256_mul_ps(p, prt_v8_pow2i(n));
}

/* ---- Logarithm ------------------------------------------------------------------------------- */

/* ln x within 2 ulp for every positive float, denormals included; -inf for +-0, +inf for +inf,
 * NaN for x < 0 and NaN. */
static inline __m256 prt_v8_log(__m256 x) {
  /* Denormals are scaled by 2^23 first. */
  const __m256 tiny = _mm256_cmp_ps(x, PRT_V8_CONST(1.175494351e-38f), _CMP_LT_OQ);
  const __m256 scaled = prt_v8_select(tiny, _mm256_mul_ps(x, PRT_V8_CONST(8388608.0f)), x);
  /* x = 2^e m with m in [sqrt(1/2), sqrt(2)): the exponent of x / sqrt(1/2), in integers. */
  const __m256i off = _mm256_sub_epi32(_mm256_castps_si256(scaled), _mm256_set1_epi32(0x3f3504f3));
  const __m256 e = _mm256_sub_ps(_mm256_cvtepi32_ps(_mm256_srai_epi32(off, 23)),
                                 _mm256_and_ps(tiny, PRT_V8_CONST(23.0f)));
  const __m256i m_bits = _mm256_add_epi32(_mm256_and_si256(off, _mm256_set1_epi32(0x007fffff)),
                                          _mm256_set1_epi32(0x3f3504f3));
  const __m256 f = _mm256_sub_ps(_mm256_castsi256_ps(m_bits), PRT_V8_CONST(1.0f)); /* exact */
  /* ln(1 + f) = f - f^2 / 2 + f^3 P(f), the small terms summed first. */
  const __m256 f2 = _mm256_mul_ps(f, f);
  __m256 p = PRT_V8_CONST(-7.635894418e-02f);
  p = prt_v8_fma(p, f, PRT_V8_CONST(1.276211441e-01f));
  p = prt_v8_fma(p, f, PRT_V8_CONST(-1.315975338e-01f));
  p = prt_v8_fma(p, f, PRT_V8_CONST(1.420160979e-01f));
  p = prt_v8_fma(p, f, PRT_V8_CONST(-1.662340164e-01f));
  p = prt_v8_fma(p, f, PRT_V8_CONST(2.000124007e-01f));
  p = prt_v8_fma(p, f, PRT_V8_CONST(-2.500081956e-01f));
  p = prt_v8_fma(p, f, PRT_V8_CONST(3.333333135e-01f));
  __m256 y = prt_v8_fma(_mm256_mul_ps(p, f), f2, _mm256_mul_ps(e, PRT_V8_CONST(-1.904654212e-09f)));
  y = prt_v8_fma(f2, PRT_V8_CONST(-0.5f), y);
  y = prt_v8_fma(e, PRT_V8_CONST(6.931471825e-01f), _mm256_add_ps(f, y));
  /* +inf, zeros, then negatives and NaN (all bits set is a NaN). */
  y = prt_v8_select(_mm256_cmp_ps(x, PRT_V8_CONST(INFINITY), _CMP_EQ_OQ), x, y);
  y = prt_v8_select(_mm256_cmp_ps(x, _mm256_setzero_ps(), _CMP_EQ_OQ), PRT_V8_CONST(-INFINITY), y);
  return _mm256_or_ps(y, _mm256_cmp_ps(x, _mm256_setzero_ps(), _CMP_NGE_UQ));
}

/* ---- Sine and cosine ------------------------------------------------------------------------- */

/* sin x and cos x within 1e-7 (absolute) for |x| <= 2^18 (beyond, k = round(|x| 2/pi) taken in
 * float can miss by one, leaving r outside the polynomials' range); sin(-0) = -0; NaN for +-inf
 * and NaN. */
static inline void prt_v8_sincos(__m256 x, __m256* s, __m256* c) {
  const __m256 ax = prt_v8_abs(x);
  const __m256 k = _mm256_round_ps(_mm256_mul_ps(ax, PRT_V8_CONST(6.366197467e-01f)),
                                   _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  /* r = |x| - k pi/2 in [-pi/4, pi/4], pi/2 in two floats: the first step is exact with FMA, and
   * the third float of pi/2 would change r by under k 2^-48. */
  __m256 r = _mm256_fnmadd_ps(k, PRT_V8_CONST(1.570796371e+00f), ax);
  r = _mm256_fnmadd_ps(k, PRT_V8_CONST(-4.371138829e-08f), r);
  const __m256 r2 = _mm256_mul_ps(r, r);
  /* sin r = r + r^3 S(r^2), cos r = 1 - r^2 / 2 + r^4 C(r^2). */
  __m256 sp = PRT_V8_CONST(-1.949595753e-04f);
  sp = prt_v8_fma(sp, r2, PRT_V8_CONST(8.331982419e-03f));
  sp = prt_v8_fma(sp, r2, PRT_V8_CONST(-1.666665077e-01f));
  sp = prt_v8_fma(_mm256_mul_ps(sp, r2), r, r);
  __m256 cp = PRT_V8_CONST(2.443066842e-05f);
  cp = prt_v8_fma(cp, r2, PRT_V8_CONST(-1.388730132e-03f));
  cp = prt_v8_fma(cp, r2, PRT_V8_CONST(4.166664556e-02f));
  cp = prt_v8_fma(cp, r2, PRT_V8_CONST(-0.5f));
  cp = prt_v8_fma(cp, r2, PRT_V8_CONST(1.0f));
  /* Quadrant k mod 4: odd k swaps the two; sin is negative for k = 2, 3 (then odd in x), cos for
   * k = 1, 2. */
  const __m256i q = _mm256_cvtps_epi32(k);
  const __m256 odd = _mm256_castsi256_ps(
      _mm256_cmpeq_epi32(_mm256_and_si256(q, _mm256_set1_epi32(1)), _mm256_set1_epi32(1)));
  const __m256 sin_sign = _mm256_castsi256_ps(_mm256_slli_epi32(q, 30));
  const __m256 cos_sign =
      _mm256_castsi256_ps(_mm256_slli_epi32(_mm256_add_epi32(q, _mm256_set1_epi32(1)), 30));
  *s = prt_v8_xorsign(prt_v8_xorsign(prt_v8_select(odd, cp, sp), sin_sign), x);
  *c = prt_v8_xorsign(prt_v8_select(odd, sp, cp), cos_sign);
}

/* ---- Inverse trigonometric functions --------------------------------------------------------- */

/* atan2(y, x) within 2.5e-7 rad (an ulp of pi) for every finite y, x, quadrants and signed zeros as
 * C's atan2 (atan2(+-0, +0) = +-0, atan2(+-0, -0) = +-pi); one infinite argument as C's, both
 * infinite or either NaN gives NaN. */
static inline __m256 prt_v8_atan2(__m256 y, __m256 x) {
  const __m256 ax = prt_v8_abs(x), ay = prt_v8_abs(y);
  /* a = min / max in [0, 1]; the largest denominator is at least the smallest denormal, so that
   * 0 / 0 gives 0. */
  const __m256 a = _mm256_div_ps(
      _mm256_min_ps(ax, ay), _mm256_max_ps(_mm256_max_ps(ax, ay), PRT_V8_CONST(1.401298464e-45f)));
  const __m256 a2 = _mm256_mul_ps(a, a);
  /* atan a = a + a^3 T(a^2). */
  __m256 t = PRT_V8_CONST(-1.601653756e-03f);
  t = prt_v8_fma(t, a2, PRT_V8_CONST(1.002207026e-02f));
  t = prt_v8_fma(t, a2, PRT_V8_CONST(-2.943972312e-02f));
  t = prt_v8_fma(t, a2, PRT_V8_CONST(5.612037703e-02f));
  t = prt_v8_fma(t, a2, PRT_V8_CONST(-8.289344609e-02f));
  t = prt_v8_fma(t, a2, PRT_V8_CONST(1.091013476e-01f));
  t = prt_v8_fma(t, a2, PRT_V8_CONST(-1.425543576e-01f));
  t = prt_v8_fma(t, a2, PRT_V8_CONST(1.999761760e-01f));
  t = prt_v8_fma(t, a2, PRT_V8_CONST(-3.333326280e-01f));
  t = prt_v8_fma(_mm256_mul_ps(t, a2), a, a);
  /* The angle from the positive x axis, in [0, pi]: t, pi/2 - t, pi/2 + t or pi - t, the offset
   * carried in two floats (hi + lo) so that only the final sum rounds. */
  const __m256 swap = _mm256_cmp_ps(ay, ax, _CMP_GT_OQ);
  const __m256 x_neg = _mm256_castsi256_ps(_mm256_srai_epi32(_mm256_castps_si256(x), 31));
  const __m256 off_hi = prt_v8_select(swap, PRT_V8_CONST(1.570796371e+00f),
                                      _mm256_and_ps(x_neg, PRT_V8_CONST(3.141592741e+00f)));
  const __m256 off_lo = prt_v8_select(swap, PRT_V8_CONST(-4.371138829e-08f),
                                      _mm256_and_ps(x_neg, PRT_V8_CONST(-8.742277657e-08f)));
  t = prt_v8_xorsign(t, _mm256_xor_ps(swap, x_neg));
  t = _mm256_add_ps(_mm256_add_ps(off_lo, t), off_hi);
  t = _mm256_or_ps(t, _mm256_and_ps(y, PRT_V8_CONST(-0.0f)));
  return _mm256_or_ps(t, _mm256_cmp_ps(x, y, _CMP_UNORD_Q));
}

/* asin |x| = s + s^3 A(s^2) with s = |x| for |x| <= 1/2, else pi/2 - 2 asin s with
 * s = sqrt((1 - |x|) / 2). Returns that asin s (>= 0) and whether |x| > 1/2 in *big. */
static inline __m256 prt_v8_asin_reduced(__m256 x, __m256* big) {
  const __m256 ax = prt_v8_abs(x);
  *big = _mm256_cmp_ps(ax, PRT_V8_CONST(0.5f), _CMP_GT_OQ);
  /* 1 - |x| is exact for |x| >= 1/2. */
  const __m256 z =
      prt_v8_select(*big, _mm256_mul_ps(_mm256_sub_ps(PRT_V8_CONST(1.0f), ax), PRT_V8_CONST(0.5f)),
                    _mm256_mul_ps(ax, ax));
  const __m256 s = prt_v8_select(*big, _mm256_sqrt_ps(z), ax);
  __m256 p = PRT_V8_CONST(4.216239601e-02f);
  p = prt_v8_fma(p, z, PRT_V8_CONST(2.418275923e-02f));
  p = prt_v8_fma(p, z, PRT_V8_CONST(4.546946287e-02f));
  p = prt_v8_fma(p, z, PRT_V8_CONST(7.495307922e-02f));
  p = prt_v8_fma(p, z, PRT_V8_CONST(1.666675210e-01f));
  return prt_v8_fma(_mm256_mul_ps(p, z), s, s);
}

/* asin x within 1.5e-7 (absolute) for x in [-1, 1], asin(-0) = -0; NaN outside and for NaN. */
static inline __m256 prt_v8_asin(__m256 x) {
  __m256 big;
  const __m256 p = prt_v8_asin_reduced(x, &big);
  /* pi/2 - 2 p with pi/2 in two floats. */
  const __m256 far =
      _mm256_add_ps(_mm256_fnmadd_ps(PRT_V8_CONST(2.0f), p, PRT_V8_CONST(-4.371138829e-08f)),
                    PRT_V8_CONST(1.570796371e+00f));
  return prt_v8_xorsign(prt_v8_select(big, far, p), x);
}

/* acos x within 2.5e-7 (absolute, an ulp of pi) for x in [-1, 1]; NaN outside and for NaN. */
static inline __m256 prt_v8_acos(__m256 x) {
  __m256 big;
  const __m256 p = prt_v8_xorsign(prt_v8_asin_reduced(x, &big), x);
  /* |x| <= 1/2: pi/2 - p; x > 1/2: 2 p; x < -1/2: pi + 2 p (p signed as x). */
  const __m256 neg = _mm256_cmp_ps(x, _mm256_setzero_ps(), _CMP_LT_OQ);
  const __m256 off_hi = prt_v8_select(big, _mm256_and_ps(neg, PRT_V8_CONST(3.141592741e+00f)),
                                      PRT_V8_CONST(1.570796371e+00f));
  const __m256 off_lo = prt_v8_select(big, _mm256_and_ps(neg, PRT_V8_CONST(-8.742277657e-08f)),
                                      PRT_V8_CONST(-4.371138829e-08f));
  const __m256 k = prt_v8_select(big, PRT_V8_CONST(2.0f), PRT_V8_CONST(-1.0f));
  return _mm256_add_ps(prt_v8_fma(k, p, off_lo), off_hi);
}

/* ---- Complementary error function and the standard normal distribution ---------------------- */

/* erfc a for a >= 0 (NaN stays NaN), given a^2 = a2_hi + a2_lo exactly (a2_lo tiny):
 * erfc a = e^-a^2 R(a), R(a) = P(t) with t = 2 / (2 + a), fitted for a in [0, 10.5] (erfc is
 * below the smallest denormal beyond). e^-a^2 = e^-a2_hi (1 - a2_lo): a^2 rounded to float would
 * cost up to a^2 ulp. */
static inline __m256 prt_v8_erfc_nonneg(__m256 a, __m256 a2_hi, __m256 a2_lo) {
  const __m256 t = _mm256_div_ps(PRT_V8_CONST(2.0f), _mm256_add_ps(a, PRT_V8_CONST(2.0f)));
  __m256 r = PRT_V8_CONST(-5.583102629e-02f);
  r = prt_v8_fma(r, t, PRT_V8_CONST(2.679618895e-01f));
  r = prt_v8_fma(r, t, PRT_V8_CONST(-4.505742490e-01f));
  r = prt_v8_fma(r, t, PRT_V8_CONST(2.326784879e-01f));
  r = prt_v8_fma(r, t, PRT_V8_CONST(8.097195067e-03f));
  r = prt_v8_fma(r, t, PRT_V8_CONST(1.857427508e-01f));
  r = prt_v8_fma(r, t, PRT_V8_CONST(2.483594418e-01f));
  r = prt_v8_fma(r, t, PRT_V8_CONST(2.813792527e-01f));
  r = prt_v8_fma(r, t, PRT_V8_CONST(2.821908295e-01f));
  r = prt_v8_fma(r, t, PRT_V8_CONST(-4.606810762e-06f));
  return prt_v8_exp_times(_mm256_sub_ps(_mm256_setzero_ps(), a2_hi), _mm256_fnmadd_ps(r, a2_lo, r));
}

/* erfc x within 7 ulp (relative 4.2e-7) for every x, denormal results included (an ulp there is
 * 2^-149, so relative accuracy ends at x = 9.19), 2 below x = -3.9; erfc(+inf) = 0,
 * erfc(-inf) = 2, NaN for NaN. */
static inline __m256 prt_v8_erfc(__m256 x) {
  /* Clamped where erfc is 0 in float: a^2 stays finite. */
  const __m256 a = _mm256_min_ps(PRT_V8_CONST(10.5f), prt_v8_abs(x));
  const __m256 a2 = _mm256_mul_ps(a, a);
  const __m256 e = prt_v8_erfc_nonneg(a, a2, _mm256_fmsub_ps(a, a, a2));
  return prt_v8_select(_mm256_cmp_ps(x, _mm256_setzero_ps(), _CMP_LT_OQ),
                       _mm256_sub_ps(PRT_V8_CONST(2.0f), e), e);
}

/* Phi(z) = erfc(-z / sqrt 2) / 2, the standard normal CDF, within 7 ulp for every z, denormal
 * results included (relative accuracy ends at z = -12.95): better than 0.5 prt_v8_erfc(-z / sqrt
 * 2), whose rounded argument costs up to z^2 ulp. Phi(+inf) = 1, Phi(-inf) = 0, NaN for NaN. */
static inline __m256 prt_v8_normal_cdf(__m256 z) {
  const __m256 az = _mm256_min_ps(PRT_V8_CONST(14.8f), prt_v8_abs(z));
  const __m256 z2 = _mm256_mul_ps(az, az);
  const __m256 z2_lo = _mm256_fmsub_ps(az, az, z2);
  const __m256 half_tail =
      _mm256_mul_ps(prt_v8_erfc_nonneg(_mm256_mul_ps(az, PRT_V8_CONST(7.071067691e-01f)),
                                       _mm256_mul_ps(z2, PRT_V8_CONST(0.5f)),
                                       _mm256_mul_ps(z2_lo, PRT_V8_CONST(0.5f))),
                    PRT_V8_CONST(0.5f));
  return prt_v8_select(_mm256_cmp_ps(z, _mm256_setzero_ps(), _CMP_LT_OQ), half_tail,
                       _mm256_sub_ps(PRT_V8_CONST(1.0f), half_tail));
}

/* Phi(b) - Phi(a) for a <= b, both terms taken on the side of 0 where the interval's midpoint is
 * not (Phi(b) - Phi(a) = Phi(-a) - Phi(-b)), so that neither is near 1 and a mass in either tail
 * keeps its relative accuracy: within 12 ulp of the larger of the two terms; NaN for NaN. */
static inline __m256 prt_v8_normal_cdf_diff(__m256 a, __m256 b) {
  const __m256 flip = _mm256_cmp_ps(_mm256_add_ps(a, b), _mm256_setzero_ps(), _CMP_GT_OQ);
  const __m256 neg_a = _mm256_xor_ps(a, PRT_V8_CONST(-0.0f)),
               neg_b = _mm256_xor_ps(b, PRT_V8_CONST(-0.0f));
  return _mm256_sub_ps(prt_v8_normal_cdf(prt_v8_select(flip, neg_a, b)),
                       prt_v8_normal_cdf(prt_v8_select(flip, neg_b, a)));
}

/* The limit prt_v8_normal_quantile's results are clamped to: Phi(-8.5) is about 1e-17. */
#define PRT_V8_NORMAL_QUANTILE_LIMIT 8.5f

/* Phi^-1(p), the inverse standard normal CDF, within 4e-6 (absolute: a few ulp of z in the
 * tails) for p in (0, 1), clamped to +-8.5 (so -8.5 for p <= 9.5e-18 and p = 0, 8.5 for p = 1);
 * NaN outside [0, 1] and for NaN.
 * With x = 2p - 1 and w = -ln(1 - x^2) = -ln(4 p (1 - p)), Phi^-1(p) = x G(w): G a polynomial
 * in w for w < 5, a rational function of sqrt(w) above (w <= 39.5, clamped there). */
static inline __m256 prt_v8_normal_quantile(__m256 p) {
  const __m256 x = _mm256_fmsub_ps(p, PRT_V8_CONST(2.0f), PRT_V8_CONST(1.0f));
  /* 1 - p is exact for p >= 1/2, so w keeps its accuracy in both tails. */
  const __m256 pq = _mm256_mul_ps(p, _mm256_sub_ps(PRT_V8_CONST(1.0f), p));
  __m256 w = _mm256_sub_ps(_mm256_setzero_ps(), prt_v8_log(_mm256_mul_ps(pq, PRT_V8_CONST(4.0f))));
  w = _mm256_min_ps(PRT_V8_CONST(39.5f), w); /* NaN stays NaN */
  const __m256 u = _mm256_sub_ps(w, PRT_V8_CONST(2.5f));
  __m256 central = PRT_V8_CONST(2.426429191e-08f);
  central = prt_v8_fma(central, u, PRT_V8_CONST(4.972031888e-07f));
  central = prt_v8_fma(central, u, PRT_V8_CONST(-4.804309356e-06f));
  central = prt_v8_fma(central, u, PRT_V8_CONST(-6.320274224e-06f));
  central = prt_v8_fma(central, u, PRT_V8_CONST(3.084793570e-04f));
  central = prt_v8_fma(central, u, PRT_V8_CONST(-1.772750868e-03f));
  central = prt_v8_fma(central, u, PRT_V8_CONST(-5.907399114e-03f));
  central = prt_v8_fma(central, u, PRT_V8_CONST(3.488025069e-01f));
  central = prt_v8_fma(central, u, PRT_V8_CONST(2.123313427e+00f));
  const __m256 v = _mm256_sub_ps(_mm256_sqrt_ps(w), PRT_V8_CONST(3.0f));
  __m256 num = PRT_V8_CONST(6.827177107e-02f);
  num = prt_v8_fma(num, v, PRT_V8_CONST(7.924730182e-01f));
  num = prt_v8_fma(num, v, PRT_V8_CONST(3.354454517e+00f));
  num = prt_v8_fma(num, v, PRT_V8_CONST(6.895160198e+00f));
  num = prt_v8_fma(num, v, PRT_V8_CONST(7.516608238e+00f));
  num = prt_v8_fma(num, v, PRT_V8_CONST(4.006434441e+00f));
  __m256 den = PRT_V8_CONST(4.820242524e-02f);
  den = prt_v8_fma(den, v, PRT_V8_CONST(4.178954959e-01f));
  den = prt_v8_fma(den, v, PRT_V8_CONST(1.179347992e+00f));
  den = prt_v8_fma(den, v, PRT_V8_CONST(1.522557497e+00f));
  den = prt_v8_fma(den, v, PRT_V8_CONST(1.0f));
  const __m256 g = prt_v8_select(_mm256_cmp_ps(w, PRT_V8_CONST(5.0f), _CMP_LT_OQ), central,
                                 _mm256_div_ps(num, den));
  const __m256 z = _mm256_mul_ps(x, g);
  return _mm256_min_ps(PRT_V8_CONST(PRT_V8_NORMAL_QUANTILE_LIMIT),
                       _mm256_max_ps(PRT_V8_CONST(-PRT_V8_NORMAL_QUANTILE_LIMIT), z));
}

#undef PRT_V8_CONST

#endif /* PRT_RUNTIME_CLOTH_SIMD_MATH_H */
