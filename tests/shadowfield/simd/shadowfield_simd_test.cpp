// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s SIMD backend against the scalar reference. Each kernel sums the same
// products in another order and with fused multiply-adds, so for an output that is a sum of n
// products p_t each backend is within gamma_n sum |p_t| of the exact sum (gamma_n = n u / (1 -
// n u), u = 2^-24; Higham, "Accuracy and Stability of Numerical Algorithms", 3.1), and the two
// within twice that: the kernel tests check that bound, computed here in double from the inputs.
// A whole frame chains these sums through the passes; its test checks a bound of the same form
// on the output's scale. Sizes are chosen so that no SIMD block divides them (odd n^2, vertex and
// point counts, term counts).
#include <gtest/gtest.h>

#include <prt/prt.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "shadowfield/runtime/shadowfield_test_scene.hpp"
#include "support/limited_context.hpp"
#include "support/simd_dispatch.hpp"

extern "C" {
#include "internal.h"
#include "shadowfield_kernels.h"
#include "shadowfield_scene.h"
}

namespace prt::test {
namespace {

constexpr double kUnit = 1.0 / 16777216.0;  // u = 2^-24

bool simd_here() {
  const prt::ContextPtr context = prt_test::limited_context();
  return prt_test::simd_usable(context.get()) &&
         prt_internal_simd_isa(context.get()) >= PRT_SIMD_ISA_AVX2;
}

#define SKIP_WITHOUT_AVX2() \
  if (!simd_here()) GTEST_SKIP() << "no AVX2 + FMA here (or compiled out)"

#if defined(PRT_HAS_X86_SIMD)

double gamma(double n) {
  return n * kUnit / (1.0 - n * kUnit);
}

std::vector<float> random_floats(size_t count, uint32_t seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<float> out(count);
  for (float& v : out) v = uniform(generator);
  return out;
}

// The C library's allocator: the kernels load unaligned, so its alignment serves.
prt_allocator malloc_allocator() {
  prt_allocator allocator{};
  allocator.alloc = [](void*, size_t size, size_t) -> void* { return std::malloc(size); };
  allocator.free = [](void*, void* p, size_t) { std::free(p); };
  return allocator;
}

// |a - b| <= 2 gamma_n magnitude for every output; returns the largest ratio of the two sides.
double check_within(const std::vector<float>& a, const std::vector<float>& b,
                    const std::vector<double>& magnitude, double terms) {
  double worst = 0.0;
  for (size_t e = 0; e < a.size(); ++e) {
    const double bound = 2.0 * gamma(terms) * magnitude[e];
    EXPECT_LE(std::fabs(double(a[e]) - b[e]), bound) << "output " << e;
    if (bound > 0.0) worst = std::max(worst, std::fabs(double(a[e]) - b[e]) / bound);
  }
  static int checks = 0;
  ::testing::Test::RecordProperty("check" + std::to_string(checks++) + "_difference_over_bound",
                                  std::to_string(worst));
  return worst;
}

// A masked lane kernel's outputs (n2 coefficients x PRT_SF_LANES lanes, lane-interleaved) on
// both backends from the same input `a`: the lanes outside `mask` keep a's bits on both, the
// others agree within check_within's bound of `terms` with magnitude(coefficient, lane).
void check_masked_lanes(const std::vector<float>& a, const std::vector<float>& scalar,
                        const std::vector<float>& simd, uint32_t n2, uint32_t mask, double terms,
                        const std::function<double(uint32_t, uint32_t)>& magnitude) {
  std::vector<float> masked_scalar, masked_simd;
  std::vector<double> magnitudes;
  for (uint32_t k = 0; k < n2; ++k)
    for (uint32_t lane = 0; lane < PRT_SF_LANES; ++lane) {
      const size_t at = k * PRT_SF_LANES + lane;
      if (!(mask >> lane & 1u)) {
        EXPECT_EQ(scalar[at], a[at]);
        EXPECT_EQ(simd[at], a[at]);
        continue;
      }
      magnitudes.push_back(magnitude(k, lane));
      masked_scalar.push_back(scalar[at]);
      masked_simd.push_back(simd[at]);
    }
  check_within(masked_scalar, masked_simd, magnitudes, terms);
}

TEST(ShadowfieldSimdKernels, ReadRowsAgreeForEveryWidth) {
  SKIP_WITHOUT_AVX2();
  for (const uint32_t width : {4u, 9u, 16u, 25u, 36u}) {
    const uint64_t points = 37;
    const std::vector<float> field = random_floats(3 * points * width, width);
    prt_sf_lookup lookup{};
    lookup.count = 8;
    for (uint32_t e = 0; e < 8; ++e) {
      lookup.index[e] = (e * 5 + 3) % points;
      lookup.weight[e] = 0.05f + 0.02f * float(e);
    }
    std::vector<float> scalar(3 * width), simd(3 * width);
    prt_sf_kernels_scalar.read_rows(field.data(), points * width, 3, width, &lookup, scalar.data());
    prt_sf_kernels_avx2.read_rows(field.data(), points * width, 3, width, &lookup, simd.data());
    std::vector<double> magnitude(3 * width, 0.0);
    for (uint32_t c = 0; c < 3; ++c)
      for (uint32_t i = 0; i < width; ++i)
        for (uint32_t e = 0; e < 8; ++e)
          magnitude[c * width + i] += std::fabs(
              double(lookup.weight[e]) * field[c * points * width + lookup.index[e] * width + i]);
    check_within(scalar, simd, magnitude, 8);
  }
}

// A bounce's read of three colour planes dotted with one or two transfer vectors, summed over
// two sources in lanes and reduced: within the bound of the whole sum (8 weighted rows, then the
// dot over the width, then the two sources), against the scalar table and against the same
// sums taken here in double.
TEST(ShadowfieldSimdKernels, ReadDotAgreesForEveryWidth) {
  SKIP_WITHOUT_AVX2();
  for (const uint32_t width : {4u, 9u, 16u, 25u, 36u})
    for (const uint32_t terms : {1u, 2u}) {
      const uint64_t points = 37;
      const std::vector<float> field = random_floats(3 * points * width, width + 70);
      const std::vector<float> transfer = random_floats(terms * width, width + 80);
      prt_sf_lookup lookups[2]{};
      for (uint32_t s = 0; s < 2; ++s) {
        lookups[s].count = s == 0 ? 8 : 4;
        for (uint32_t e = 0; e < lookups[s].count; ++e) {
          lookups[s].index[e] = (e * 7 + 5 * s + 1) % points;
          lookups[s].weight[e] = 0.04f + 0.03f * float(e + s);
        }
      }
      std::vector<float> outputs[2];
      const prt_sf_kernels* tables[2] = {&prt_sf_kernels_scalar, &prt_sf_kernels_avx2};
      for (uint32_t t = 0; t < 2; ++t) {
        std::vector<float> partial(3 * terms * PRT_SF_LANES, 0.0f);
        for (const prt_sf_lookup& lookup : lookups)
          tables[t]->read_dot(field.data(), points * width, width, &lookup, transfer.data(), terms,
                              partial.data());
        outputs[t].assign(3 * terms, 0.0f);
        tables[t]->reduce_lanes(partial.data(), 3 * terms, outputs[t].data());
      }
      std::vector<double> magnitude(3 * terms, 0.0), exact(3 * terms, 0.0);
      for (uint32_t k = 0; k < terms; ++k)
        for (uint32_t c = 0; c < 3; ++c)
          for (const prt_sf_lookup& lookup : lookups)
            for (uint32_t e = 0; e < lookup.count; ++e)
              for (uint32_t i = 0; i < width; ++i) {
                const double product = double(transfer[k * width + i]) * lookup.weight[e] *
                                       field[c * points * width + lookup.index[e] * width + i];
                magnitude[3 * k + c] += std::fabs(product);
                exact[3 * k + c] += product;
              }
      // Each product: two multiplications; sums of 8 rows, width values, 2 sources and 8 lanes.
      const double n = 2.0 + 8.0 + width + 2.0 + 8.0;
      check_within(outputs[0], outputs[1], magnitude, n);
      for (uint32_t r = 0; r < 3 * terms; ++r)
        for (uint32_t t = 0; t < 2; ++t)
          EXPECT_LE(std::fabs(outputs[t][r] - exact[r]), gamma(n) * magnitude[r]) << r;
    }
}

TEST(ShadowfieldSimdKernels, LightTimesAndTransferAgree) {
  SKIP_WITHOUT_AVX2();
  for (const uint32_t order : {2u, 3u, 4u, 5u, 6u}) {
    const uint32_t n2 = order * order, terms = 5;
    const std::vector<float> matrix = random_floats(3 * n2 * n2, order);
    const std::vector<float> visibility = random_floats(n2, order + 10);
    std::vector<float> scalar(3 * n2), simd(3 * n2);
    prt_sf_kernels_scalar.light_times(matrix.data(), n2, visibility.data(), scalar.data());
    prt_sf_kernels_avx2.light_times(matrix.data(), n2, visibility.data(), simd.data());
    std::vector<double> magnitude(3 * n2, 0.0);
    for (uint32_t c = 0; c < 3; ++c)
      for (uint32_t k = 0; k < n2; ++k)
        for (uint32_t j = 0; j < n2; ++j)
          magnitude[c * n2 + k] += std::fabs(double(matrix[(c * n2 + k) * n2 + j]) * visibility[j]);
    check_within(scalar, simd, magnitude, n2);

    const std::vector<float> transfer = random_floats(terms * n2, order + 20);
    std::vector<float> t_scalar(3 * terms), t_simd(3 * terms);
    prt_sf_kernels_scalar.transfer_dot(transfer.data(), n2, terms, scalar.data(), t_scalar.data());
    prt_sf_kernels_avx2.transfer_dot(transfer.data(), n2, terms, scalar.data(), t_simd.data());
    std::vector<double> t_magnitude(3 * terms, 0.0);
    for (uint32_t k = 0; k < terms; ++k)
      for (uint32_t c = 0; c < 3; ++c)
        for (uint32_t i = 0; i < n2; ++i)
          t_magnitude[3 * k + c] += std::fabs(double(transfer[k * n2 + i]) * scalar[c * n2 + i]);
    check_within(t_scalar, t_simd, t_magnitude, n2);
  }
}

// Per output, the sum of |block entry x input| of its row: row a of band l's block from the
// pair's row-major blocks, or with `transpose` (the inverse rotation) column a.
std::vector<double> rotation_magnitude(const prt_sf_pair* pair, uint32_t order,
                                       const std::vector<float>& in, uint32_t planes,
                                       bool transpose) {
  const uint32_t n2 = order * order;
  std::vector<double> magnitude(planes * n2, 0.0);
  for (uint32_t c = 0; c < planes; ++c) {
    const float* block = pair->sh_rotation;
    for (uint32_t l = 0; l < order; ++l) {
      const uint32_t width = 2 * l + 1, base = l * l;
      for (uint32_t a = 0; a < width; ++a)
        for (uint32_t b = 0; b < width; ++b) {
          const float entry = transpose ? block[b * width + a] : block[a * width + b];
          magnitude[c * n2 + base + a] += std::fabs(double(entry) * in[c * n2 + base + b]);
        }
      block += width * width;
    }
  }
  return magnitude;
}

// Two patches, the second turned about a tilted axis: the pair's rotation from the frame's
// preparation, as the kernels read it.
TEST(ShadowfieldSimdKernels, RotationsAgree) {
  SKIP_WITHOUT_AVX2();
  for (const uint32_t order : {3u, 4u, 6u}) {
    SyntheticObject a = make_patch(order, 2), b = make_patch(order, 2);
    TestScene s(2);
    const float axis[3] = {0.48f, 0.6f, 0.64f};
    float turn[9];
    axis_rotation(axis, 0.9f, turn);
    s.add_instance(s.add_object(a), make_transform(identity_rotation(), 0, 0, 0));
    s.add_instance(s.add_object(b), make_transform(turn, 0.3f, 0.5f, 0));
    const std::vector<float> light = test_light(order);
    const float eye[3] = {0, 3, 1};
    ASSERT_EQ(prt_shadowfield_prepare(s.scene, light.data(), eye, nullptr), PRT_OK);
    ASSERT_GT(s.scene->pair_count, 0u);
    const prt_sf_pair* pair = &s.scene->pairs[0];
    const uint32_t n2 = order * order;
    const std::vector<float> in = random_floats(3 * n2, order);
    std::vector<float> scalar(3 * n2), simd(3 * n2);
    prt_sf_kernels_scalar.rotate(pair, order, in.data(), scalar.data(), 3);
    prt_sf_kernels_avx2.rotate(pair, order, in.data(), simd.data(), 3);
    check_within(scalar, simd, rotation_magnitude(pair, order, in, 3, false), 2 * order - 1);
  }
}

// The inverse rotation (a receiver's transfer turned into a source's frame): the backends agree
// within the bound of the transpose's sums, and turning back undoes the rotation up to the
// rounding of the blocks' orthogonality.
TEST(ShadowfieldSimdKernels, RotationsBackAgreeAndUndoTheRotation) {
  SKIP_WITHOUT_AVX2();
  for (const uint32_t order : {3u, 4u, 6u}) {
    SyntheticObject a = make_patch(order, 2), b = make_patch(order, 2);
    TestScene s(2);
    const float axis[3] = {-0.36f, 0.8f, 0.48f};
    float turn[9];
    axis_rotation(axis, 2.1f, turn);
    s.add_instance(s.add_object(a), make_transform(identity_rotation(), 0, 0, 0));
    s.add_instance(s.add_object(b), make_transform(turn, 0.2f, -0.4f, 0.1f));
    const std::vector<float> light = test_light(order);
    const float eye[3] = {0, 3, 1};
    ASSERT_EQ(prt_shadowfield_prepare(s.scene, light.data(), eye, nullptr), PRT_OK);
    ASSERT_GT(s.scene->pair_count, 0u);
    const prt_sf_pair* pair = &s.scene->pairs[0];
    const uint32_t n2 = order * order;
    const std::vector<float> in = random_floats(2 * n2, order + 40);
    std::vector<float> scalar(2 * n2), simd(2 * n2);
    prt_sf_kernels_scalar.rotate_back(pair, order, in.data(), scalar.data(), 2);
    prt_sf_kernels_avx2.rotate_back(pair, order, in.data(), simd.data(), 2);
    check_within(scalar, simd, rotation_magnitude(pair, order, in, 2, true), 2 * order - 1);
    // Inputs within [-1, 1]: the round trip stays within a few float steps of 1 (measured up to
    // 1.8e-7 over these orders).
    for (const prt_sf_kernels* kernels : {&prt_sf_kernels_scalar, &prt_sf_kernels_avx2}) {
      std::vector<float> turned(2 * n2), back(2 * n2);
      kernels->rotate(pair, order, in.data(), turned.data(), 2);
      kernels->rotate_back(pair, order, turned.data(), back.data(), 2);
      for (uint32_t e = 0; e < 2 * n2; ++e) EXPECT_NEAR(back[e], in[e], 5e-7) << "value " << e;
    }
  }
}

// A blocker's reads turned eight vertices at a time (the direct pass): on each backend, the
// masked lanes hold that backend's rotation of the lane alone, bit for bit (so the frame's
// bounds against the scalar rotation carry over), and the other lanes keep their bits.
TEST(ShadowfieldSimdKernels, RotateLanesIsTheRotationLaneByLane) {
  SKIP_WITHOUT_AVX2();
  for (const uint32_t order : {3u, 4u, 6u}) {
    SyntheticObject a = make_patch(order, 2), b = make_patch(order, 2);
    TestScene s(2);
    const float axis[3] = {0.64f, -0.48f, 0.6f};
    float turn[9];
    axis_rotation(axis, 1.3f, turn);
    s.add_instance(s.add_object(a), make_transform(identity_rotation(), 0, 0, 0));
    s.add_instance(s.add_object(b), make_transform(turn, -0.3f, 0.2f, 0.4f));
    const std::vector<float> light = test_light(order);
    const float eye[3] = {0, 3, 1};
    ASSERT_EQ(prt_shadowfield_prepare(s.scene, light.data(), eye, nullptr), PRT_OK);
    ASSERT_GT(s.scene->pair_count, 0u);
    const prt_sf_pair* pair = &s.scene->pairs[0];
    const uint32_t n2 = order * order, mask = 0x5Bu;
    const std::vector<float> in = random_floats(n2 * PRT_SF_LANES, order + 70);
    const std::vector<float> before = random_floats(n2 * PRT_SF_LANES, order + 80);
    for (const prt_sf_kernels* kernels : {&prt_sf_kernels_scalar, &prt_sf_kernels_avx2}) {
      std::vector<float> out = before;
      kernels->rotate_lanes(pair, order, in.data(), out.data(), mask);
      for (uint32_t lane = 0; lane < PRT_SF_LANES; ++lane) {
        std::vector<float> plane(n2), turned(n2);
        for (uint32_t k = 0; k < n2; ++k) plane[k] = in[k * PRT_SF_LANES + lane];
        kernels->rotate(pair, order, plane.data(), turned.data(), 1);
        for (uint32_t k = 0; k < n2; ++k) {
          const size_t at = k * PRT_SF_LANES + lane;
          EXPECT_EQ(out[at], mask >> lane & 1u ? turned[k] : before[at])
              << "order " << order << " lane " << lane << " coefficient " << k;
        }
      }
    }
  }
}

// The triple product eight vertices at a time: in the masked lanes the SIMD kernel is within the
// bound of each coefficient's sparse sum of the scalar one, which is prt_sf_sh_multiply lane by
// lane; the other lanes keep their bits on both.
TEST(ShadowfieldSimdKernels, MultiplyLanesAgreesAndKeepsTheOtherLanes) {
  SKIP_WITHOUT_AVX2();
  const prt_allocator allocator = malloc_allocator();
  for (const uint32_t order : {2u, 3u, 4u, 5u, 6u}) {
    prt_sf_gaunt gaunt{};
    ASSERT_EQ(prt_sf_gaunt_build(&allocator, order, &gaunt), PRT_OK);
    const uint32_t n2 = order * order, mask = 0xB5u;
    const std::vector<float> a = random_floats(n2 * PRT_SF_LANES, order + 50);
    const std::vector<float> b = random_floats(n2 * PRT_SF_LANES, order + 60);
    std::vector<float> scalar = a, simd = a;
    prt_sf_kernels_scalar.multiply_lanes(&gaunt, scalar.data(), b.data(), mask);
    prt_sf_kernels_avx2.multiply_lanes(&gaunt, simd.data(), b.data(), mask);
    uint32_t longest = 0;
    for (uint32_t k = 0; k < n2; ++k)
      longest = std::max(longest, gaunt.k_start[k + 1] - gaunt.k_start[k]);
    // Each product has two multiplications: a sum of m of them is within gamma_(m + 2).
    check_masked_lanes(a, scalar, simd, n2, mask, longest + 2, [&](uint32_t k, uint32_t lane) {
      double sum = 0.0;
      for (uint32_t e = gaunt.k_start[k]; e < gaunt.k_start[k + 1]; ++e)
        sum += std::fabs(double(gaunt.value[e]) * a[gaunt.i[e] * PRT_SF_LANES + lane] *
                         b[gaunt.j[e] * PRT_SF_LANES + lane]);
      return sum;
    });
    prt_sf_gaunt_free(&allocator, &gaunt);
  }
}

// The log-space product's exponential eight vertices at a time. Each output sums D terms
// p_d exp(x_d) with x_d a sum of n^2 products; an error eps in x_d moves its term by about
// |x_d| eps, and the exponential adds a few ulps: within gamma_(n^2 + D + 4) of
// sum_d |p_d| exp(x_d) (1 + sum_j |y_dj f_j|). The other lanes keep their bits on both.
TEST(ShadowfieldSimdKernels, ExpLanesAgreesAndKeepsTheOtherLanes) {
  SKIP_WITHOUT_AVX2();
  const prt_allocator allocator = malloc_allocator();
  for (const uint32_t order : {2u, 3u, 4u, 5u, 6u}) {
    prt_sf_sphere_rule rule{};
    ASSERT_EQ(prt_sf_exp_rule_build(&allocator, order, &rule), PRT_OK);
    const uint32_t n2 = order * order, mask = 0x6Du;
    std::vector<float> a = random_floats(n2 * PRT_SF_LANES, order + 70);
    for (uint32_t lane = 0; lane < PRT_SF_LANES; ++lane) a[lane] -= 6.0f;  // logs mostly < 0
    std::vector<float> scalar = a, simd = a;
    prt_sf_kernels_scalar.exp_lanes(&rule, scalar.data(), mask);
    prt_sf_kernels_avx2.exp_lanes(&rule, simd.data(), mask);
    check_masked_lanes(
        a, scalar, simd, n2, mask, n2 + rule.directions + 4, [&](uint32_t i, uint32_t lane) {
          double sum = 0.0;
          for (uint32_t d = 0; d < rule.directions; ++d) {
            double x = 0.0, size = 0.0;
            for (uint32_t j = 0; j < n2; ++j) {
              x += double(rule.eval[d * n2 + j]) * a[j * PRT_SF_LANES + lane];
              size += std::fabs(double(rule.eval[d * n2 + j]) * a[j * PRT_SF_LANES + lane]);
            }
            sum += std::fabs(double(rule.project[i * rule.directions + d])) * std::exp(x) *
                   (1.0 + size);
          }
          return sum;
        });
    prt_sf_sphere_rule_free(&allocator, &rule);
  }
}

// A field of 5 shells of 6 x 3 x 3 points (270, not a multiple of any block), cast over the
// whole grid and over a range that starts and ends inside blocks.
TEST(ShadowfieldSimdKernels, CastFieldAgrees) {
  SKIP_WITHOUT_AVX2();
  SyntheticObject o = make_patch(3, 3);
  o.terms = 3;
  o.basis_size = 5;
  o.srf_shells = default_shells(0.75f);
  o.srf_shells.shells = 5;
  o.srf_shells.face_size = 3;
  const uint64_t points = prt_sf_point_count(&o.srf_shells);
  const uint32_t n2 = 9, rows = o.basis_size * o.terms;
  o.srf = random_floats(size_t(rows) * points * n2, 7);
  const std::vector<float> weights = random_floats(size_t(rows) * 3, 8);
  const prt_sf_object* object = o.view();
  for (const auto& [first, count] : {std::pair<uint64_t, uint64_t>{0, points}, {13, 201}}) {
    std::vector<float> scalar(3 * points * n2, 0.0f), simd(3 * points * n2, 0.0f);
    prt_sf_kernels_scalar.cast_field(object, weights.data(), scalar.data(), first, count);
    prt_sf_kernels_avx2.cast_field(object, weights.data(), simd.data(), first, count);
    std::vector<double> magnitude(scalar.size(), 0.0);
    for (uint32_t c = 0; c < 3; ++c)
      for (uint64_t e = first * n2; e < (first + count) * n2; ++e)
        for (uint32_t r = 0; r < rows; ++r)
          magnitude[c * points * n2 + e] +=
              std::fabs(double(weights[3 * r + c]) * o.srf[r * points * n2 + e]);
    check_within(scalar, simd, magnitude, rows);
    // Outside the range neither writes.
    for (uint64_t e = 0; e < first * n2; ++e) EXPECT_EQ(simd[e], 0.0f);
  }
}

#endif  // PRT_HAS_X86_SIMD

// ---- Whole frames ---------------------------------------------------------------------------

// A glossy source of `terms` terms with a radiance basis and source field from formulas.
SyntheticObject make_source(uint32_t order, uint32_t side, uint32_t terms) {
  SyntheticObject o = make_patch(order, side);
  const uint32_t n2 = order * order;
  o.glossy = 1;
  o.terms = terms;
  o.brdf_grid = 8;
  o.g_table.assign(size_t(terms) * 64, 0.0f);
  for (size_t e = 0; e < o.g_table.size(); ++e) o.g_table[e] = 0.5f + 0.3f * std::sin(0.7f * e);
  const std::vector<float> cosine = o.transfer;
  o.transfer.clear();
  for (uint32_t v = 0; v < o.vertex_count; ++v)
    for (uint32_t k = 0; k < terms; ++k)
      for (uint32_t i = 0; i < n2; ++i)
        o.transfer.push_back(cosine[n2 * v + i] * (1.0f - 0.2f * k));
  o.oof_shells.shells = 5;
  o.oof_shells.face_size = 3;
  const uint64_t oof_points = prt_sf_point_count(&o.oof_shells);
  o.oof.resize(oof_points * n2);
  for (size_t e = 0; e < o.oof.size(); ++e) o.oof[e] = 0.2f * std::sin(0.37f * float(e));
  for (uint64_t p = 0; p < oof_points; ++p) o.oof[p * n2] = 2.5f;
  o.basis_size = 3;
  o.basis.resize(size_t(3) * o.vertex_count);
  for (size_t e = 0; e < o.basis.size(); ++e) o.basis[e] = 0.4f + 0.1f * std::cos(float(e));
  o.vertex_weights.assign(o.vertex_count, 1.0f / float(o.vertex_count));
  o.basis_inverse = {1.0f, 0.1f, 0.0f, 0.0f, 1.0f, 0.2f, 0.1f, 0.0f, 1.0f};
  o.srf_shells.shells = 5;
  o.srf_shells.face_size = 3;
  const uint64_t srf_points = prt_sf_point_count(&o.srf_shells);
  o.srf.resize(size_t(3) * terms * srf_points * n2);
  for (size_t e = 0; e < o.srf.size(); ++e) o.srf[e] = 0.05f * std::sin(0.11f * float(e) + 1.0f);
  return o;
}

// Three instances: a 13 x 13 receiver, a glossy source of 3 terms turned about a tilted axis and
// a second copy of it, all within each other's fields; 3 bounces on `backend`.
struct FrameScene {
  SyntheticObject floor, source;
  prt::ContextPtr context;
  prt_shadowfield_scene* scene = nullptr;
  prt_workers* workers = nullptr;
  float probe_spacing = 0.0f;  // prt_shadowfield_settings::bounce_probe_spacing

  FrameScene(uint32_t order, prt_simd_isa isa)
      : floor(make_patch(order, 13)),
        source(make_source(order, 7, 3)),
        context(prt_test::limited_context(PRT_BACKEND_AUTO, isa)) {
    EXPECT_EQ(prt_shadowfield_scene_create(context.get(), 3, &scene), PRT_OK);
    uint32_t floor_id = 0, source_id = 0, id = 0;
    EXPECT_EQ(prt_internal_sf_scene_add_object(scene, floor.view(), &floor_id), PRT_OK);
    EXPECT_EQ(prt_internal_sf_scene_add_object(scene, source.view(), &source_id), PRT_OK);
    const float axis[3] = {0.36f, 0.8f, 0.48f};
    float turn[9];
    axis_rotation(axis, 1.1f, turn);
    const prt_shadowfield_transform t0 = make_transform(identity_rotation(), 0, 0, 0, 3.0f);
    const prt_shadowfield_transform t1 = make_transform(turn, 0.2f, 0.6f, 0.1f);
    const prt_shadowfield_transform t2 = make_transform(identity_rotation(), -0.5f, 0.9f, 0.3f);
    EXPECT_EQ(prt_shadowfield_scene_add_instance(scene, floor_id, &t0, &id), PRT_OK);
    EXPECT_EQ(prt_shadowfield_scene_add_instance(scene, source_id, &t1, &id), PRT_OK);
    EXPECT_EQ(prt_shadowfield_scene_add_instance(scene, source_id, &t2, &id), PRT_OK);
  }
  ~FrameScene() {
    prt_workers_destroy(workers);
    prt_shadowfield_scene_destroy(scene);
  }

  std::vector<float> shade(prt_backend backend, uint32_t threads = 1,
                           prt_result expected = PRT_OK) {
    const std::vector<float> light = test_light(scene->order);
    const float eye[3] = {1.0f, 4.0f, 2.0f};
    prt_shadowfield_settings settings{};
    settings.struct_size = sizeof settings;
    settings.bounces = 3;
    settings.backend = backend;
    settings.bounce_probe_spacing = probe_spacing;
    std::vector<float> out(size_t(floor.vertex_count + 2 * source.vertex_count) * 3);
    float* pointers[3] = {out.data(), out.data() + floor.vertex_count * 3,
                          out.data() + (floor.vertex_count + source.vertex_count) * 3};
    prt_result result;
    if (threads > 1) {
      if (!workers) {
        prt_workers_desc desc{};
        desc.struct_size = sizeof desc;
        desc.thread_count = threads;
        EXPECT_EQ(prt_workers_create(context.get(), &desc, &workers), PRT_OK);
      }
      result =
          prt_shadowfield_shade_workers(workers, scene, light.data(), eye, &settings, pointers);
    } else {
      result = prt_shadowfield_shade(scene, light.data(), eye, &settings, pointers);
    }
    EXPECT_EQ(result, expected) << prt_context_last_message(context.get());
    return out;
  }
};

// The frame on both backends, at the orders whose n^2 is below a SIMD block (2), no block
// divides (3), the default (4), and the largest (6, bands wider than a block). Its outputs are
// sums through 4 passes of reads (8 points), rotations and dot products (n^2 terms) and
// projections over the source's vertices: n = 4 (8 + 2 n^2 + V) rounded terms. The worst case
// (gamma_n) is far from what independent roundings give; the bound is the probabilistic one,
// sqrt(n) u on the output's scale per backend (Higham and Mary, SIAM J. Sci. Comput. 2019).
TEST(ShadowfieldSimdFrame, AgreesWithScalar) {
  SKIP_WITHOUT_AVX2();
  for (const uint32_t order : {2u, 3u, 4u, 6u}) {
    FrameScene s(order, PRT_SIMD_ISA_AUTO);
    const std::vector<float> scalar = s.shade(PRT_BACKEND_CPU);
    const std::vector<float> simd = s.shade(PRT_BACKEND_SIMD);
    const double n2 = order * order;
    const double terms = 4.0 * (8.0 + 2.0 * n2 + s.source.vertex_count);
    const double bound = 2.0 * std::sqrt(terms) * kUnit * max_abs(scalar);
    const double difference = max_difference(scalar, simd);
    EXPECT_LE(difference, bound) << "order " << order;
    EXPECT_GT(max_abs(scalar), 0.1);  // lit: the comparison is not of zeros
    RecordProperty("order" + std::to_string(order) + "_difference_over_bound",
                   std::to_string(difference / bound));
  }
}

// The same frame with the log-space product: the exponential adds its D directions' terms to
// each blocked vertex's light.
TEST(ShadowfieldSimdFrame, AgreesWithScalarWithTheLogProduct) {
  SKIP_WITHOUT_AVX2();
  for (const uint32_t order : {2u, 4u, 6u}) {
    FrameScene s(order, PRT_SIMD_ISA_AUTO);
    ASSERT_EQ(prt_shadowfield_scene_set_product(s.scene, PRT_SHADOWFIELD_PRODUCT_LOG), PRT_OK);
    const std::vector<float> scalar = s.shade(PRT_BACKEND_CPU);
    const std::vector<float> simd = s.shade(PRT_BACKEND_SIMD);
    const double n2 = order * order;
    const double terms =
        4.0 * (8.0 + 2.0 * n2 + s.source.vertex_count) + s.scene->exp_rule.directions;
    const double bound = 2.0 * std::sqrt(terms) * kUnit * max_abs(scalar);
    const double difference = max_difference(scalar, simd);
    EXPECT_LE(difference, bound) << "order " << order;
    EXPECT_GT(max_abs(scalar), 0.1);
    RecordProperty("log_order" + std::to_string(order) + "_difference_over_bound",
                   std::to_string(difference / bound));
  }
}

// With bounce probes (a 5 x 5 grid on both objects, far fewer than their vertices), each bounce
// adds a probe's reads and its rotation (8 + n^2 terms), then a vertex's read of its probes (8).
TEST(ShadowfieldSimdFrame, AgreesWithScalarWithBounceProbes) {
  SKIP_WITHOUT_AVX2();
  for (const uint32_t order : {2u, 4u, 6u}) {
    FrameScene s(order, PRT_SIMD_ISA_AUTO);
    s.probe_spacing = 0.25f;
    const std::vector<float> scalar = s.shade(PRT_BACKEND_CPU);
    ASSERT_EQ(prt_shadowfield_instance_probe_count(s.scene, 0), 25u);
    ASSERT_EQ(prt_shadowfield_instance_probe_count(s.scene, 1), 25u);
    const std::vector<float> simd = s.shade(PRT_BACKEND_SIMD);
    const double n2 = order * order;
    const double terms = 4.0 * (8.0 + 2.0 * n2 + s.source.vertex_count) + 3.0 * (16.0 + n2);
    const double bound = 2.0 * std::sqrt(terms) * kUnit * max_abs(scalar);
    const double difference = max_difference(scalar, simd);
    EXPECT_LE(difference, bound) << "order " << order;
    EXPECT_GT(max_abs(scalar), 0.1);
    RecordProperty("probes_order" + std::to_string(order) + "_difference_over_bound",
                   std::to_string(difference / bound));
  }
}

// The pool splits vertices, probes and field points across threads; each is computed as on one
// thread.
TEST(ShadowfieldSimdFrame, ThreadsGiveTheSameBits) {
  SKIP_WITHOUT_AVX2();
  for (const float spacing : {0.0f, 0.25f}) {
    FrameScene s(4, PRT_SIMD_ISA_AUTO);
    s.probe_spacing = spacing;
    const std::vector<float> one = s.shade(PRT_BACKEND_SIMD);
    const std::vector<float> two = s.shade(PRT_BACKEND_SIMD, 2);
    EXPECT_TRUE(prt_test::same_bits(one, two)) << "probe spacing " << spacing;
  }
}

TEST(ShadowfieldSimdFrame, AutoPicksSimdWhereUsable) {
  SKIP_WITHOUT_AVX2();
  FrameScene s(4, PRT_SIMD_ISA_AUTO);
  EXPECT_TRUE(prt_test::same_bits(s.shade(PRT_BACKEND_AUTO), s.shade(PRT_BACKEND_SIMD)));
}

// With the ISA limited below AVX2, AUTO shades as the scalar reference and SIMD is refused.
TEST(ShadowfieldSimdFrame, BelowAvx2AutoIsScalarAndSimdRefused) {
  FrameScene s(4, PRT_SIMD_ISA_SSE41);
  const std::vector<float> scalar = s.shade(PRT_BACKEND_CPU);
  EXPECT_TRUE(prt_test::same_bits(s.shade(PRT_BACKEND_AUTO), scalar));
  s.shade(PRT_BACKEND_SIMD, 1, PRT_ERROR_UNSUPPORTED_BACKEND);
}

}  // namespace
}  // namespace prt::test
