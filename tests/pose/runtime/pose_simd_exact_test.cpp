// SPDX-License-Identifier: MIT
// Model 1's exact part on the SIMD backend (float: skinned normal and SH recurrence) against the
// scalar reference (double), alone: the learned part is made zero (every basis offset and scale
// 0), so transfer and shading are rho A_l / pi y_c(n) and its light-weighted sum.
//
// The bound, derived per value from two facts of real SH (the addition theorem): for band l,
// |y_lm| <= N_l = sqrt((2l+1) / 4 pi), |grad y_lm| <= sqrt(l(l+1)) N_l, and for the band's sum
// g(n) = sum_m e_m y_lm(n), |g| <= |e| N_l and |grad g| <= sqrt(l(l+1)) |e| N_l. The float path
// differs from the double one by
//  - the normal's direction, an angle theta: the skinning matrix K3 blended in float from float
//    joint matrices (per entry within 6 u of |K|_abs = sum_k w_k |K_j|), its cofactors
//    (2 products: 14 u of cof_abs, the cofactors of |K|_abs), cof n (3 more), so
//    |d m| <= 17 u |cof_abs| |n_local| and theta <= 17 u |cof_abs| |n_local| / |cof n_local| + 2 u
//    (the normalisation); caller normals only the normalisation, theta <= 2 u;
//  - the recurrence at a given normal: (4 l + 4) u N_l per value (three roundings a step of the
//    three-term recurrence and two of each power of x + i y, the constants rounded once);
//  - shading's C-term FMA sum, the light folded in float and the final addition: (C + 2) u
//    of sum_l |e_l| N_l; transfer's product with the factor and addition: 3 u N_l per value.
// So a coefficient of band l is within |f_l| N_l (theta sqrt(l(l+1)) + (4 l + 7) u) and a channel
// within sum_l |e_l| N_l (theta sqrt(l(l+1)) + (4 l + C + 6) u), e_l the band's folded light
// f_l L'. Every value is checked against that; the worst ratio of error to bound is printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "pose/pose_blob.hpp"
#include "support/limited_context.hpp"
#include "support/simd_dispatch.hpp"

namespace {

using namespace prt_test;

const double kPi = 3.14159265358979323846;
const double kU = 0x1p-24;

// theta's bound for vertex v skinned at `rotations` (SPEC §7.3's K, in double).
double skinned_angle_bound(const PoseSection& s, const std::vector<float>& rotations, uint32_t v) {
  const std::vector<Affine> g = globals(s, rotations);
  const Affine m_inv = affine_inverse(model_frame(g[s.model_joint]));
  const PoseSkin& k = s.skin[v];
  // A joint index >= J (quick validation only) counts as weight 0; no weight left: identity.
  auto used = [&](int i) { return k.weights[i] > 0 && k.joints[i] < s.joint_count(); };
  double total = 0, kk[9] = {0}, ka[9] = {0};
  for (int i = 0; i < 4; ++i) total += used(i) ? k.weights[i] : 0;
  if (total == 0)
    for (int e = 0; e < 9; e += 4) kk[e] = ka[e] = 1;
  for (int i = 0; i < 4; ++i) {
    if (!used(i)) continue;
    const Affine kj = affine_mul(
        m_inv, affine_mul(g[k.joints[i]], from_float12(s.joints[k.joints[i]].inverse_bind)));
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        kk[3 * r + c] += k.weights[i] / total * kj[4 * r + c];
        ka[3 * r + c] += k.weights[i] / total * std::fabs(kj[4 * r + c]);
      }
  }
  double m[3] = {0, 0, 0}, ma[3] = {0, 0, 0};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      const double cof = kk[3 * r1 + c1] * kk[3 * r2 + c2] - kk[3 * r1 + c2] * kk[3 * r2 + c1];
      const double cofa = ka[3 * r1 + c1] * ka[3 * r2 + c2] + ka[3 * r1 + c2] * ka[3 * r2 + c1];
      m[r] += cof * k.normal[c];
      ma[r] += cofa * std::fabs(k.normal[c]);
    }
  const double len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
  const double lena = std::sqrt(ma[0] * ma[0] + ma[1] * ma[1] + ma[2] * ma[2]);
  return 17 * kU * lena / len + 2 * kU;
}

// L' = rotate(L, R_m^T) (no world rotation), R_m from prt_pose_skin's model frame.
std::vector<float> model_light(const prt_asset* asset, const PoseSection& s,
                               const std::vector<float>& r, const std::vector<float>& light) {
  std::vector<float> frame(12);
  const prt_pose_input pose = pose_of(r);
  EXPECT_EQ(prt_pose_skin(asset, &pose, 0, 0, nullptr, nullptr, frame.data()), PRT_OK);
  float rt[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rt[3 * i + j] = frame[4 * j + i];
  std::vector<float> out(light.size());
  EXPECT_EQ(prt_sh_rotate(s.order, rt, light.data(), out.data(), 3), PRT_OK);
  return out;
}

// Transfer and shading of every vertex of `s` (loaded as `a`, its learned part 0) on both
// backends, each value against the bound above; the worst ratios of error to bound so far in
// worst_transfer and worst_shade.
void check_exact(const LoadedAsset& a, const PoseSection& s, const std::vector<float>& r,
                 bool caller_normals, double& worst_transfer, double& worst_shade) {
  const uint32_t vertices = s.vertices, order = s.order, n2 = order * order;
  const prt_pose_input pose = pose_of(r);
  std::vector<float> normals(3 * vertices);
  for (uint32_t v = 0; v < vertices; ++v)  // unnormalised on purpose
    for (int i = 0; i < 3; ++i) normals[3 * v + i] = float(std::sin(1.7 * v + 2.3 * i) * 3.0);
  const float* given = caller_normals ? normals.data() : nullptr;
  std::vector<float> t_cpu(vertices * n2), t_simd(vertices * n2);
  ASSERT_EQ(prt_pose_transfer(a.asset, PRT_BACKEND_CPU, &pose, given, 0, vertices, t_cpu.data()),
            PRT_OK);
  ASSERT_EQ(prt_pose_transfer(a.asset, PRT_BACKEND_SIMD, &pose, given, 0, vertices, t_simd.data()),
            PRT_OK);
  std::vector<float> light(3 * n2);
  for (size_t i = 0; i < light.size(); ++i) light[i] = float(std::cos(0.9 * i + order));
  prt_pose_light l{};
  l.struct_size = sizeof l;
  l.light_rgb = light.data();
  l.normals = given;
  std::vector<float> rgb_cpu(3 * vertices), rgb_simd(3 * vertices);
  ASSERT_EQ(prt_pose_shade(a.asset, PRT_BACKEND_CPU, &pose, &l, 0, vertices, rgb_cpu.data()),
            PRT_OK);
  ASSERT_EQ(prt_pose_shade(a.asset, PRT_BACKEND_SIMD, &pose, &l, 0, vertices, rgb_simd.data()),
            PRT_OK);
  const std::vector<float> lp = model_light(a.asset, s, r, light);
  // |f_l| N_l and |e_l| N_l per band and channel.
  std::vector<double> fn(order), en(3 * order);
  for (uint32_t b = 0; b < order; ++b) {
    const double f = s.albedo * prt_sh_cosine_band_factor(b) / kPi;
    fn[b] = std::fabs(f) * std::sqrt((2 * b + 1) / (4 * kPi));
    for (int ch = 0; ch < 3; ++ch) {
      double e2 = 0;
      for (uint32_t c = b * b; c < (b + 1) * (b + 1); ++c)
        e2 += f * f * lp[3 * c + ch] * lp[3 * c + ch];
      en[3 * b + ch] = std::sqrt(e2) * std::sqrt((2 * b + 1) / (4 * kPi));
    }
  }
  for (uint32_t v = 0; v < vertices; ++v) {
    const double theta = caller_normals ? 2 * kU : skinned_angle_bound(s, r, v);
    for (uint32_t b = 0; b < order; ++b)
      for (uint32_t c = b * b; c < (b + 1) * (b + 1); ++c) {
        const double bound = fn[b] * (theta * std::sqrt(b * (b + 1.0)) + (4 * b + 7) * kU);
        const double err = std::fabs(double(t_simd[v * n2 + c]) - t_cpu[v * n2 + c]);
        if (bound > 0) worst_transfer = std::max(worst_transfer, err / bound);
        EXPECT_LE(err, bound) << "vertex " << v << " c " << c;
      }
    for (int ch = 0; ch < 3; ++ch) {
      double bound = 0;
      for (uint32_t b = 0; b < order; ++b)
        bound += en[3 * b + ch] * (theta * std::sqrt(b * (b + 1.0)) + (4 * b + n2 + 6) * kU);
      const double err = std::fabs(double(rgb_simd[3 * v + ch]) - rgb_cpu[3 * v + ch]);
      worst_shade = std::max(worst_shade, err / bound);
      EXPECT_LE(err, bound) << "vertex " << v << " ch " << ch;
    }
  }
}

class PoseSimdExact : public SimdIsaTest {};

TEST_P(PoseSimdExact, SkinnedNormalAndBasisWithinTheFloatBound) {
  if (GetParam() == PRT_SIMD_ISA_SSE41) GTEST_SKIP() << "no SSE4.1 kernel";
  double worst_transfer = 0, worst_shade = 0;
  for (uint32_t order = 1; order <= 8; ++order)
    for (const bool caller_normals : {false, true}) {
      SCOPED_TRACE(testing::Message() << "order " << order << " caller normals " << caller_normals);
      // 61 vertices: seven full batches of 8 and a partial one.
      PoseSection s = random_section(order, 61, 7, 4, 3, 8, 1, 100 + order);
      for (float& p : s.basis_params) p = 0.0f;  // the learned part is 0
      const LoadedAsset a(ctx, pose_blob(s));
      ASSERT_EQ(a.result, PRT_OK);
      check_exact(a, s, random_rotations(7, 200 + order), caller_normals, worst_transfer,
                  worst_shade);
    }
  std::printf(
      "exact part, SIMD vs scalar: worst error %.3f of the bound (transfer), %.3f (shade)\n",
      worst_transfer, worst_shade);
}

// What the scalar path skips the SIMD one must not blend: joint indices >= J (quick validation
// only), and joints named with weight 0 whose matrices overflow float (scales of 1e20 on two
// chained joints). Vertices with no usable weight keep the identity.
TEST_P(PoseSimdExact, IgnoredInfluencesStayOutOfTheBlend) {
  if (GetParam() == PRT_SIMD_ISA_SSE41) GTEST_SKIP() << "no SSE4.1 kernel";
  PoseSection s = random_section(6, 13, 4, 2, 3, 8, 1, 300);
  for (float& p : s.basis_params) p = 0.0f;
  s.joints[2].scale = {1e20f, 1e20f, 1e20f};
  s.joints[3].scale = {1e20f, 1e20f, 1e20f};
  for (PoseSkin& k : s.skin) k.joints = {0, 1, 0, 1};  // only joints 0 and 1 carry weight
  s.skin[0].joints = {200, 1, 0, 0};
  s.skin[0].weights = {30000, 35535, 0, 0};
  s.skin[1].joints = {250, 251, 252, 253};  // no usable weight: the identity
  s.skin[2].weights = {0, 0, 0, 0};         // likewise
  s.skin[3].joints = {3, 0, 2, 1};
  s.skin[3].weights = {0, 40000, 0, 25535};
  s.skin[4].joints = {1, 255, 3, 0};
  s.skin[4].weights = {20000, 0, 0, 1000};
  const LoadedAsset a(ctx, pose_blob(s), PRT_VALIDATE_QUICK);
  ASSERT_EQ(a.result, PRT_OK);
  double worst_transfer = 0, worst_shade = 0;
  check_exact(a, s, random_rotations(4, 301), false, worst_transfer, worst_shade);
  std::printf("ignored influences: worst error %.3f of the bound (transfer), %.3f (shade)\n",
              worst_transfer, worst_shade);
}

INSTANTIATE_TEST_SUITE_P(Isa, PoseSimdExact, kSimdIsas, isa_test_name);

}  // namespace
