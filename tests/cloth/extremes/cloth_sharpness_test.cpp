// SPDX-License-Identifier: MIT
// The light's sharpness over its whole range, lambda = 2 / sigma^2 from PRT_CLOTH_MIN_SHARPNESS
// to PRT_CLOTH_MAX_SHARPNESS: the shading stays as close to the exact model's reference as it is
// at moderate sharpness, for a lobe high in the sky and for one near the horizon.
#include <gtest/gtest.h>

#include "cloth/extremes/cloth_extremes.hpp"

namespace {

using namespace prt_test;

void expect_ends_of_the_range_as_close_as_moderate(std::uint32_t fabric, const Vec3d& axis) {
  const double bar = moderate_error(fabric, axis);
  for (const double lambda :
       {double(PRT_CLOTH_MIN_SHARPNESS), 1.0, 1e3, double(PRT_CLOTH_MAX_SHARPNESS)}) {
    const Patch patch(spread_views());
    const prt_cloth_lobe lobe = make_lobe(axis, lambda);
    const std::vector<float> shaded = shade(fabric, nullptr, {lobe}, patch);
    EXPECT_TRUE(all_finite_non_negative(shaded)) << "lambda " << lambda;
    const std::vector<float> truth = reference(fabric, baked_cloth().presets[fabric].params,
                                               hemisphere_texels(lobe, reference_step()), patch);
    EXPECT_LE(relative_rms(shaded, truth), kSlack * bar)
        << baked_cloth().presets[fabric].name << ", lambda " << lambda;
  }
}

TEST(ClothExtremes, SharpnessOverItsRangeHighInTheSky) {
  for (const std::uint32_t fabric : {BakedCloth::kLinen, BakedCloth::kSatin})
    expect_ends_of_the_range_as_close_as_moderate(fabric, high_axis());
}

TEST(ClothExtremes, SharpnessOverItsRangeNearTheHorizon) {
  for (const std::uint32_t fabric : {BakedCloth::kLinen, BakedCloth::kSatin})
    expect_ends_of_the_range_as_close_as_moderate(fabric, from_angles(degrees(8), degrees(-60)));
}

// The bar itself: what the small grid's tables allow at moderate sharpness, so that a bar that
// grew with a broken method would not let the extremes pass with it.
TEST(ClothExtremes, TheModerateErrorIsTheSmallGridsError) {
  EXPECT_LE(moderate_error(BakedCloth::kLinen), kModerateErrorBound[BakedCloth::kLinen]);
  EXPECT_LE(moderate_error(BakedCloth::kSatin), kModerateErrorBound[BakedCloth::kSatin]);
}

}  // namespace
