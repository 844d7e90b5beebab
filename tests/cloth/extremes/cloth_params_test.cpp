// SPDX-License-Identifier: MIT
// The live parameters at the ends of their ranges: eta -> 1 (no interface: the surface term
// vanishes and only the volume term is left), k_d 0 and 1, and very small gamma_s and gamma_v
// (the lobes in theta_h tend to a delta on the specular cone).
#include <gtest/gtest.h>

#include "cloth/extremes/cloth_extremes.hpp"

namespace {

using namespace prt_test;

const std::vector<std::uint32_t> kFabrics = {BakedCloth::kLinen, BakedCloth::kSatin};

// The fabric's parameters with `field` set to `value` in both threads.
prt_cloth_params with(std::uint32_t fabric, float prt_cloth_thread::*field, float value) {
  prt_cloth_params p = baked_cloth().presets[fabric].params;
  for (prt_cloth_thread& t : p.threads) t.*field = value;
  return p;
}

prt_cloth_params with(prt_cloth_params p, float prt_cloth_thread::*field, float value) {
  for (prt_cloth_thread& t : p.threads) t.*field = value;
  return p;
}

prt_cloth_params without_albedo(prt_cloth_params p) {
  for (prt_cloth_thread& t : p.threads) t.albedo[0] = t.albedo[1] = t.albedo[2] = 0.0f;
  return p;
}

bool all_zero(const std::vector<float>& v) {
  return std::all_of(v.begin(), v.end(), [](float x) { return x == 0.0f; });
}

std::vector<float> difference(const std::vector<float>& a, const std::vector<float>& b) {
  std::vector<float> d(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) d[i] = a[i] - b[i];
  return d;
}

// F_r(1, c) = 0 and F = 1: without albedo nothing is left (the reference agrees); with it, what
// is left does not depend on gamma_s at all, is continuous as eta -> 1, and matches the
// reference.
TEST(ClothExtremes, EtaOneLeavesTheVolumeTermOnly) {
  const Patch patch(spread_views());
  const prt_cloth_lobe lobe = make_lobe(high_axis(), 10.0);
  const Texels texels = hemisphere_texels(lobe, reference_step());
  for (const std::uint32_t fabric : kFabrics) {
    const prt_cloth_params one = with(fabric, &prt_cloth_thread::eta, 1.0f);
    const std::vector<float> shaded = shade(fabric, &one, {lobe}, patch);
    ASSERT_TRUE(all_finite_non_negative(shaded));
    const prt_cloth_params dark = without_albedo(one);
    EXPECT_TRUE(all_zero(shade(fabric, &dark, {lobe}, patch)));
    EXPECT_TRUE(all_zero(reference(fabric, dark, texels, patch)));
    // The surface term is there at the fabric's own eta.
    const prt_cloth_params own_dark = without_albedo(baked_cloth().presets[fabric].params);
    EXPECT_FALSE(all_zero(shade(fabric, &own_dark, {lobe}, patch)));
    for (const float gamma_s : {1e-4f, 0.1f, 3.0f}) {
      const prt_cloth_params other = with(one, &prt_cloth_thread::gamma_s, gamma_s);
      EXPECT_EQ(shade(fabric, &other, {lobe}, patch), shaded) << "gamma_s " << gamma_s;
    }
    // eta just above 1 (the next float up, and 1e-3 up) shades as eta = 1 does, up to the
    // surface term's F_r, which is of order (eta - 1)^2 except at grazing incidence on the fibre.
    for (const float eta : {std::nextafter(1.0f, 2.0f), 1.001f}) {
      const prt_cloth_params near = with(fabric, &prt_cloth_thread::eta, eta);
      EXPECT_LE(relative_rms(shade(fabric, &near, {lobe}, patch), shaded), kEtaContinuity)
          << "eta " << eta;
    }
    EXPECT_LE(relative_rms(shaded, reference(fabric, one, texels, patch)),
              kSlack * moderate_error(fabric));
  }
}

// k_d = 1 makes the volume term isotropic: gamma_v no longer matters. The change from k_d 0 to
// 1 is the reference's change, as closely as a value (a difference of two shadings, so twice
// the slack).
TEST(ClothExtremes, KdZeroAndOne) {
  const Patch patch(spread_views());
  const prt_cloth_lobe lobe = make_lobe(high_axis(), 10.0);
  const Texels texels = hemisphere_texels(lobe, reference_step());
  for (const std::uint32_t fabric : kFabrics) {
    const prt_cloth_params kd0 = with(fabric, &prt_cloth_thread::kd, 0.0f);
    const prt_cloth_params kd1 = with(fabric, &prt_cloth_thread::kd, 1.0f);
    const std::vector<float> s0 = shade(fabric, &kd0, {lobe}, patch);
    const std::vector<float> s1 = shade(fabric, &kd1, {lobe}, patch);
    ASSERT_TRUE(all_finite_non_negative(s0));
    ASSERT_TRUE(all_finite_non_negative(s1));
    for (const float gamma_v : {1e-4f, 0.1f, 3.0f}) {
      const prt_cloth_params other = with(kd1, &prt_cloth_thread::gamma_v, gamma_v);
      EXPECT_EQ(shade(fabric, &other, {lobe}, patch), s1) << "gamma_v " << gamma_v;
    }
    const std::vector<float> r0 = reference(fabric, kd0, texels, patch);
    const std::vector<float> r1 = reference(fabric, kd1, texels, patch);
    const double bar = moderate_error(fabric);
    EXPECT_LE(relative_rms(s0, r0), kSlack * bar);
    EXPECT_LE(relative_rms(s1, r1), kSlack * bar);
    EXPECT_LE(relative_rms(difference(s1, s0), difference(r1, r0)), 2.0 * kSlack * bar);
  }
}

// Views on and near the specular cone of a sharp lobe (the warp's mirror direction and beside
// it), where a narrow surface or volume lobe concentrates.
Patch cone_views() {
  return Patch({from_angles(degrees(40), degrees(210)), from_angles(degrees(50), degrees(200)),
                from_angles(degrees(30), degrees(240)), from_angles(degrees(60), degrees(90))});
}

// Down to a quarter of a degree, against a reference fine enough to resolve it (texels a third
// of gamma wide, under a lobe a couple of degrees wide so that stays affordable).
TEST(ClothExtremes, SmallGammaMatchesTheReference) {
  const Patch patch = cone_views();
  const prt_cloth_lobe lobe = make_lobe(high_axis(), 1e3);
  for (const std::uint32_t fabric : kFabrics)
    for (float prt_cloth_thread::*field : {&prt_cloth_thread::gamma_s, &prt_cloth_thread::gamma_v})
      for (const double gamma : {degrees(2), degrees(0.25)}) {
        const prt_cloth_params p = with(fabric, field, float(gamma));
        const std::vector<float> shaded = shade(fabric, &p, {lobe}, patch);
        ASSERT_TRUE(all_finite_non_negative(shaded));
        const std::vector<float> truth =
            reference(fabric, p, hemisphere_texels(lobe, gamma / 3.0), patch);
        EXPECT_LE(relative_rms(shaded, truth), kSlack * moderate_error(fabric))
            << baked_cloth().presets[fabric].name << ", gamma " << gamma;
      }
}

// Below that, down to 1e-6 rad: finite, non-negative, converged (the last two agree to a few
// float roundings), and the limit is the trend of the reference at a quarter of a degree.
TEST(ClothExtremes, VerySmallGammaConvergesToTheReferencesTrend) {
  const Patch patch = cone_views();
  for (const double lambda : {10.0, 1e3}) {
    const prt_cloth_lobe lobe = make_lobe(high_axis(), lambda);
    for (const std::uint32_t fabric : kFabrics)
      for (float prt_cloth_thread::*field :
           {&prt_cloth_thread::gamma_s, &prt_cloth_thread::gamma_v}) {
        std::vector<std::vector<float>> shaded;
        for (const double gamma : {1e-3, 1e-4, 1e-5, 1e-6}) {
          const prt_cloth_params p = with(fabric, field, float(gamma));
          shaded.push_back(shade(fabric, &p, {lobe}, patch));
          ASSERT_TRUE(all_finite_non_negative(shaded.back())) << "gamma " << gamma;
        }
        EXPECT_LE(relative_rms(shaded[2], shaded[3]), 1e-6);
        if (lambda < 100.0) continue;  // the reference at a quarter degree: under the sharp lobe
        const prt_cloth_params quarter = with(fabric, field, float(degrees(0.25)));
        const std::vector<float> truth =
            reference(fabric, quarter, hemisphere_texels(lobe, degrees(0.25) / 3.0), patch);
        EXPECT_LE(relative_rms(shaded[3], truth), kSlack * moderate_error(fabric))
            << baked_cloth().presets[fabric].name;
      }
  }
}

}  // namespace
