// SPDX-License-Identifier: MIT
// A lobe below the horizon: wholly below (to within its tail) it shades to exactly 0, and kept on
// purpose (PRT_CLOTH_KEEP_HIDDEN_LOBES) it gives no more than its tail can; half below, the
// clipped lobe shades as close to the reference as a lobe in the open sky.
#include <gtest/gtest.h>

#include <cmath>

#include "cloth/extremes/cloth_extremes.hpp"

namespace {

using namespace prt_test;

const std::vector<std::uint32_t> kFabrics = {BakedCloth::kLinen, BakedCloth::kSatin};

// The largest value over the upper hemisphere of a unit lobe of sharpness lambda whose axis is
// `depth` radians below the horizon: at the horizon's nearest point, exp(lambda (cos depth - 1)).
double tail(double lambda, double depth) {
  return std::exp(lambda * (std::cos(depth) - 1.0));
}

// Lobes whose tail over the hemisphere is below 1e-4 of their peak (the shading's culling
// threshold, docs/cloth/method.md), from wide to sharp.
struct HiddenLobe {
  double lambda, depth_degrees;
};
const std::vector<HiddenLobe> kHidden = {{10.0, 90.0}, {100.0, 30.0}, {1e3, 10.0}, {1e4, 3.0}};

TEST(ClothExtremes, ALobeWhollyBelowTheHorizonShadesToZero) {
  const Patch patch(spread_views());
  for (const HiddenLobe& h : kHidden) {
    ASSERT_LT(tail(h.lambda, degrees(h.depth_degrees)), 1e-4);
    for (const double azimuth : {0.0, 45.0, 160.0}) {
      const prt_cloth_lobe lobe =
          make_lobe(from_angles(-degrees(h.depth_degrees), degrees(azimuth)), h.lambda);
      for (const std::uint32_t fabric : kFabrics) {
        const std::vector<float> shaded = shade(fabric, nullptr, {lobe}, patch);
        EXPECT_TRUE(std::all_of(shaded.begin(), shaded.end(), [](float x) { return x == 0.0f; }))
            << "lambda " << h.lambda << ", depth " << h.depth_degrees;
      }
    }
  }
}

// Kept, the lobe adds at most its tail times what a uniform sky of radiance 1 gives (the
// reference's, from texels of a lobe so wide it is 1 everywhere to within 1e-9).
TEST(ClothExtremes, AHiddenLobeKeptGivesNoMoreThanItsTail) {
  const Patch patch(spread_views());
  prt_cloth_settings keep = prt::sized<prt_cloth_settings>();
  keep.flags = PRT_CLOTH_KEEP_HIDDEN_LOBES;
  prt_cloth_lobe uniform = make_lobe({0, 0, 1}, 1e-9);
  for (const std::uint32_t fabric : kFabrics) {
    const std::vector<float> sky = reference(fabric, baked_cloth().presets[fabric].params,
                                             hemisphere_texels(uniform, reference_step()), patch);
    ASSERT_TRUE(all_finite_non_negative(sky));
    for (const HiddenLobe& h : kHidden) {
      const double bound = tail(h.lambda, degrees(h.depth_degrees));
      const prt_cloth_lobe lobe = make_lobe(from_angles(-degrees(h.depth_degrees), 0.3), h.lambda);
      const std::vector<float> shaded = shade(fabric, nullptr, {lobe}, patch, &keep);
      EXPECT_TRUE(all_finite_non_negative(shaded)) << "lambda " << h.lambda;
      for (std::size_t i = 0; i < shaded.size(); ++i)
        EXPECT_LE(shaded[i], bound * sky[i]) << "lambda " << h.lambda << ", sample " << i / 3;
    }
  }
}

// Axis on the horizon and one lobe width below it: the part of the lobe above is light, the
// rest is cut off by the hemisphere (the tables' average and the phi integrals run over the
// cloth's hemisphere only). The bar is a lobe of moderate sharpness just above the horizon on the
// same azimuth, with the slack of a grazing view: a sharp lobe below the horizon lights the cloth
// only at grazing angles.
TEST(ClothExtremes, ALobeHalfBelowTheHorizonMatchesTheReference) {
  const Patch patch(spread_views());
  for (const std::uint32_t fabric : kFabrics) {
    const double bar = moderate_error(fabric, from_angles(degrees(8), degrees(-60)));
    for (const double lambda : {1.0, 10.0, 100.0, 1e4})
      for (const double elevation : {0.0, -1.0 / std::sqrt(lambda)}) {
        const prt_cloth_lobe lobe = make_lobe(from_angles(elevation, degrees(-60)), lambda);
        const std::vector<float> shaded = shade(fabric, nullptr, {lobe}, patch);
        const std::vector<float> truth =
            reference(fabric, baked_cloth().presets[fabric].params,
                      hemisphere_texels(lobe, reference_step()), patch);
        EXPECT_TRUE(all_finite_non_negative(shaded))
            << baked_cloth().presets[fabric].name << ", lambda " << lambda << ", elevation "
            << elevation;
        EXPECT_LE(relative_rms(shaded, truth), kGrazingSlack * bar)
            << baked_cloth().presets[fabric].name << ", lambda " << lambda << ", elevation "
            << elevation;
      }
  }
}

}  // namespace
