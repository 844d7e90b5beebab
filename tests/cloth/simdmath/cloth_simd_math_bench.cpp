// SPDX-License-Identifier: MIT
// prt_cloth_simdmath_bench: nanoseconds per 8-wide call of each function of
// runtime/src/cloth/cloth_simd_math.h, beside 8 calls of the scalar libm function in float and in
// double, measured in the same run (throughput: independent calls over a 4096-float array that
// stays in L1, the best of several repetitions). Prints, asserts nothing; run by hand.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include "cloth/simdmath/cloth_simd_math_lanes.hpp"

namespace {

using namespace prt_simdmath_test;

const size_t kCount = 4096;

// Best time of `runs` timings of `reps` calls of body(), in ns per group of 8 elements.
double ns_per_eight(const std::function<void()>& body) {
  const int runs = 7, reps = 200;
  double best = 1e300;
  body();  // warm up
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < reps; ++i) body();
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double, std::nano>(t1 - t0).count() / reps);
  }
  return best / (kCount / 8);
}

std::vector<float> uniform(float lo, float hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(lo, hi);
  std::vector<float> v(kCount);
  for (float& x : v) x = d(rng);
  return v;
}

template <typename F>
void scalar_loop(const std::vector<float>& x, std::vector<float>& out, F f) {
  for (size_t i = 0; i < x.size(); ++i) out[i] = f(x[i]);
  // Keeps the compiler from dropping the loop.
  asm volatile("" : : "r"(out.data()) : "memory");
}

void row(const char* name, double vec, double scalar_float, double scalar_double) {
  std::printf("%-16s %10.2f %14.2f %8.1fx %15.2f %8.1fx\n", name, vec, scalar_float,
              scalar_float / vec, scalar_double, scalar_double / vec);
}

struct UnaryCase {
  const char* name;
  Unary f;
  float lo, hi;
  float (*scalar_float)(float);
  double (*scalar_double)(double);
};

float normal_cdf_f(float z) {
  return 0.5f * erfcf(z * -0.70710678f);
}
double normal_cdf_d(double z) {
  return 0.5 * std::erfc(z * -0.70710678118654752);
}

}  // namespace

int main() {
  if (!cpu_has_avx2_fma()) {
    std::printf("the CPU lacks AVX2 or FMA\n");
    return 0;
  }
  const UnaryCase cases[] = {
      {"exp", Unary::kExp, -80, 80, expf, [](double x) { return std::exp(x); }},
      {"exp_neg", Unary::kExpNeg, -80, 0, expf, [](double x) { return std::exp(x); }},
      {"log", Unary::kLog, 1e-6f, 1e6f, logf, [](double x) { return std::log(x); }},
      {"asin", Unary::kAsin, -1, 1, asinf, [](double x) { return std::asin(x); }},
      {"acos", Unary::kAcos, -1, 1, acosf, [](double x) { return std::acos(x); }},
      {"erfc", Unary::kErfc, -6, 9, erfcf, [](double x) { return std::erfc(x); }},
      {"normal_cdf", Unary::kNormalCdf, -8, 8, normal_cdf_f, normal_cdf_d},
  };
  std::printf("%-16s %10s %14s %9s %15s %9s\n", "function", "v8 ns/call", "8 libm f ns", "ratio",
              "8 libm d ns", "ratio");
  std::vector<float> out(kCount), out2(kCount);
  unsigned seed = 1;
  for (const UnaryCase& c : cases) {
    const std::vector<float> x = uniform(c.lo, c.hi, seed++);
    const double v = ns_per_eight([&] { eval_unary(c.f, x.data(), out.data(), kCount); });
    const double sf = ns_per_eight([&] { scalar_loop(x, out, c.scalar_float); });
    const double sd = ns_per_eight(
        [&] { scalar_loop(x, out, [&](float a) { return float(c.scalar_double(a)); }); });
    row(c.name, v, sf, sd);
  }
  {
    const std::vector<float> x = uniform(-64, 64, seed++);
    const double v = ns_per_eight([&] { eval_sincos(x.data(), out.data(), out2.data(), kCount); });
    const double sf = ns_per_eight([&] {
      for (size_t i = 0; i < kCount; ++i) sincosf(x[i], &out[i], &out2[i]);
      asm volatile("" : : "r"(out.data()), "r"(out2.data()) : "memory");
    });
    const double sd = ns_per_eight([&] {
      for (size_t i = 0; i < kCount; ++i) {
        double s, c;
        sincos(double(x[i]), &s, &c);
        out[i] = float(s), out2[i] = float(c);
      }
      asm volatile("" : : "r"(out.data()), "r"(out2.data()) : "memory");
    });
    row("sincos", v, sf, sd);
  }
  {
    const std::vector<float> y = uniform(-1, 1, seed++), x = uniform(-1, 1, seed++);
    const double v = ns_per_eight(
        [&] { eval_binary(Binary::kAtan2, y.data(), x.data(), nullptr, out.data(), kCount); });
    const double sf = ns_per_eight([&] {
      for (size_t i = 0; i < kCount; ++i) out[i] = atan2f(y[i], x[i]);
      asm volatile("" : : "r"(out.data()) : "memory");
    });
    const double sd = ns_per_eight([&] {
      for (size_t i = 0; i < kCount; ++i) out[i] = float(std::atan2(double(y[i]), double(x[i])));
      asm volatile("" : : "r"(out.data()) : "memory");
    });
    row("atan2", v, sf, sd);
  }
  {
    // Phi(b) - Phi(a): two erfc calls per element in libm.
    const std::vector<float> a = uniform(-8, 8, seed++), w = uniform(0, 1, seed++);
    std::vector<float> b(kCount);
    for (size_t i = 0; i < kCount; ++i) b[i] = a[i] + w[i];
    const double v = ns_per_eight([&] {
      eval_binary(Binary::kNormalCdfDiff, a.data(), b.data(), nullptr, out.data(), kCount);
    });
    const double sf = ns_per_eight([&] {
      for (size_t i = 0; i < kCount; ++i) out[i] = normal_cdf_f(b[i]) - normal_cdf_f(a[i]);
      asm volatile("" : : "r"(out.data()) : "memory");
    });
    const double sd = ns_per_eight([&] {
      for (size_t i = 0; i < kCount; ++i) out[i] = float(normal_cdf_d(b[i]) - normal_cdf_d(a[i]));
      asm volatile("" : : "r"(out.data()) : "memory");
    });
    row("normal_cdf_diff", v, sf, sd);
  }
  {
    // libm has no inverse normal CDF: only the vector figure.
    const std::vector<float> p = uniform(1e-7f, 1 - 1e-7f, seed++);
    const double v =
        ns_per_eight([&] { eval_unary(Unary::kQuantile, p.data(), out.data(), kCount); });
    std::printf("%-16s %10.2f %14s %9s %15s %9s\n", "normal_quantile", v, "-", "-", "-", "-");
  }
  return 0;
}
