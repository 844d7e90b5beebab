// SPDX-License-Identifier: MIT
// The SH triple product (runtime/src/shadowfield/shadowfield_gaunt.h): its band-0 slice against
// the closed form C_0jk = delta_jk / sqrt(4 pi), its symmetry, and prt_sf_sh_multiply against
// the projection of the pointwise product by a dense midpoint quadrature written here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "shadowfield/runtime/shadowfield_synthetic.hpp"

extern "C" {
#include "shadowfield_gaunt.h"
}

namespace prt::test {
namespace {

prt_allocator plain_allocator() {
  prt_allocator a{};
  // malloc's alignment covers every request the tensor makes (at most 8).
  a.alloc = [](void*, size_t size, size_t) -> void* { return std::malloc(size); };
  a.free = [](void*, void* p, size_t) { std::free(p); };
  return a;
}

struct Tensor {
  prt_allocator allocator = plain_allocator();
  prt_sf_gaunt gaunt{};
  explicit Tensor(uint32_t order) {
    EXPECT_EQ(prt_sf_gaunt_build(&allocator, order, &gaunt), PRT_OK);
  }
  ~Tensor() { prt_sf_gaunt_free(&allocator, &gaunt); }

  // C_ijk, 0 when not stored.
  double at(uint32_t i, uint32_t j, uint32_t k) const {
    for (uint32_t e = gaunt.k_start[k]; e < gaunt.k_start[k + 1]; ++e)
      if (gaunt.i[e] == i && gaunt.j[e] == j) return gaunt.value[e];
    return 0.0;
  }
};

TEST(ShadowfieldGaunt, BandZeroIsTheIdentityOverSqrtFourPi) {
  for (uint32_t order = 1; order <= 6; ++order) {
    const Tensor t(order);
    const uint32_t n2 = order * order;
    double worst = 0.0, smallest = 1.0;
    for (uint32_t e = 0; e < t.gaunt.count; ++e)
      smallest = std::min(smallest, std::fabs(double(t.gaunt.value[e])));
    for (uint32_t j = 0; j < n2; ++j)
      for (uint32_t k = 0; k < n2; ++k) {
        const double expected = j == k ? 1.0 / std::sqrt(4.0 * kSfPi) : 0.0;
        worst = std::max(worst, std::fabs(t.at(0, j, k) - expected));
      }
    std::printf("order %u: %u non-zero coefficients of %u, smallest %.2e, band-0 error %.2e\n",
                order, t.gaunt.count, n2 * n2 * n2, smallest, worst);
    EXPECT_LT(worst, 1.5e-7) << "order " << order;  // measured 4.5e-8: float rounding
    // The cut-off keeps every true coefficient: none lies near it.
    EXPECT_GT(smallest, 1e-3) << "order " << order;
  }
}

TEST(ShadowfieldGaunt, IsSymmetricInItsThreeIndices) {
  const Tensor t(6);
  double worst = 0.0;
  for (uint32_t k = 0; k < 36; ++k)
    for (uint32_t e = t.gaunt.k_start[k]; e < t.gaunt.k_start[k + 1]; ++e) {
      const uint32_t i = t.gaunt.i[e], j = t.gaunt.j[e];
      worst = std::max(worst, std::fabs(t.at(j, i, k) - t.gaunt.value[e]));
      worst = std::max(worst, std::fabs(t.at(k, j, i) - t.gaunt.value[e]));
    }
  EXPECT_LT(worst, 1e-6);
}

TEST(ShadowfieldGaunt, MultiplyIsTheProjectionOfThePointwiseProduct) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  for (const uint32_t order : {2u, 4u, 6u}) {
    const Tensor t(order);
    const uint32_t n2 = order * order;
    std::vector<float> a(n2), b(n2), out(n2);
    for (uint32_t i = 0; i < n2; ++i) a[i] = value(random), b[i] = value(random);
    prt_sf_sh_multiply(&t.gaunt, a.data(), b.data(), out.data());
    const std::vector<double> expected = project_dense(order, [&](const float* w) {
      return sh_value(order, a.data(), w) * sh_value(order, b.data(), w);
    });
    double worst = 0.0, scale = 0.0;
    for (uint32_t k = 0; k < n2; ++k) {
      worst = std::max(worst, std::fabs(out[k] - expected[k]));
      scale = std::max(scale, std::fabs(expected[k]));
    }
    std::printf("order %u: max |product - dense projection| %.2e (of %.2f)\n", order, worst, scale);
    // Measured up to 4.3e-5 of the scale: the midpoint rule's own error.
    EXPECT_LT(worst, 1e-4 * scale) << "order " << order;
  }
}

TEST(ShadowfieldGaunt, RejectsOrdersOutsideOneToSix) {
  prt_allocator allocator = plain_allocator();
  prt_sf_gaunt gaunt;
  EXPECT_EQ(prt_sf_gaunt_build(&allocator, 0, &gaunt), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sf_gaunt_build(&allocator, 7, &gaunt), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(gaunt.count, 0u);
}

}  // namespace
}  // namespace prt::test
