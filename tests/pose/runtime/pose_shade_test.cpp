// SPDX-License-Identifier: MIT
// Transfer and shading of the `pose` runtime: the transfer against the SPEC's model restated in
// double (pose/pose_blob.hpp), model 1's exact part against prt_sh_eval times A_l / pi, shading
// against the transfer dotted with the light rotated by prt_sh_rotate, a property of the world
// placement, the SIMD backend against the scalar one within a bound derived from float
// arithmetic, the backend dispatch, workers and the argument checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "pose/pose_blob.hpp"
#include "support/limited_context.hpp"
#include "support/simd_dispatch.hpp"

namespace {

using namespace prt_test;

const double kPi = 3.14159265358979323846;
const double kU = 0x1p-24;  // float unit roundoff

std::vector<float> transfer_all(const prt_asset* asset, prt_backend backend, const PoseSection& s,
                                const std::vector<float>& r, const float* normals = nullptr,
                                prt_result expected = PRT_OK) {
  std::vector<float> out(size_t(s.vertices) * s.coefficients(), -99.0f);
  const prt_pose_input pose = pose_of(r);
  EXPECT_EQ(prt_pose_transfer(asset, backend, &pose, normals, 0, s.vertices, out.data()), expected);
  return out;
}

prt_pose_light light_of(const std::vector<float>& rgb, const float* world = nullptr,
                        const float* normals = nullptr) {
  prt_pose_light l{};
  l.struct_size = sizeof l;
  l.light_rgb = rgb.data();
  l.world_from_character = world;
  l.normals = normals;
  return l;
}

std::vector<float> shade_all(const prt_asset* asset, prt_backend backend, const PoseSection& s,
                             const std::vector<float>& r, const prt_pose_light& light,
                             prt_result expected = PRT_OK) {
  std::vector<float> out(size_t(s.vertices) * 3, -99.0f);
  const prt_pose_input pose = pose_of(r);
  EXPECT_EQ(prt_pose_shade(asset, backend, &pose, &light, 0, s.vertices, out.data()), expected);
  return out;
}

std::vector<float> random_light(uint32_t order, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<float> l(size_t(order) * order * 3);
  for (float& x : l) x = unit(rng);
  l[0] += 3.0f, l[1] += 3.0f, l[2] += 3.0f;
  return l;
}

// Row-major rotation of angle t about a unit axis.
std::vector<float> rotation(double x, double y, double z, double t) {
  const double len = std::sqrt(x * x + y * y + z * z);
  x /= len, y /= len, z /= len;
  const double c = std::cos(t), s = std::sin(t), k = 1 - c;
  return {float(c + x * x * k),     float(x * y * k - z * s), float(x * z * k + y * s),
          float(y * x * k + z * s), float(c + y * y * k),     float(y * z * k - x * s),
          float(z * x * k - y * s), float(z * y * k + x * s), float(c + z * z * k)};
}

// L' = rotate(L, (W R_m)^T), R_m from prt_pose_skin's model frame.
std::vector<float> model_light(const prt_asset* asset, const PoseSection& s,
                               const std::vector<float>& r, const std::vector<float>& light,
                               const float* world) {
  std::vector<float> frame(12);
  const prt_pose_input pose = pose_of(r);
  EXPECT_EQ(prt_pose_skin(asset, &pose, 0, 0, nullptr, nullptr, frame.data()), PRT_OK);
  float rt[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double wr = 0;
      for (int k = 0; k < 3; ++k) wr += (world ? world[3 * j + k] : (j == k)) * frame[4 * k + i];
      rt[3 * i + j] = float(wr);
    }
  std::vector<float> out(light.size());
  EXPECT_EQ(prt_sh_rotate(s.order, rt, light.data(), out.data(), 3), PRT_OK);
  return out;
}

struct Loaded {
  prt::ContextPtr context;
  LoadedAsset asset;
  Loaded(const PoseSection& s, prt_simd_isa isa = PRT_SIMD_ISA_AUTO,
         prt_backend limit = PRT_BACKEND_AUTO)
      : context(limited_context(limit, isa)), asset(context.get(), pose_blob(s)) {
    EXPECT_EQ(asset.result, PRT_OK) << prt_context_last_message(context.get());
  }
  const prt_asset* get() const { return asset.asset; }
};

// Model 0: t[v][c] = sum_k U[v][k] y[k][c] from the SPEC's model in double, t_00 clamped.
TEST(PoseTransfer, DirectModelMatchesTheSpec) {
  for (uint32_t bits : {8u, 16u}) {
    const PoseSection s = random_section(3, 9, 6, 5, 7, bits, 0, 30 + bits);
    const Loaded a(s);
    const std::vector<float> r = random_rotations(6, 31);
    const std::vector<float> t = transfer_all(a.get(), PRT_BACKEND_CPU, s, r);
    const std::vector<double> y = coefficients(s, r);
    double worst = 0;
    for (uint32_t v = 0; v < s.vertices; ++v)
      for (uint32_t c = 0; c < 9; ++c) {
        double sum = 0, magnitude = 0;
        for (uint32_t k = 0; k < s.basis_dims; ++k) {
          sum += basis_u(s, v, k) * y[k * 9 + c];
          magnitude += std::fabs(basis_u(s, v, k) * y[k * 9 + c]);
        }
        // SPEC §7.3 clamps t_00 of model 0 to [0, albedo / (2 sqrt(pi))]; the clamped value
        // is the float sum moved by a correction summed in double, so one more rounding.
        const double unoccluded = s.albedo / (2.0 * std::sqrt(3.14159265358979323846));
        const double expected = c == 0 ? std::clamp(sum, 0.0, unoccluded) : sum;
        const double err = std::fabs(t[v * 9 + c] - expected);
        worst = std::max(worst, err / (kU * magnitude));
        EXPECT_LE(err, 3 * kU * magnitude + kU * std::fabs(expected)) << v << " " << c;
      }
    std::printf("direct transfer, %u bits: worst error %.2f u M\n", bits, worst);
  }
}

// SPEC §7.3's clamp: t_00 within [0, albedo / (2 sqrt(pi))] on every backend, for random models
// whose unclamped t_00 leaves that range at some vertices (counted, so the test exercises it).
TEST(PoseTransfer, T00StaysInTheUniformSkysBounds) {
  for (uint32_t model : {0u, 1u}) {
    const PoseSection s = random_section(3, 37, 5, 4, 6, 16, model, 90 + model);
    const Loaded a(s);
    const std::vector<float> r = random_rotations(5, 91);
    const std::vector<double> y = coefficients(s, r);
    const double unoccluded = s.albedo / (2.0 * std::sqrt(3.14159265358979323846));
    uint32_t crossing = 0;
    std::vector<double> magnitude(s.vertices, 0.0);
    for (uint32_t v = 0; v < s.vertices; ++v) {
      double learned = 0;
      for (uint32_t k = 0; k < s.basis_dims; ++k) {
        learned += basis_u(s, v, k) * y[k * 9];
        magnitude[v] += std::fabs(basis_u(s, v, k) * y[k * 9]);
      }
      const double t00 = learned + (model == 1 ? unoccluded : 0.0);
      crossing += t00 < 0.0 || t00 > unoccluded;
    }
    EXPECT_GT(crossing, 0u) << "model " << model << ": nothing to clamp";
    for (prt_backend backend : {PRT_BACKEND_CPU, PRT_BACKEND_SIMD}) {
      std::vector<float> t(s.vertices * 9);
      const prt_pose_input pose = pose_of(r);
      const prt_result result =
          prt_pose_transfer(a.get(), backend, &pose, nullptr, 0, s.vertices, t.data());
      if (backend == PRT_BACKEND_SIMD && result == PRT_ERROR_UNSUPPORTED_BACKEND) continue;
      ASSERT_EQ(result, PRT_OK);
      // The clamp corrects the backend's float sum by a double one: within the sum's rounding
      // (as DirectModelMatchesTheSpec bounds it) and one more of the bound.
      for (uint32_t v = 0; v < s.vertices; ++v) {
        const double slack = 3 * kU * magnitude[v] + kU * unoccluded;
        EXPECT_GE(t[v * 9], -slack) << model << " " << v;
        EXPECT_LE(t[v * 9], unoccluded + slack) << model << " " << v;
      }
    }
  }
}

// Model 1 with a zero regression is the exact part alone: albedo A_l / pi y_lm(n) at the skinned
// normal, or at the caller's normals when given.
TEST(PoseTransfer, ResidualModelsExactPartIsTheCosineLobe) {
  for (uint32_t order : {1u, 3u, 5u, 8u}) {
    PoseSection s = random_section(order, 6, 3, 2, 2, 8, 1, order);
    s.regression.assign(s.regression.size(), 0.0f);
    s.albedo = 0.75f;
    const Loaded a(s);
    const std::vector<float> r = random_rotations(3, 40 + order);
    const prt_pose_input pose = pose_of(r);
    std::vector<float> normals(3 * s.vertices);
    ASSERT_EQ(prt_pose_skin(a.get(), &pose, 0, s.vertices, nullptr, normals.data(), nullptr),
              PRT_OK);
    std::vector<float> given(3 * s.vertices);
    for (uint32_t v = 0; v < s.vertices; ++v) given[3 * v] = 0.6f, given[3 * v + 2] = -0.8f;
    const uint32_t n2 = order * order;
    double worst = 0;
    for (int caller : {0, 1}) {
      const std::vector<float>& n = caller ? given : normals;
      for (prt_backend backend : {PRT_BACKEND_CPU, PRT_BACKEND_AUTO}) {
        const std::vector<float> t =
            transfer_all(a.get(), backend, s, r, caller ? given.data() : nullptr);
        for (uint32_t v = 0; v < s.vertices; ++v) {
          std::vector<float> basis(n2);
          ASSERT_EQ(prt_sh_eval(order, &n[3 * v], basis.data()), PRT_OK);
          for (uint32_t l = 0; l < order; ++l)
            for (uint32_t c = l * l; c < (l + 1) * (l + 1); ++c) {
              const double expected = 0.75 * prt_sh_cosine_band_factor(l) / kPi * basis[c];
              worst = std::max(worst, std::fabs(t[v * n2 + c] - expected));
              EXPECT_NEAR(t[v * n2 + c], expected, 1e-7) << order << " " << v << " " << c;
            }
        }
      }
    }
    std::printf("exact part, order %u: worst error %.3g\n", order, worst);
  }
}

// Shading is sum_c t[v][c] L'[c] with t from prt_pose_transfer and L' the light rotated into the
// model frame by (W R_m)^T, for both models, a turned model joint and a world placement.
TEST(PoseShade, IsTheTransferDottedWithTheLightInTheModelFrame) {
  for (uint32_t model : {0u, 1u}) {
    const PoseSection s = random_section(4, 11, 5, 4, 6, 16, model, 50 + model);
    const Loaded a(s);
    const std::vector<float> r = random_rotations(5, 51);
    const std::vector<float> light = random_light(4, 52);
    const std::vector<float> world = rotation(0.3, 1, -0.2, 0.8);
    const std::vector<float> t = transfer_all(a.get(), PRT_BACKEND_CPU, s, r);
    const std::vector<float> lp = model_light(a.get(), s, r, light, world.data());
    const std::vector<float> rgb =
        shade_all(a.get(), PRT_BACKEND_CPU, s, r, light_of(light, world.data()));
    double worst = 0;
    for (uint32_t v = 0; v < s.vertices; ++v)
      for (int ch = 0; ch < 3; ++ch) {
        double sum = 0, magnitude = 0;
        for (uint32_t c = 0; c < 16; ++c) {
          sum += double(t[v * 16 + c]) * lp[3 * c + ch];
          magnitude += std::fabs(double(t[v * 16 + c]) * lp[3 * c + ch]);
        }
        const double err = std::fabs(rgb[3 * v + ch] - sum);
        worst = std::max(worst, err / (kU * magnitude));
        EXPECT_LE(err, 4 * kU * magnitude) << model << " " << v << " " << ch;
      }
    std::printf("shade vs transfer . L', model %u: worst error %.2f u M\n", model, worst);
  }
}

// Turning the world placement and the light by the same rotation leaves the radiance unchanged.
TEST(PoseShade, TurningTheWorldAndTheLightTogetherChangesNothing) {
  for (uint32_t model : {0u, 1u}) {
    const PoseSection s = random_section(5, 8, 4, 3, 5, 8, model, 60 + model);
    const Loaded a(s);
    const std::vector<float> r = random_rotations(4, 61);
    const std::vector<float> light = random_light(5, 62);
    const std::vector<float> world = rotation(1, 0.2, 0.1, -0.4);
    const std::vector<float> turn = rotation(-0.3, 0.5, 1, 2.2);
    std::vector<float> turned_world(9), turned_light(light.size());
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double sum = 0;
        for (int k = 0; k < 3; ++k) sum += double(turn[3 * i + k]) * world[3 * k + j];
        turned_world[3 * i + j] = float(sum);
      }
    ASSERT_EQ(prt_sh_rotate(5, turn.data(), light.data(), turned_light.data(), 3), PRT_OK);
    const std::vector<float> before =
        shade_all(a.get(), PRT_BACKEND_CPU, s, r, light_of(light, world.data()));
    const std::vector<float> after =
        shade_all(a.get(), PRT_BACKEND_CPU, s, r, light_of(turned_light, turned_world.data()));
    double scale = 0, worst = 0;
    for (float x : before) scale = std::max(scale, double(std::fabs(x)));
    for (size_t i = 0; i < before.size(); ++i) {
      worst = std::max(worst, std::fabs(double(before[i]) - after[i]) / scale);
      EXPECT_NEAR(before[i], after[i], 2e-6 * scale) << i;
    }
    std::printf("world + light turned, model %u: worst change %.3g of the largest radiance\n",
                model, worst);
  }
}

// ---- SIMD against the scalar reference ----

// The bound: the SIMD path rounds each folded weight (scale_k w_k or scale_k y[k][c]) to float
// once, the bias once, sums q products with an FMA each (one rounding; shading splits them over
// 8 lanes and adds the lanes by a tree of 3), adds the bias (1) and, for model 1, the exact part
// in float (2, when its own error is small against M: pose_simd_exact_test.cpp bounds it alone,
// from the skinned normal's conditioning and the SH recurrence). That is at most (q + 8) u of M,
// the sum of the magnitudes of the terms (|offset_k w_k| + |scale_k value w_k| over k, plus the
// exact part's); the scalar reference adds 1 u. Each value must be within that bound,
// (q + 9) u M; and since the bound is linear in q while rounding errors mostly cancel, the worst
// over the fixed seeds below must also stay within 8 u M (measured: 3.45 u M for transfer,
// 1.72 u M for shading).
class PoseSimd : public SimdIsaTest {};

struct Config {
  uint32_t order, basis_dims, bits, model;
};

const Config kConfigs[] = {{1, 1, 8, 0}, {2, 13, 16, 1}, {3, 13, 8, 0},   {3, 64, 16, 1},
                           {5, 9, 8, 1}, {8, 37, 8, 0},  {8, 256, 16, 1}, {6, 8, 16, 0}};

TEST_P(PoseSimd, TransferAndShadeAgreeWithTheScalarReference) {
  const uint32_t vertices = 37;  // no SIMD width or group divides it
  if (GetParam() == PRT_SIMD_ISA_SSE41) {
    // No SSE4.1 kernel: SIMD is refused and AUTO runs the scalar code.
    const PoseSection s = random_section(3, vertices, 4, 3, 5, 8, 0, 1);
    const LoadedAsset a(ctx, pose_blob(s));
    const std::vector<float> r = random_rotations(4, 2);
    transfer_all(a.asset, PRT_BACKEND_SIMD, s, r, nullptr, PRT_ERROR_UNSUPPORTED_BACKEND);
    EXPECT_TRUE(same_bits(transfer_all(a.asset, PRT_BACKEND_AUTO, s, r),
                          transfer_all(a.asset, PRT_BACKEND_CPU, s, r)));
    return;
  }
  double worst_transfer = 0, worst_shade = 0;
  for (const Config& cfg : kConfigs) {
    SCOPED_TRACE(testing::Message() << "order " << cfg.order << " q " << cfg.basis_dims << " bits "
                                    << cfg.bits << " model " << cfg.model);
    const PoseSection s =
        random_section(cfg.order, vertices, 6, 5, cfg.basis_dims, cfg.bits, cfg.model, cfg.order);
    const LoadedAsset a(ctx, pose_blob(s));
    ASSERT_EQ(a.result, PRT_OK);
    const std::vector<float> r = random_rotations(6, cfg.basis_dims);
    const uint32_t n2 = cfg.order * cfg.order, q = cfg.basis_dims;
    const std::vector<double> y = coefficients(s, r);
    const std::vector<float> t_cpu = transfer_all(a.asset, PRT_BACKEND_CPU, s, r);
    const std::vector<float> t_simd = transfer_all(a.asset, PRT_BACKEND_SIMD, s, r);
    const std::vector<float> light = random_light(cfg.order, 7);
    const std::vector<float> world = rotation(0.2, 1, 0.4, 1.3);
    const std::vector<float> lp = model_light(a.asset, s, r, light, world.data());
    const std::vector<float> rgb_cpu =
        shade_all(a.asset, PRT_BACKEND_CPU, s, r, light_of(light, world.data()));
    const std::vector<float> rgb_simd =
        shade_all(a.asset, PRT_BACKEND_SIMD, s, r, light_of(light, world.data()));
    // The exact part's magnitude, from the normals the runtime skins.
    std::vector<float> normals(3 * vertices);
    const prt_pose_input pose = pose_of(r);
    ASSERT_EQ(prt_pose_skin(a.asset, &pose, 0, vertices, nullptr, normals.data(), nullptr), PRT_OK);
    for (uint32_t v = 0; v < vertices; ++v) {
      std::vector<float> basis(n2, 0.0f);
      const bool has_normal =
          normals[3 * v] != 0 || normals[3 * v + 1] != 0 || normals[3 * v + 2] != 0;
      if (cfg.model == 1 && has_normal) {
        ASSERT_EQ(prt_sh_eval(cfg.order, &normals[3 * v], basis.data()), PRT_OK);
      }
      std::vector<double> exact(n2);
      for (uint32_t l = 0; l < cfg.order; ++l)
        for (uint32_t c = l * l; c < (l + 1) * (l + 1); ++c)
          exact[c] = s.albedo * prt_sh_cosine_band_factor(l) / kPi * basis[c];
      for (uint32_t c = 0; c < n2; ++c) {
        double m = std::fabs(exact[c]);
        for (uint32_t k = 0; k < q; ++k)
          m += std::fabs(s.basis_params[2 * k] * y[k * n2 + c]) +
               std::fabs(s.basis_params[2 * k + 1] * s.values[v * q + k] * y[k * n2 + c]);
        const double err = std::fabs(double(t_simd[v * n2 + c]) - t_cpu[v * n2 + c]);
        worst_transfer = std::max(worst_transfer, err / (kU * m));
        EXPECT_LE(err, (q + 9) * kU * m) << v << " " << c;
      }
      for (int ch = 0; ch < 3; ++ch) {
        double m = 0;
        for (uint32_t c = 0; c < n2; ++c) m += std::fabs(exact[c] * lp[3 * c + ch]);
        for (uint32_t k = 0; k < q; ++k) {
          double w = 0;
          for (uint32_t c = 0; c < n2; ++c) w += y[k * n2 + c] * lp[3 * c + ch];
          m += std::fabs(s.basis_params[2 * k] * w) +
               std::fabs(s.basis_params[2 * k + 1] * s.values[v * q + k] * w);
        }
        const double err = std::fabs(double(rgb_simd[3 * v + ch]) - rgb_cpu[3 * v + ch]);
        worst_shade = std::max(worst_shade, err / (kU * m));
        EXPECT_LE(err, (q + 9) * kU * m) << v << " " << ch;
      }
    }
  }
  std::printf("SIMD vs scalar: worst transfer error %.2f u M, worst shade error %.2f u M\n",
              worst_transfer, worst_shade);
  EXPECT_LE(worst_transfer, 8.0);
  EXPECT_LE(worst_shade, 8.0);
}

// Split ranges give the bits of one call (a vertex's arithmetic does not depend on where a
// range starts), on every backend.
TEST_P(PoseSimd, SplitRangesEqualOneCall) {
  if (GetParam() == PRT_SIMD_ISA_SSE41) GTEST_SKIP() << "no SSE4.1 kernel";
  const PoseSection s = random_section(3, 37, 4, 3, 11, 8, 1, 5);
  const LoadedAsset a(ctx, pose_blob(s));
  const std::vector<float> r = random_rotations(4, 6);
  const prt_pose_input pose = pose_of(r);
  const std::vector<float> light = random_light(3, 8);
  const prt_pose_light l = light_of(light);
  for (prt_backend backend : {PRT_BACKEND_CPU, PRT_BACKEND_SIMD}) {
    const std::vector<float> whole_t = transfer_all(a.asset, backend, s, r);
    const std::vector<float> whole = shade_all(a.asset, backend, s, r, l);
    for (uint32_t first : {1u, 5u, 30u}) {
      std::vector<float> part(3 * (37 - first)), part_t(9 * (37 - first));
      ASSERT_EQ(prt_pose_shade(a.asset, backend, &pose, &l, first, 37 - first, part.data()),
                PRT_OK);
      ASSERT_EQ(
          prt_pose_transfer(a.asset, backend, &pose, nullptr, first, 37 - first, part_t.data()),
          PRT_OK);
      EXPECT_EQ(std::memcmp(part.data(), whole.data() + 3 * first, 4 * part.size()), 0);
      EXPECT_EQ(std::memcmp(part_t.data(), whole_t.data() + 9 * first, 4 * part_t.size()), 0);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Isa, PoseSimd, kSimdIsas, isa_test_name);

// ---- dispatch ----

ShadeAll pose_shade_all(const PoseSection& s) {
  return [s](const prt_asset* asset, prt_backend backend, std::vector<float>* out) {
    static const std::vector<float> r = random_rotations(4, 70);
    static const std::vector<float> light = random_light(3, 71);
    const prt_pose_input pose = pose_of(r);
    const prt_pose_light l = light_of(light);
    out->assign(size_t(s.vertices) * 3, 0.0f);
    return prt_pose_shade(asset, backend, &pose, &l, 0, s.vertices, out->data());
  };
}

TEST(PoseDispatch, BackendsFollowTheContext) {
  const PoseSection s = random_section(3, 37, 4, 3, 10, 8, 1, 72);
  const Bytes blob = pose_blob(s);
  const ShadeAll shade = pose_shade_all(s);
  prt::ContextPtr probe = limited_context();
  prt_backend_info info = prt::sized<prt_backend_info>();
  ASSERT_EQ(prt_backend_get_info(probe.get(), PRT_BACKEND_SIMD, &info), PRT_OK);
  if (!info.compiled) {
    expect_compiled_out_simd_unsupported(blob, shade);
  } else if (info.usable && info.isa >= PRT_SIMD_ISA_AVX2) {
    EXPECT_FALSE(expect_auto_shades_as_simd(blob, shade));  // float sums differ from double
  }
  expect_cpu_limit_refuses_simd(blob, shade);
  expect_isa_limit_none_refuses_simd(blob, shade);
  expect_gl_not_shaded_here(blob, shade);
}

// ---- workers ----

TEST(PoseWorkers, SplitOverThreadsIsBitwiseTheOneRangeCall) {
  const PoseSection s = random_section(4, 101, 5, 4, 19, 16, 1, 80);
  const Loaded a(s);
  const std::vector<float> r = random_rotations(5, 81);
  const prt_pose_input pose = pose_of(r);
  const std::vector<float> light = random_light(4, 82);
  std::vector<float> normals(3 * s.vertices);
  for (uint32_t v = 0; v < s.vertices; ++v) normals[3 * v + 1] = 1.0f, normals[3 * v] = 0.01f * v;
  for (uint32_t threads : {2u, 3u, 4u}) {
    prt_workers_desc desc = prt::sized<prt_workers_desc>();
    desc.thread_count = threads;
    prt_workers* workers = nullptr;
    ASSERT_EQ(prt_workers_create(a.context.get(), &desc, &workers), PRT_OK);
    for (prt_backend backend : {PRT_BACKEND_CPU, PRT_BACKEND_AUTO}) {
      const float* range_normals = normals.data() + 3;  // the shaded range starts at vertex 1
      for (const float* n : {static_cast<const float*>(nullptr), range_normals}) {
        const prt_pose_light l = light_of(light, nullptr, n);
        std::vector<float> one(3 * 100), split(3 * 100, -1.0f);
        ASSERT_EQ(prt_pose_shade(a.get(), backend, &pose, &l, 1, 100, one.data()), PRT_OK);
        ASSERT_EQ(
            prt_pose_shade_workers(workers, a.get(), backend, &pose, &l, 1, 100, split.data()),
            PRT_OK);
        EXPECT_TRUE(same_bits(one, split)) << threads;
      }
    }
    const prt_pose_light l = light_of(light);
    std::vector<float> out(3 * s.vertices);
    EXPECT_EQ(prt_pose_shade_workers(workers, a.get(), PRT_BACKEND_CPU, &pose, &l, 1, s.vertices,
                                     out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(
        prt_pose_shade_workers(workers, a.get(), PRT_BACKEND_CPU, &pose, nullptr, 0, 4, out.data()),
        PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(
        prt_pose_shade_workers(workers, nullptr, PRT_BACKEND_CPU, &pose, &l, 0, 4, out.data()),
        PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(prt_pose_shade_workers(workers, a.get(), PRT_BACKEND_CPU, &pose, &l, 2, 0xFFFFFFFFu,
                                     out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    prt_workers_destroy(workers);
  }
  const prt_pose_light l = light_of(light);
  std::vector<float> out(3);
  EXPECT_EQ(prt_pose_shade_workers(nullptr, a.get(), PRT_BACKEND_CPU, &pose, &l, 0, 1, out.data()),
            PRT_ERROR_INVALID_ARGUMENT);
}

// ---- arguments ----

TEST(PoseShade, RejectsInvalidRangesAndArguments) {
  const PoseSection s = random_section(2, 5, 3, 2, 3, 8, 1, 90);
  const Loaded a(s);
  const std::vector<float> r = random_rotations(3, 91);
  const prt_pose_input pose = pose_of(r);
  const std::vector<float> light = random_light(2, 92);
  const prt_pose_light l = light_of(light);
  std::vector<float> out(4 * 5 * 3);
  for (prt_backend backend : {PRT_BACKEND_CPU, PRT_BACKEND_AUTO}) {
    EXPECT_EQ(prt_pose_shade(a.get(), backend, &pose, &l, 0, 5, out.data()), PRT_OK);
    EXPECT_EQ(prt_pose_shade(a.get(), backend, &pose, &l, 5, 0, nullptr), PRT_OK);
    EXPECT_EQ(prt_pose_shade(a.get(), backend, &pose, &l, 4, 2, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(prt_pose_shade(a.get(), backend, &pose, &l, 6, 0, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(prt_pose_shade(a.get(), backend, &pose, &l, 0, 1, nullptr),
              PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(prt_pose_shade(a.get(), backend, &pose, nullptr, 0, 1, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(prt_pose_shade(a.get(), backend, nullptr, &l, 0, 1, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(prt_pose_shade(nullptr, backend, &pose, &l, 0, 1, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    prt_pose_light bad = l;
    bad.struct_size = 8;
    EXPECT_EQ(prt_pose_shade(a.get(), backend, &pose, &bad, 0, 1, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    bad = l;
    bad.light_rgb = nullptr;
    EXPECT_EQ(prt_pose_shade(a.get(), backend, &pose, &bad, 0, 1, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    const float scaled[9] = {2, 0, 0, 0, 2, 0, 0, 0, 2}, mirror[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1};
    bad = l;
    bad.world_from_character = scaled;
    EXPECT_EQ(prt_pose_shade(a.get(), backend, &pose, &bad, 0, 1, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    bad.world_from_character = mirror;
    EXPECT_EQ(prt_pose_shade(a.get(), backend, &pose, &bad, 0, 1, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(prt_pose_transfer(a.get(), backend, &pose, nullptr, 0, 5, out.data()), PRT_OK);
    EXPECT_EQ(prt_pose_transfer(a.get(), backend, &pose, nullptr, 5, 0, nullptr), PRT_OK);
    EXPECT_EQ(prt_pose_transfer(a.get(), backend, &pose, nullptr, 3, 3, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(prt_pose_transfer(a.get(), backend, &pose, nullptr, 0, 1, nullptr),
              PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(prt_pose_transfer(a.get(), backend, nullptr, nullptr, 0, 1, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    std::vector<float> zero = r;
    zero[4] = zero[5] = zero[6] = zero[7] = 0.0f;
    const prt_pose_input zero_pose = pose_of(zero);
    EXPECT_EQ(prt_pose_transfer(a.get(), backend, &zero_pose, nullptr, 0, 1, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(prt_pose_shade(a.get(), backend, &zero_pose, &l, 0, 1, out.data()),
              PRT_ERROR_INVALID_ARGUMENT);
  }
  EXPECT_EQ(prt_pose_shade(a.get(), PRT_BACKEND_GL, &pose, &l, 0, 1, out.data()),
            PRT_ERROR_UNSUPPORTED_BACKEND);
  EXPECT_EQ(prt_pose_transfer(a.get(), PRT_BACKEND_GL, &pose, nullptr, 0, 1, out.data()),
            PRT_ERROR_UNSUPPORTED_BACKEND);
  EXPECT_EQ(prt_pose_shade(a.get(), static_cast<prt_backend>(99), &pose, &l, 0, 1, out.data()),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(
      prt_pose_transfer(a.get(), static_cast<prt_backend>(99), &pose, nullptr, 0, 1, out.data()),
      PRT_ERROR_INVALID_ARGUMENT);
}

// An asset without a PSTR section: every function reports NOT_FOUND.
TEST(PoseShade, AssetWithoutPoseReportsNotFound) {
  Context ctx;
  const LoadedAsset a(ctx.ctx, mesh_only_blob());
  ASSERT_EQ(a.result, PRT_OK);
  EXPECT_EQ(prt_asset_techniques(a.asset) & (1u << PRT_TECHNIQUE_POSE), 0u);
  const std::vector<float> r = {0, 0, 0, 1};
  const prt_pose_input pose = pose_of(r);
  const std::vector<float> light = random_light(2, 1);
  const prt_pose_light l = light_of(light);
  std::vector<float> out(64);
  prt_pose_info info = prt::sized<prt_pose_info>();
  EXPECT_EQ(prt_pose_get_info(a.asset, &info), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_pose_features(a.asset, &pose, out.data()), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_pose_bind_pose(a.asset, out.data(), nullptr, nullptr), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_pose_coefficients(a.asset, &pose, out.data(), out.data()), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_pose_skin(a.asset, &pose, 0, 1, out.data(), nullptr, nullptr), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_pose_transfer(a.asset, PRT_BACKEND_CPU, &pose, nullptr, 0, 1, out.data()),
            PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_pose_shade(a.asset, PRT_BACKEND_CPU, &pose, &l, 0, 1, out.data()),
            PRT_ERROR_NOT_FOUND);
}

}  // namespace
