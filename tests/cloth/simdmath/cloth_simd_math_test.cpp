// SPDX-License-Identifier: MIT
// runtime/src/cloth/cloth_simd_math.h against libm in double over dense sweeps: uniform grids of
// each domain and strided walks over the float bit patterns (every binade, the ends of the
// domain, denormals and the floats around FLT_MIN), then the special values one by one. Each
// test prints the largest error it measured and where; its bound is that function's documented
// accuracy, a small multiple of the measured error. The normal quantile, which libm lacks, is
// checked against a double-precision Newton inversion of libm's erfc.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "cloth/simdmath/cloth_simd_math_lanes.hpp"

namespace {

using namespace prt_simdmath_test;

const double kPi = 3.14159265358979323846;
const float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::numeric_limits<float>::quiet_NaN();

class SimdMath : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!cpu_has_avx2_fma()) GTEST_SKIP() << "the CPU lacks AVX2 or FMA";
  }
};

uint32_t bits_of(float x) {
  uint32_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

float from_bits(uint32_t b) {
  float x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}

bool same_bits(float a, float b) {
  return bits_of(a) == bits_of(b);
}

// n floats from a to b, both ends included.
std::vector<float> linear(double a, double b, size_t n) {
  std::vector<float> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = static_cast<float>(a + (b - a) * double(i) / double(n - 1));
  v.back() = static_cast<float>(b);
  return v;
}

// Every stride-th float from lo to hi (0 <= lo <= hi), and hi; with both signs if `mirror`.
std::vector<float> by_bits(float lo, float hi, uint32_t stride, bool mirror = false) {
  std::vector<float> v;
  for (uint64_t b = bits_of(lo); b <= bits_of(hi); b += stride) v.push_back(from_bits(uint32_t(b)));
  v.push_back(hi);
  if (mirror) {
    const size_t n = v.size();
    for (size_t i = 0; i < n; ++i) v.push_back(-v[i]);
  }
  return v;
}

std::vector<float> joined(std::initializer_list<std::vector<float>> parts) {
  std::vector<float> v;
  for (const auto& p : parts) v.insert(v.end(), p.begin(), p.end());
  return v;
}

// The ulp of `want` rounded to float (2^-149 in the denormals).
double ulp_of(double want) {
  const float f = std::fabs(static_cast<float>(want));
  if (f < FLT_MIN) return 0x1p-149;
  if (std::isinf(f)) return 0x1p104;
  return std::ldexp(1.0, std::ilogb(f) - 23);
}

enum class Measure { kUlp, kAbsolute };

// The largest error of a sweep and where it was.
struct Worst {
  double error = 0;
  float x = 0, x2 = 0;
  double got = 0, want = 0;
  size_t count = 0;

  void add(double got_value, double want_value, Measure m, float at, float at2 = 0) {
    ++count;
    double e;
    if (std::isinf(want_value) || std::isinf(got_value))
      e = got_value == want_value ? 0 : std::numeric_limits<double>::infinity();
    else if (m == Measure::kUlp)
      e = std::fabs(got_value - want_value) / ulp_of(want_value);
    else
      e = std::fabs(got_value - want_value);
    if (!(e <= error)) {  // NaN counts as the worst
      error = std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
      x = at, x2 = at2, got = got_value, want = want_value;
    }
  }

  void print(const char* what, Measure m) const {
    std::printf("[ measured ] %-36s max %.3g %s over %zu points at %.9g", what, error,
                m == Measure::kUlp ? "ulp" : "abs", count, double(x));
    if (x2 != 0) std::printf(", %.9g", double(x2));
    std::printf(" (got %.9g, want %.9g)\n", got, want);
  }
};

Worst sweep(Unary f, const std::vector<float>& xs, double (*ref)(double), Measure m) {
  std::vector<float> out(xs.size());
  eval_unary(f, xs.data(), out.data(), xs.size());
  Worst w;
  for (size_t i = 0; i < xs.size(); ++i) w.add(out[i], ref(xs[i]), m, xs[i]);
  return w;
}

float one(Unary f, float x) {
  float r;
  eval_unary(f, &x, &r, 1);
  return r;
}

float atan2_v8(float y, float x) {
  float r;
  eval_binary(Binary::kAtan2, &y, &x, nullptr, &r, 1);
  return r;
}

double ref_exp(double x) {
  return std::exp(x);
}
double ref_log(double x) {
  return std::log(x);
}
double ref_asin(double x) {
  return std::asin(x);
}
double ref_acos(double x) {
  return std::acos(x);
}
double ref_erfc(double x) {
  return std::erfc(x);
}
double ref_normal_cdf(double z) {
  return 0.5 * std::erfc(-z / std::sqrt(2.0));
}

// Phi^-1(p) for p in (0, 1/2]: Newton on ln Phi(z) = ln p, which is concave and increasing in z,
// from a start left of the root (Phi(-t) <= e^(-t^2 / 2) / 2 puts the root right of
// -sqrt(-2 ln p)): the iterates rise monotonically to it.
double quantile_lower(double p) {
  double z = -std::sqrt(-2 * std::log(p)) - 0.1;
  for (int i = 0; i < 200; ++i) {
    const double cdf = ref_normal_cdf(z);
    const double density = std::exp(-0.5 * z * z) / std::sqrt(2 * kPi);
    const double step = (std::log(cdf) - std::log(p)) * cdf / density;
    z -= step;
    if (std::fabs(step) <= 1e-15 * (1 + std::fabs(z))) break;
  }
  return z;
}

double ref_quantile(double p) {
  return p <= 0.5 ? quantile_lower(p) : -quantile_lower(1 - p);
}

// ---- exp ---------------------------------------------------------------------------------------

TEST_F(SimdMath, ExpWithinTwoUlpOverItsDomainDenormalsIncluded) {
  const std::vector<float> xs = joined({linear(-104, 88.72f, 3000000), by_bits(0, 88.72f, 509),
                                        by_bits(0, 104, 509, /*mirror=*/true)});
  std::vector<float> in;
  for (float x : xs)
    if (x >= -104 && x <= 88.72f) in.push_back(x);
  const Worst w = sweep(Unary::kExp, in, ref_exp, Measure::kUlp);
  w.print("exp [-104, 88.72]", Measure::kUlp);
  EXPECT_LE(w.error, 2.0) << "at x = " << w.x;
}

TEST_F(SimdMath, ExpSpecialValues) {
  EXPECT_EQ(one(Unary::kExp, 0.0f), 1.0f);
  EXPECT_EQ(one(Unary::kExp, -0.0f), 1.0f);
  EXPECT_NEAR(one(Unary::kExp, 88.7228f), std::exp(double(88.7228f)), 2 * 0x1p104);  // finite
  EXPECT_EQ(one(Unary::kExp, 88.7229f), kInf);
  EXPECT_EQ(one(Unary::kExp, 1e30f), kInf);
  EXPECT_EQ(one(Unary::kExp, kInf), kInf);
  EXPECT_EQ(one(Unary::kExp, -103.9f), 0x1p-149f);           // e^x is 0.53 2^-149
  EXPECT_TRUE(same_bits(one(Unary::kExp, -103.98f), 0.0f));  // 0.495 2^-149
  EXPECT_TRUE(same_bits(one(Unary::kExp, -104.5f), 0.0f));
  EXPECT_TRUE(same_bits(one(Unary::kExp, -kInf), 0.0f));
  EXPECT_TRUE(std::isnan(one(Unary::kExp, kNaN)));
}

TEST_F(SimdMath, ExpNegWithinTwoUlpForNormalResultsAndFlushesBelow) {
  std::vector<float> negative = by_bits(0, 87.33f, 509);
  for (float& x : negative) x = -x;
  const Worst w =
      sweep(Unary::kExpNeg, joined({linear(-87.33f, 0, 2000000), negative, linear(0, 88, 100000)}),
            ref_exp, Measure::kUlp);
  w.print("exp_neg [-87.33, 88]", Measure::kUlp);
  EXPECT_LE(w.error, 2.0) << "at x = " << w.x;
  // Below FLT_MIN: a denormal or 0, never more than the true value plus an ulp; 0 from -87.69.
  for (float x : linear(-87.69f, -87.34f, 10000)) {
    const float r = one(Unary::kExpNeg, x);
    EXPECT_TRUE(r >= 0 && r <= FLT_MIN) << x;
  }
  for (float x : {-87.69f, -88.0f, -100.0f, -1e30f, -kInf})
    EXPECT_TRUE(same_bits(one(Unary::kExpNeg, x), 0.0f)) << x;
  EXPECT_EQ(one(Unary::kExpNeg, 0.0f), 1.0f);
  EXPECT_TRUE(std::isnan(one(Unary::kExpNeg, kNaN)));
}

// ---- log ---------------------------------------------------------------------------------------

TEST_F(SimdMath, LogWithinTwoUlpOnEveryPositiveFloat) {
  const std::vector<float> xs =
      joined({by_bits(0x1p-149f, FLT_MAX, 509), linear(0.5, 2, 2000000),
              by_bits(from_bits(0x00700000), from_bits(0x00900000), 1)});  // around FLT_MIN
  const Worst w = sweep(Unary::kLog, xs, ref_log, Measure::kUlp);
  w.print("log (0, FLT_MAX]", Measure::kUlp);
  EXPECT_LE(w.error, 2.0) << "at x = " << w.x;
}

TEST_F(SimdMath, LogSpecialValues) {
  EXPECT_TRUE(same_bits(one(Unary::kLog, 1.0f), 0.0f));
  EXPECT_EQ(one(Unary::kLog, 0.0f), -kInf);
  EXPECT_EQ(one(Unary::kLog, -0.0f), -kInf);
  EXPECT_EQ(one(Unary::kLog, kInf), kInf);
  EXPECT_EQ(one(Unary::kLog, 2.0f), float(std::log(2.0)));
  for (float x : {-1.0f, -0x1p-149f, -FLT_MIN, -kInf, kNaN})
    EXPECT_TRUE(std::isnan(one(Unary::kLog, x))) << x;
}

// ---- sin and cos -------------------------------------------------------------------------------

// Both outputs of one sweep against sin and cos.
std::pair<Worst, Worst> sweep_sincos(const std::vector<float>& xs) {
  std::vector<float> s(xs.size()), c(xs.size());
  eval_sincos(xs.data(), s.data(), c.data(), xs.size());
  Worst ws, wc;
  for (size_t i = 0; i < xs.size(); ++i) {
    ws.add(s[i], std::sin(double(xs[i])), Measure::kAbsolute, xs[i]);
    wc.add(c[i], std::cos(double(xs[i])), Measure::kAbsolute, xs[i]);
  }
  return {ws, wc};
}

TEST_F(SimdMath, SinCosWithinAbsoluteBoundUpToTwoToThe18) {
  // Around each multiple of pi/2 up to 64: the reduction's hardest inputs.
  std::vector<float> near_axes;
  for (int k = -41; k <= 41; ++k) {
    if (k == 0) continue;
    const uint32_t b = bits_of(std::fabs(float(k * kPi / 2)));
    for (int d = -2000; d <= 2000; ++d)
      near_axes.push_back(std::copysign(from_bits(uint32_t(int64_t(b) + d)), float(k)));
  }
  const auto [ws, wc] = sweep_sincos(
      joined({linear(-64, 64, 4000000), near_axes, by_bits(0x1p-149f, 0x1p18f, 509, true)}));
  ws.print("sin |x| <= 2^18", Measure::kAbsolute);
  wc.print("cos |x| <= 2^18", Measure::kAbsolute);
  EXPECT_LE(ws.error, 1e-7) << "at x = " << ws.x;
  EXPECT_LE(wc.error, 1e-7) << "at x = " << wc.x;
}

TEST_F(SimdMath, SinCosSpecialValues) {
  const std::vector<float> xs = {0.0f, -0.0f, 0x1p-149f, -0x1p-149f, kInf, -kInf, kNaN};
  std::vector<float> s(xs.size()), c(xs.size());
  eval_sincos(xs.data(), s.data(), c.data(), xs.size());
  EXPECT_TRUE(same_bits(s[0], 0.0f));
  EXPECT_TRUE(same_bits(s[1], -0.0f));
  EXPECT_EQ(c[0], 1.0f);
  EXPECT_EQ(c[1], 1.0f);
  EXPECT_EQ(s[2], 0x1p-149f);
  EXPECT_EQ(s[3], -0x1p-149f);
  EXPECT_EQ(c[2], 1.0f);
  for (size_t i = 4; i < xs.size(); ++i) {
    EXPECT_TRUE(std::isnan(s[i])) << xs[i];
    EXPECT_TRUE(std::isnan(c[i])) << xs[i];
  }
}

// ---- atan2 -------------------------------------------------------------------------------------

Worst sweep_atan2(const std::vector<float>& ys, const std::vector<float>& xs) {
  std::vector<float> out(ys.size());
  eval_binary(Binary::kAtan2, ys.data(), xs.data(), nullptr, out.data(), ys.size());
  Worst w;
  for (size_t i = 0; i < ys.size(); ++i)
    w.add(out[i], std::atan2(double(ys[i]), double(xs[i])), Measure::kAbsolute, ys[i], xs[i]);
  return w;
}

TEST_F(SimdMath, Atan2WithinAbsoluteBoundOnEveryQuadrantAndScale) {
  std::vector<float> ys, xs;
  // Circles of radii from the denormals to near FLT_MAX.
  for (double r : {1e-44, 1e-39, 1e-20, 1e-3, 1.0, 7.0, 1e20, 3e38}) {
    const int n = 250000;
    for (int i = 0; i < n; ++i) {
      const double t = -kPi + 2 * kPi * (i + 0.5) / n;
      ys.push_back(float(r * std::sin(t)));
      xs.push_back(float(r * std::cos(t)));
    }
  }
  // Random finite floats of every magnitude and sign.
  std::mt19937 rng(20240611);
  while (ys.size() < 4000000) {
    const float y = from_bits(uint32_t(rng())), x = from_bits(uint32_t(rng()));
    if (!std::isfinite(y) || !std::isfinite(x)) continue;
    ys.push_back(y);
    xs.push_back(x);
  }
  const Worst w = sweep_atan2(ys, xs);
  w.print("atan2 (finite y, x)", Measure::kAbsolute);
  EXPECT_LE(w.error, 2.5e-7) << "at y = " << w.x << ", x = " << w.x2;
}

TEST_F(SimdMath, Atan2ZerosAndInfinitiesAsC) {
  const float values[] = {0.0f,  -0.0f,   0x1p-149f, -0x1p-149f, 1.0f,
                          -1.0f, FLT_MAX, -FLT_MAX,  kInf,       -kInf};
  for (float y : values)
    for (float x : values) {
      const float got = atan2_v8(y, x);
      if (std::isinf(y) && std::isinf(x)) {
        EXPECT_TRUE(std::isnan(got)) << "documented: both infinite gives NaN";
        continue;
      }
      const double want = std::atan2(double(y), double(x));
      EXPECT_NEAR(got, want, 2.5e-7) << "atan2(" << y << ", " << x << ")";
      EXPECT_EQ(std::signbit(got), std::signbit(want)) << "atan2(" << y << ", " << x << ")";
      if (want == 0) {
        EXPECT_EQ(got, 0.0f) << "atan2(" << y << ", " << x << ")";
      }
    }
  EXPECT_TRUE(same_bits(atan2_v8(0.0f, 0.0f), 0.0f));
  EXPECT_TRUE(std::isnan(atan2_v8(kNaN, 1.0f)));
  EXPECT_TRUE(std::isnan(atan2_v8(1.0f, kNaN)));
}

// ---- asin and acos -----------------------------------------------------------------------------

TEST_F(SimdMath, AsinAcosWithinAbsoluteBoundOnMinusOneToOne) {
  const std::vector<float> xs = joined({linear(-1, 1, 4000000), by_bits(0x1p-149f, 1, 257, true)});
  const Worst ws = sweep(Unary::kAsin, xs, ref_asin, Measure::kAbsolute);
  const Worst wc = sweep(Unary::kAcos, xs, ref_acos, Measure::kAbsolute);
  ws.print("asin [-1, 1]", Measure::kAbsolute);
  wc.print("acos [-1, 1]", Measure::kAbsolute);
  EXPECT_LE(ws.error, 1.5e-7) << "at x = " << ws.x;
  EXPECT_LE(wc.error, 2.5e-7) << "at x = " << wc.x;
}

TEST_F(SimdMath, AsinAcosSpecialValues) {
  EXPECT_TRUE(same_bits(one(Unary::kAsin, 0.0f), 0.0f));
  EXPECT_TRUE(same_bits(one(Unary::kAsin, -0.0f), -0.0f));
  EXPECT_EQ(one(Unary::kAsin, 1.0f), float(kPi / 2));
  EXPECT_EQ(one(Unary::kAsin, -1.0f), -float(kPi / 2));
  EXPECT_TRUE(same_bits(one(Unary::kAcos, 1.0f), 0.0f));
  EXPECT_EQ(one(Unary::kAcos, -1.0f), float(kPi));
  EXPECT_EQ(one(Unary::kAcos, 0.0f), float(kPi / 2));
  EXPECT_EQ(one(Unary::kAcos, -0.0f), float(kPi / 2));
  for (float x : {1.0000001f, -1.0000001f, 2.0f, kInf, -kInf, kNaN}) {
    EXPECT_TRUE(std::isnan(one(Unary::kAsin, x))) << x;
    EXPECT_TRUE(std::isnan(one(Unary::kAcos, x))) << x;
  }
}

// ---- erfc and Phi ------------------------------------------------------------------------------

TEST_F(SimdMath, ErfcWithinSevenUlpDenormalsIncluded) {
  const std::vector<float> xs =
      joined({linear(-10, 10.5, 4000000), by_bits(0x1p-149f, 12, 509, true)});
  const Worst w = sweep(Unary::kErfc, xs, ref_erfc, Measure::kUlp);
  w.print("erfc (relative while normal)", Measure::kUlp);
  EXPECT_LE(w.error, 7.0) << "at x = " << w.x;
}

TEST_F(SimdMath, ErfcSpecialValues) {
  EXPECT_NEAR(one(Unary::kErfc, 0.0f), 1.0, 0x1p-23);
  EXPECT_NEAR(one(Unary::kErfc, -0.0f), 1.0, 0x1p-23);
  EXPECT_TRUE(same_bits(one(Unary::kErfc, 11.0f), 0.0f));
  EXPECT_TRUE(same_bits(one(Unary::kErfc, kInf), 0.0f));
  EXPECT_EQ(one(Unary::kErfc, -4.0f), 2.0f);
  EXPECT_EQ(one(Unary::kErfc, -kInf), 2.0f);
  EXPECT_TRUE(std::isnan(one(Unary::kErfc, kNaN)));
}

TEST_F(SimdMath, NormalCdfWithinSevenUlpDenormalsIncluded) {
  const std::vector<float> xs =
      joined({linear(-14.9, 9, 4000000), by_bits(0x1p-149f, 16, 509, true)});
  const Worst w = sweep(Unary::kNormalCdf, xs, ref_normal_cdf, Measure::kUlp);
  w.print("normal_cdf (relative while normal)", Measure::kUlp);
  EXPECT_LE(w.error, 7.0) << "at z = " << w.x;
}

TEST_F(SimdMath, NormalCdfSpecialValues) {
  EXPECT_EQ(one(Unary::kNormalCdf, 0.0f), 0.5f);
  EXPECT_EQ(one(Unary::kNormalCdf, -0.0f), 0.5f);
  EXPECT_EQ(one(Unary::kNormalCdf, 6.0f), 1.0f);
  EXPECT_EQ(one(Unary::kNormalCdf, kInf), 1.0f);
  EXPECT_TRUE(same_bits(one(Unary::kNormalCdf, -kInf), 0.0f));
  EXPECT_TRUE(std::isnan(one(Unary::kNormalCdf, kNaN)));
}

// Phi(b) - Phi(a) in double from erfc when both are on one side of 0 (both terms tails), from erf
// across it (each term near 1/2): no cancellation that float would see.
double ref_normal_cdf_diff(double a, double b) {
  const double s = 1 / std::sqrt(2.0);
  if (a >= 0) return 0.5 * (std::erfc(a * s) - std::erfc(b * s));
  if (b <= 0) return 0.5 * (std::erfc(-b * s) - std::erfc(-a * s));
  return 0.5 * (std::erf(b * s) - std::erf(a * s));
}

TEST_F(SimdMath, NormalCdfDiffWithinTwelveUlpOfTheLargerTermInBothTails) {
  // Intervals of every width (down to adjacent floats) at every position over [-14.9, 14.9].
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> position(-14.9f, 14.9f);
  std::uniform_real_distribution<float> log_width(-7, 1.5f);
  std::vector<float> as, bs;
  for (float a : linear(-14.9, 14.9, 20000)) {
    as.push_back(a);
    bs.push_back(std::nextafter(a, kInf));  // the next float up
  }
  while (as.size() < 3000000) {
    const float a = position(rng), b = a + std::pow(10.0f, log_width(rng));
    as.push_back(a);
    bs.push_back(b);
  }
  std::vector<float> out(as.size());
  eval_binary(Binary::kNormalCdfDiff, as.data(), bs.data(), nullptr, out.data(), as.size());
  Worst w;
  for (size_t i = 0; i < as.size(); ++i) {
    // The larger term of the difference the function takes: that of the end nearer 0, folded
    // to the negative side.
    const double near = std::min(std::fabs(double(as[i])), std::fabs(double(bs[i])));
    const bool straddles = as[i] < 0 && bs[i] > 0;
    const double larger = straddles ? 0.5 : ref_normal_cdf(-near);
    const double want = ref_normal_cdf_diff(as[i], bs[i]);
    ++w.count;
    const double e = std::fabs(out[i] - want) / ulp_of(larger);
    if (!(e <= w.error)) w.error = e, w.x = as[i], w.x2 = bs[i], w.got = out[i], w.want = want;
  }
  w.print("normal_cdf_diff (ulp of larger term)", Measure::kUlp);
  EXPECT_LE(w.error, 12.0) << "at a = " << w.x << ", b = " << w.x2;
  // Far in the upper tail, where Phi(b) - Phi(a) taken directly would be 0.
  const float a = 7, b = 8;
  float d;
  eval_binary(Binary::kNormalCdfDiff, &a, &b, nullptr, &d, 1);
  EXPECT_NEAR(d, ref_normal_cdf_diff(a, b), 12 * ulp_of(ref_normal_cdf(-7)));
  EXPECT_GT(d, 0);
}

// ---- the normal quantile -----------------------------------------------------------------------

TEST_F(SimdMath, NormalQuantileWithinAbsoluteBoundFromOneInTenToTheFifteen) {
  std::vector<float> ps =
      joined({linear(0, 1, 1000000), by_bits(1e-15f, 0.5f, 509), by_bits(0.5f, 1.0f, 11)});
  std::vector<float> in;
  for (float p : ps)
    if (p >= 1e-15f && p < 1.0f) in.push_back(p);
  in.push_back(from_bits(bits_of(1.0f) - 1));  // 1 - 2^-24, the largest float below 1
  const Worst w = sweep(Unary::kQuantile, in, ref_quantile, Measure::kAbsolute);
  w.print("normal_quantile [1e-15, 1)", Measure::kAbsolute);
  EXPECT_LE(w.error, 4e-6) << "at p = " << w.x;
  // Further down, to the clamp at z = -8.5.
  const Worst tail =
      sweep(Unary::kQuantile, by_bits(9.5e-18f, 1e-15f, 67), ref_quantile, Measure::kAbsolute);
  tail.print("normal_quantile [9.5e-18, 1e-15]", Measure::kAbsolute);
  EXPECT_LE(tail.error, 4e-6) << "at p = " << tail.x;
}

TEST_F(SimdMath, NormalQuantileSpecialValuesAndClamp) {
  EXPECT_TRUE(same_bits(one(Unary::kQuantile, 0.5f), 0.0f));
  EXPECT_EQ(one(Unary::kQuantile, 0.0f), -8.5f);
  EXPECT_EQ(one(Unary::kQuantile, -0.0f), -8.5f);
  EXPECT_EQ(one(Unary::kQuantile, 1.0f), 8.5f);
  for (float p : {9e-18f, 1e-30f, FLT_MIN, 0x1p-149f})
    EXPECT_EQ(one(Unary::kQuantile, p), -8.5f) << p;
  for (float p : {-0x1p-149f, -0.1f, 1.0000001f, 2.0f, kInf, -kInf, kNaN})
    EXPECT_TRUE(std::isnan(one(Unary::kQuantile, p))) << p;
}

// ---- the lane-wise basics ----------------------------------------------------------------------

TEST_F(SimdMath, AbsMinMaxSelectAreExact) {
  const std::vector<float> a = {-0.0f, -2.5f, 3.0f, -kInf, kNaN, 1.0f, 0x1p-149f, -7.0f, 4.0f};
  const std::vector<float> b = {1.0f, 2.0f, -3.0f, 5.0f, 1.0f, kNaN, -0x1p-149f, -8.0f, 4.5f};
  const std::vector<float> mask = {1, 0, 1, 0, 1, 0, 1, 0, 1};
  const size_t n = a.size();
  std::vector<float> abs(n), mn(n), mx(n), sel(n);
  eval_abs(a.data(), abs.data(), n);
  eval_binary(Binary::kMin, a.data(), b.data(), nullptr, mn.data(), n);
  eval_binary(Binary::kMax, a.data(), b.data(), nullptr, mx.data(), n);
  eval_binary(Binary::kSelect, a.data(), b.data(), mask.data(), sel.data(), n);
  for (size_t i = 0; i < n; ++i) {
    if (std::isnan(a[i]))
      EXPECT_TRUE(std::isnan(abs[i]));
    else
      EXPECT_TRUE(same_bits(abs[i], std::fabs(a[i]))) << a[i];
    if (std::isnan(a[i]) || std::isnan(b[i])) {  // documented: b where either is NaN
      EXPECT_TRUE(same_bits(mn[i], b[i])) << i;
      EXPECT_TRUE(same_bits(mx[i], b[i])) << i;
    } else {
      EXPECT_EQ(mn[i], std::fmin(a[i], b[i])) << i;
      EXPECT_EQ(mx[i], std::fmax(a[i], b[i])) << i;
    }
    EXPECT_TRUE(same_bits(sel[i], mask[i] != 0 ? a[i] : b[i])) << i;
  }
}

}  // namespace
