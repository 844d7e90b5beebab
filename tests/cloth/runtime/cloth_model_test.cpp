// SPDX-License-Identifier: MIT
// The exact model of `cloth` (prt_cloth_kernel, prt_cloth_thread_weights) against
// docs/cloth/model.md restated by hand (cloth/cloth_hand_model.hpp): closed forms at normal
// incidence and retroreflection, the textbook Fresnel, every term from chosen angles, the
// model's symmetries, the weights' normalisation, and finite values at the extremes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "cloth/cloth_hand_model.hpp"

namespace {

using namespace cloth_test;

const float kNormal[3] = {0.0f, 0.0f, 1.0f};
const float kWarp[3] = {1.0f, 0.0f, 0.0f};

// The kernel through the API in the frame n = Z, u = X.
Rgb kernel_api(const prt_cloth_params& p, const prt_cloth_weave& w, const Vec3& wi, const Vec3& wo,
               const float* normal = kNormal, const float* warp = kWarp) {
  const auto li = to_float(wi), vo = to_float(wo);
  float rgb[3] = {-1.0f, -1.0f, -1.0f};
  EXPECT_EQ(prt_cloth_kernel(&p, &w, normal, warp, li.data(), vo.data(), rgb), PRT_OK);
  return {rgb[0], rgb[1], rgb[2]};
}

std::vector<double> weights_api(const prt_cloth_weave& w, uint32_t thread, const Vec3& wi,
                                const Vec3& wo) {
  const auto li = to_float(wi), vo = to_float(wo);
  std::vector<float> out(PRT_CLOTH_MAX_THREAD_TANGENTS, -1.0f);
  EXPECT_EQ(prt_cloth_thread_weights(&w, thread, kNormal, kWarp, li.data(), vo.data(), out.data()),
            PRT_OK);
  return std::vector<double>(out.begin(), out.begin() + w.tangent_count[thread]);
}

// The direction as the float the API receives, back in double (the hand model normalises it
// as the API does).
Vec3 as_sent(const Vec3& w) {
  return {float_rounded(w[0]), float_rounded(w[1]), float_rounded(w[2])};
}
// A thread of one tangent at tau = 0 covering everything, the other thread absent.
prt_cloth_params one_thread(int j, float eta, std::array<float, 3> albedo, float kd, float gs,
                            float gv) {
  const prt_cloth_thread on = thread_of(eta, albedo, kd, gs, gv, 1.0f);
  const prt_cloth_thread off = thread_of(1.5f, {0.5f, 0.5f, 0.5f}, 0.5f, 0.1f, 0.2f, 0.0f);
  return j == 0 ? params_of(on, off) : params_of(off, on);
}

const prt_cloth_weave kFlatWeave = weave_of({{0, 1}}, {{0, 1}});

void expect_rgb_near(const Rgb& got, const Rgb& want, double relative, const char* what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(got[c], want[c], relative * std::abs(want[c]) + 1e-30) << what << " channel " << c;
}

// Fresnel through the kernel: albedo 0 leaves the surface term alone, and with both directions
// in the fibre's normal plane at azimuths +a and -a, theta_d = 0, c = cos(a) and
// k = F_r(eta, cos a) cos(a) g(0; gamma_s) M.
double fresnel_seen(float eta, double a) {
  const double gamma_s = 0.2;
  const prt_cloth_params p = one_thread(0, eta, {0, 0, 0}, 0.3f, float(gamma_s), 0.4f);
  const Vec3 wi = as_sent(thread_direction(0, 0.0, 0.0, a));
  const Vec3 wo = as_sent(thread_direction(0, 0.0, 0.0, -a));
  const double ai = std::atan2(wi[1], wi[2]), ao = std::atan2(wo[1], wo[2]);
  const double rest = std::cos(0.5 * (ai - ao)) * gaussian(0.0, float(gamma_s)) * shadowing(ai, ao);
  return kernel_api(p, kFlatWeave, wi, wo)[0] / rest;
}

TEST(ClothFresnel, MatchesTheTextbookSAndPFormulas) {
  for (float eta : {1.05f, 1.33f, 1.46f, 1.539f, 2.5f, 4.0f})
    for (double a : {0.0, 0.2, 0.5, 0.9, 1.2, 1.45, 1.55, 1.569}) {
      const Vec3 wi = as_sent(thread_direction(0, 0.0, 0.0, a));
      const Vec3 wo = as_sent(thread_direction(0, 0.0, 0.0, -a));
      const double c = std::cos(0.5 * (std::atan2(wi[1], wi[2]) - std::atan2(wo[1], wo[2])));
      const double want = fresnel_sp(eta, c);
      EXPECT_NEAR(fresnel_seen(eta, a), want, 1.5e-7 * want) << "eta " << eta << " a " << a;
    }
}

TEST(ClothFresnel, NormalIncidenceGrazingAndIndexOne) {
  for (float eta : {1.33f, 1.539f, 4.0f}) {
    const double f0 = (eta - 1.0) * (eta - 1.0) / ((eta + 1.0) * (eta + 1.0));
    EXPECT_NEAR(fresnel_seen(eta, 0.0), f0, 1e-7 * f0) << eta;
    // Towards grazing incidence (c = cos a -> 0) the reflectance rises to 1, 1 - F_r shrinking
    // in proportion to c.
    const double f3 = fresnel_seen(eta, kPi / 2 - 1e-3), f4 = fresnel_seen(eta, kPi / 2 - 1e-4);
    EXPECT_LE(f4, 1.0);
    EXPECT_NEAR((1.0 - f4) / (1.0 - f3), 0.1, 2e-3) << eta;
  }
  // eta = 1: no interface, so no surface reflection at all.
  const prt_cloth_params p = one_thread(0, 1.0f, {0, 0, 0}, 0.3f, 0.2f, 0.4f);
  for (double a : {0.0, 0.7, 1.5}) {
    const Rgb k =
        kernel_api(p, kFlatWeave, thread_direction(0, 0, 0.1, a), thread_direction(0, 0, -0.2, -a));
    EXPECT_EQ(k[0], 0.0) << a;
  }
}

// w_i = w_o = n: theta = phi = psi = 0, c = 1, M = P = W = 1, so
// k = a (F0 g(0; gamma_s) + (1 - F0)^2 ((1 - kd) g(0; gamma_v) + kd) A / 2).
TEST(ClothKernel, NormalIncidenceClosedForm) {
  const std::array<float, 3> albedo = {0.2f, 0.5f, 0.9f};
  for (int j = 0; j < 2; ++j)
    for (float eta : {1.0f, 1.46f}) {
      const float kd = 0.3f, gs = 0.15f, gv = 0.35f;
      const prt_cloth_params p = one_thread(j, eta, albedo, kd, gs, gv);
      const double f0 = (eta - 1.0) * (eta - 1.0) / ((eta + 1.0) * (eta + 1.0));
      const double g_s = 1.0 / (gs * std::sqrt(2.0 * kPi)), g_v = 1.0 / (gv * std::sqrt(2.0 * kPi));
      Rgb want;
      for (int c = 0; c < 3; ++c)
        want[c] = f0 * g_s + (1 - f0) * (1 - f0) * ((1 - kd) * g_v + kd) * albedo[c] / 2;
      expect_rgb_near(kernel_api(p, kFlatWeave, {0, 0, 1}, {0, 0, 1}), want, 1.5e-7, "normal");
    }
}

// w_i = w_o at elevation theta along the thread: theta_h = theta, theta_d = 0, c = 1,
// M = 1 and P = min(cos theta, cos theta), so W = 1 and
// k = a (F0 g(theta; gamma_s) + (1 - F0)^2 ((1 - kd) g(theta; gamma_v) + kd) A / (2 cos theta))
//     cos theta.
TEST(ClothKernel, RetroreflectionAlongTheThreadClosedForm) {
  const std::array<float, 3> albedo = {0.1f, 0.4f, 0.8f};
  const float eta = 1.539f, kd = 0.2f, gs = 0.3f, gv = 0.6f;
  const double f0 = (eta - 1.0) * (eta - 1.0) / ((eta + 1.0) * (eta + 1.0));
  for (int j = 0; j < 2; ++j)
    for (double theta : {0.1, 0.5, 1.0, 1.4}) {
      const prt_cloth_params p = one_thread(j, eta, albedo, kd, gs, gv);
      const double s = std::sin(theta), c = std::cos(theta);
      const Vec3 w = as_sent(j == 0 ? Vec3{s, 0, c} : Vec3{0, s, c});
      const double th = std::atan2(j == 0 ? w[0] : w[1], w[2]);
      Rgb want;
      for (int ch = 0; ch < 3; ++ch)
        want[ch] =
            (f0 * gaussian(th, gs) + (1 - f0) * (1 - f0) * ((1 - kd) * gaussian(th, gv) + kd) *
                                         albedo[ch] / (2 * std::cos(th))) *
            std::cos(th);
      expect_rgb_near(kernel_api(p, kFlatWeave, w, w), want, 1.5e-7, "retro");
    }
}

// Every term from chosen angles of light and view in the frame of one tilted fibre: the
// directions are built from the angles, and the expected kernel, a f_s cos(theta_i) M (one
// tangent: W = M P / P), from the same angles.
TEST(ClothKernel, EveryTermFromChosenAngles) {
  struct Case {
    int thread;
    double tau, theta_i, phi_i, theta_o, phi_o;
  };
  const Case cases[] = {
      {0, 0.0, 0.3, 0.2, -0.1, -0.4},   {0, 0.0, 0.05, 0.0, -0.05, 0.0},
      {0, 0.4, 0.6, -0.5, 0.2, 0.9},    {0, -0.6, -0.3, 0.3, 0.5, 0.1},
      {1, 0.0, 0.4, 1.0, -0.7, -1.0},   {1, 0.5, -0.2, 0.1, -0.2, 0.1},
      {1, -1.2, -0.9, 0.4, -0.8, -0.3}, {0, 1.5, 1.2, 0.2, 1.0, -0.1},
  };
  const std::array<float, 3> albedo = {0.3f, 0.6f, 0.9f};
  for (const Case& k : cases) {
    const prt_cloth_params p = one_thread(k.thread, 1.46f, albedo, 0.25f, 0.2f, 0.45f);
    prt_cloth_weave w = weave_of({{0, 1}}, {{0, 1}});
    w.offsets[k.thread][0] = float(k.tau);
    const Vec3 wi = as_sent(thread_direction(k.thread, w.offsets[k.thread][0], k.theta_i, k.phi_i));
    const Vec3 wo = as_sent(thread_direction(k.thread, w.offsets[k.thread][0], k.theta_o, k.phi_o));
    ASSERT_GT(wi[2], 0.0);
    ASSERT_GT(wo[2], 0.0);
    const Angles in{k.theta_i, k.phi_i,
                    std::atan2(std::sin(k.theta_i), std::cos(k.theta_i) * std::cos(k.phi_i))};
    const Angles out{k.theta_o, k.phi_o,
                     std::atan2(std::sin(k.theta_o), std::cos(k.theta_o) * std::cos(k.phi_o))};
    ASSERT_GT(shadowing(in.psi, out.psi), 0.0);
    const Rgb fs = fibre_fs_cos(p.threads[k.thread], in, out);
    const double m = shadowing(in.phi, out.phi);
    const Rgb want = {fs[0] * m, fs[1] * m, fs[2] * m};
    expect_rgb_near(kernel_api(p, w, wi, wo), want, 1.5e-7, "angles");
  }
}

// Random directions of the upper hemisphere; `min_z` keeps them off the horizon.
std::vector<Vec3> upper_directions(size_t count, double min_z, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<Vec3> out;
  while (out.size() < count) {
    Vec3 v{normal(rng), normal(rng), std::abs(normal(rng))};
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (double& x : v) x /= len;
    if (v[2] >= min_z) out.push_back(as_sent(v));
  }
  return out;
}

double relative_difference(const Rgb& a, const Rgb& b) {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double scale = std::max(std::abs(a[c]), std::abs(b[c]));
    if (scale > 0.0) worst = std::max(worst, std::abs(a[c] - b[c]) / scale);
  }
  return worst;
}

struct Fabric {
  const char* name;
  prt_cloth_params params;
  prt_cloth_weave weave;
};

std::vector<Fabric> fabrics() {
  return {{"linen", linen_params(), linen_weave()},
          {"satin", satin_params(), satin_weave()},
          {"velvet", velvet_params(), velvet_weave()}};
}

TEST(ClothKernel, MatchesTheHandModelOnFabrics) {
  const std::vector<Vec3> dirs = upper_directions(200, 0.05, 7);
  for (const Fabric& f : fabrics()) {
    double worst = 0.0;
    for (size_t i = 0; i + 1 < dirs.size(); i += 2) {
      const Rgb got = kernel_api(f.params, f.weave, dirs[i], dirs[i + 1]);
      const Rgb want = kernel(f.params, f.weave, dirs[i], dirs[i + 1]);
      worst = std::max(worst, relative_difference(got, want));
    }
    EXPECT_LT(worst, 1.5e-7) << f.name;
  }
}

// Flipping the warp turns every fibre of an all-flat weave around (t -> -t, b -> -b).
TEST(ClothSymmetry, FibreTurnedAroundScattersTheSame) {
  const prt_cloth_params p = linen_params();
  const float flipped[3] = {-1.0f, 0.0f, 0.0f};
  const std::vector<Vec3> dirs = upper_directions(400, 0.0, 11);
  double worst = 0.0;
  for (size_t i = 0; i + 1 < dirs.size(); i += 2)
    worst = std::max(worst, relative_difference(
                                kernel_api(p, kFlatWeave, dirs[i], dirs[i + 1]),
                                kernel_api(p, kFlatWeave, dirs[i], dirs[i + 1], kNormal, flipped)));
  EXPECT_LT(worst, 1.2e-7);  // exact but for a float rounding
}

Vec3 mirrored(const Vec3& w, int axis) {
  Vec3 m = w;
  m[axis] = -m[axis];
  return m;
}

// Worst relative change of the kernel when both directions are mirrored in the plane normal to
// `axis` (0: u, 1: v).
double mirror_change(const Fabric& f, int axis) {
  const std::vector<Vec3> dirs = upper_directions(400, 0.0, 13);
  double worst = 0.0;
  for (size_t i = 0; i + 1 < dirs.size(); i += 2)
    worst =
        std::max(worst, relative_difference(kernel_api(f.params, f.weave, dirs[i], dirs[i + 1]),
                                            kernel_api(f.params, f.weave, mirrored(dirs[i], axis),
                                                       mirrored(dirs[i + 1], axis))));
  return worst;
}

// Mirroring in the plane normal to x_j maps thread j's offset tau to -tau with its fibre turned
// around, and mirrors the other thread's fibres across their b planes (phi -> -phi): the kernel
// is unchanged when T_j is symmetric.
TEST(ClothSymmetry, MirrorsOfSymmetricTangentSets) {
  const std::vector<Fabric> f = fabrics();
  EXPECT_LT(mirror_change(f[0], 0), 1.2e-7) << "linen, plane normal to u";
  EXPECT_LT(mirror_change(f[0], 1), 1.2e-7) << "linen, plane normal to v";
  EXPECT_LT(mirror_change(f[1], 0), 1.2e-7) << "satin, plane normal to u";
  EXPECT_LT(mirror_change(f[1], 1), 1.2e-7) << "satin, plane normal to v";
  // Velvet's weft set is symmetric, its warp set {-90, -50} is not.
  EXPECT_LT(mirror_change(f[2], 1), 1.2e-7) << "velvet, plane normal to v";
  EXPECT_GT(mirror_change(f[2], 0), 0.1) << "velvet, plane normal to u";
}

// A rigid rotation of the frame and both directions changes nothing, and the warp is made
// orthogonal to the normal first.
TEST(ClothKernel, FrameIsRotationInvariantAndOrthogonalises) {
  const Fabric f = fabrics()[1];
  const double a = 0.7, b = -1.1;  // R = Rz(a) Rx(b)
  auto rotate = [&](const Vec3& v) {
    const Vec3 x{v[0], std::cos(b) * v[1] - std::sin(b) * v[2],
                 std::sin(b) * v[1] + std::cos(b) * v[2]};
    return Vec3{std::cos(a) * x[0] - std::sin(a) * x[1], std::sin(a) * x[0] + std::cos(a) * x[1],
                x[2]};
  };
  const auto n = to_float(rotate({0, 0, 1}));
  const auto u = to_float(rotate({1, 0, 0.4}));  // leans towards the normal
  const std::vector<Vec3> dirs = upper_directions(200, 0.05, 17);
  double worst = 0.0;
  for (size_t i = 0; i + 1 < dirs.size(); i += 2)
    worst =
        std::max(worst, relative_difference(kernel_api(f.params, f.weave, dirs[i], dirs[i + 1]),
                                            kernel_api(f.params, f.weave, rotate(dirs[i]),
                                                       rotate(dirs[i + 1]), n.data(), u.data())));
  // The rotated float vectors are off by a float rounding, which the satin's 2.5-degree lobe
  // amplifies.
  EXPECT_LT(worst, 1e-6);
}

TEST(ClothWeights, EachThreadAveragesItsTangents) {
  const std::vector<Vec3> dirs = upper_directions(600, 0.0, 19);
  for (const Fabric& f : fabrics())
    for (uint32_t j = 0; j < 2; ++j)
      for (size_t i = 0; i + 1 < dirs.size(); i += 2) {
        const std::vector<double> w = weights_api(f.weave, j, dirs[i], dirs[i + 1]);
        const auto want = thread_weights(f.weave, int(j), dirs[i], dirs[i + 1]);
        double sum = 0.0;
        for (uint32_t k = 0; k < f.weave.tangent_count[j]; ++k) {
          EXPECT_GE(w[k], 0.0);
          EXPECT_NEAR(w[k], want[k], 1.5e-7) << f.name << " thread " << j;
          sum += f.weave.multiplicity[j][k] * w[k];
        }
        EXPECT_LE(sum, 1.0 + 5e-7) << f.name;  // float roundings of up to 8 weights
      }
}

// With one tangent W = M P / P = M wherever P > 0.
TEST(ClothWeights, OneTangentGivesM) {
  const prt_cloth_weave w = satin_weave();  // the weft has the single offset 0
  const std::vector<Vec3> dirs = upper_directions(2000, 0.0, 23);
  int checked = 0;
  for (size_t i = 0; i + 1 < dirs.size(); i += 2) {
    const Angles in = thread_angles(1, 0.0, dirs[i]), out = thread_angles(1, 0.0, dirs[i + 1]);
    if (!(shadowing(in.psi, out.psi) > 0.0)) continue;
    EXPECT_NEAR(weights_api(w, 1, dirs[i], dirs[i + 1])[0], shadowing(in.phi, out.phi), 1.5e-7);
    ++checked;
  }
  EXPECT_GT(checked, 200);
}

// The kernel is the sum over threads of a_j times the multiplicity, f_s cos(theta_i) and W of
// each offset, with W as prt_cloth_thread_weights gives it.
TEST(ClothWeights, ConsistentWithTheKernel) {
  const std::vector<Vec3> dirs = upper_directions(200, 0.05, 29);
  for (const Fabric& f : fabrics()) {
    double worst = 0.0;
    for (size_t i = 0; i + 1 < dirs.size(); i += 2) {
      Rgb sum{0, 0, 0};
      for (int j = 0; j < 2; ++j) {
        const std::vector<double> w = weights_api(f.weave, uint32_t(j), dirs[i], dirs[i + 1]);
        for (uint32_t k = 0; k < f.weave.tangent_count[j]; ++k) {
          const double tau = f.weave.offsets[j][k];
          const Rgb fs = fibre_fs_cos(f.params.threads[j], thread_angles(j, tau, dirs[i]),
                                      thread_angles(j, tau, dirs[i + 1]));
          for (int c = 0; c < 3; ++c)
            sum[c] += f.params.threads[j].coverage * f.weave.multiplicity[j][k] * fs[c] * w[k];
        }
      }
      worst = std::max(
          worst, relative_difference(kernel_api(f.params, f.weave, dirs[i], dirs[i + 1]), sum));
    }
    EXPECT_LT(worst, 2e-7) << f.name;
  }
}

TEST(ClothKernel, ZeroBelowTheSurface) {
  const Fabric f = fabrics()[0];
  const Vec3 above = as_sent({0.3, 0.2, 0.93});
  for (const Vec3& below :
       {Vec3{0.6, 0.0, -0.8}, Vec3{1.0, 0.0, 0.0}, Vec3{0.0, -1.0, 0.0}, Vec3{0.0, 0.0, -1.0}}) {
    EXPECT_EQ(kernel_api(f.params, f.weave, above, below), (Rgb{0, 0, 0}));
    EXPECT_EQ(kernel_api(f.params, f.weave, below, above), (Rgb{0, 0, 0}));
    for (uint32_t j = 0; j < 2; ++j)
      for (double w : weights_api(f.weave, j, below, above)) EXPECT_EQ(w, 0.0);
  }
  EXPECT_GT(kernel_api(f.params, f.weave, above, above)[0], 0.0);
}

// Directions that stress the model: along and against each fibre tangent, grazing ones, and
// light and view almost along t and -t (where cos theta_d -> 0).
std::vector<Vec3> extreme_directions(const prt_cloth_weave& w) {
  std::vector<Vec3> out = upper_directions(120, 0.0, 31);
  for (double z : {1e-3, 1e-6, 1e-7, 1e-20})
    for (double a = 0.0; a < 2 * kPi; a += kPi / 8) {
      const double r = std::sqrt(1 - z * z);
      out.push_back(as_sent({r * std::cos(a), r * std::sin(a), z}));
    }
  for (int j = 0; j < 2; ++j)
    for (uint32_t k = 0; k < w.tangent_count[j]; ++k)
      for (double s : {1.0, -1.0}) {
        const double tau = w.offsets[j][k];
        const Vec3 t = thread_direction(j, tau, s * kPi / 2, 0.0);
        out.push_back(as_sent(t));
        out.push_back(as_sent(thread_direction(j, tau, s * (kPi / 2 - 1e-6), 0.0)));
      }
  out.push_back({0, 0, 1});
  return out;
}

TEST(ClothKernel, FiniteAndNonNegativeAtTheExtremes) {
  std::vector<Fabric> cases = fabrics();
  const Fabric flat{"flat", linen_params(), kFlatWeave};
  const Fabric upright{"upright", linen_params(), weave_of({{-90, 3}, {90, 1}}, {{90, 2}})};
  for (const Fabric& base : {flat, upright, fabrics()[1], fabrics()[2]}) {
    Fabric f = base;
    for (auto& t : f.params.threads) t.gamma_s = t.gamma_v = 1e-4f;
    cases.push_back(f);
    f = base;
    for (auto& t : f.params.threads) t.eta = 1.0f, t.kd = 0.0f;
    cases.push_back(f);
    f = base;
    for (auto& t : f.params.threads) t.eta = 4.0f, t.kd = 1.0f, t.albedo[0] = 1.0f;
    cases.push_back(f);
  }
  for (const Fabric& f : cases) {
    const std::vector<Vec3> dirs = extreme_directions(f.weave);
    for (const Vec3& wi : dirs)
      for (const Vec3& wo : dirs) {
        const Rgb k = kernel_api(f.params, f.weave, wi, wo);
        for (double v : k) ASSERT_TRUE(std::isfinite(v) && v >= 0.0) << f.name;
        for (uint32_t j = 0; j < 2; ++j)
          for (double w : weights_api(f.weave, j, wi, wo))
            ASSERT_TRUE(w >= 0.0 && w <= 1.0) << f.name;
      }
  }
}

}  // namespace
