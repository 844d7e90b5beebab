// SPDX-License-Identifier: MIT
// A sun 1e5 times as bright as a uniform sky (one texel of a lat-long map, carrying several
// times the whole sky's power): the runtime's fit of the light keeps the sun's power and the map's,
// and the shading under the fitted lobes agrees with the reference under the map itself.
#include <gtest/gtest.h>

#include "cloth/extremes/cloth_extremes.hpp"
#include "cloth/light/sg_maps.hpp"

namespace {

using namespace prt_test;

constexpr std::uint32_t kWidth = 256, kHeight = 128;
constexpr float kSky = 1.0f, kSun = 1e5f;

struct SunMap {
  EnvImage env = latlong_image(kWidth, kHeight);
  std::size_t sun = 0;     // the sun's texel
  Vec3 sun_direction{};    // its centre
  double sun_power = 0.0;  // radiance x solid angle, one channel
};

// The sun's texel is the one whose centre is nearest a direction 35 degrees above the cloth.
SunMap sun_map() {
  SunMap m;
  const Vec3d want = from_angles(degrees(35), degrees(30));
  double best = -2.0;
  for_each_texel(m.env, [&](std::size_t k, const Vec3& d, double solid_angle) {
    for (int c = 0; c < 3; ++c) m.env.rgb[3 * k + c] = kSky;
    const double cosine = d[0] * want[0] + d[1] * want[1] + d[2] * want[2];
    if (cosine > best) {
      best = cosine;
      m.sun = k;
      m.sun_direction = d;
      m.sun_power = kSun * solid_angle;
    }
  });
  for (int c = 0; c < 3; ++c) m.env.rgb[3 * m.sun + c] = kSun;
  return m;
}

// Every texel of the map as the reference takes it.
Texels map_texels(const EnvImage& env) {
  Texels t;
  for_each_texel(env, [&](std::size_t k, const Vec3& d, double solid_angle) {
    t.add({d[0], d[1], d[2]}, {env.rgb[3 * k] * solid_angle, env.rgb[3 * k + 1] * solid_angle,
                               env.rgb[3 * k + 2] * solid_angle});
  });
  return t;
}

struct FittedLight {
  std::vector<prt_cloth_lobe> lobes;
  prt_cloth_fit_report report = prt::sized<prt_cloth_fit_report>();
};

FittedLight fit_light(const EnvImage& env) {
  FittedLight f;
  f.lobes.resize(10);
  prt_cloth_fit_desc desc = prt::sized<prt_cloth_fit_desc>();
  const prt_env_image image = env.image();
  EXPECT_EQ(
      prt_cloth_fit_light(baked_cloth().context.ctx, &image, &desc, f.lobes.data(), &f.report),
      PRT_OK);
  return f;
}

TEST(ClothExtremes, TheFitKeepsTheSunsPowerAndTheMaps) {
  const SunMap m = sun_map();
  const FittedLight f = fit_light(m.env);
  // The map's power, summed here, is the lobes'.
  const double power = map_power(m.env), lobes = power_of(f.lobes);
  EXPECT_LE(std::fabs(lobes - power) / power, kPowerTolerance);
  // The lobes within a degree of the sun carry its power, and perhaps the sky's in its texel
  // (kSky / kSun of it).
  double near_sun = 0.0;
  for (const prt_cloth_lobe& l : f.lobes)
    if (degrees_between(axis_of(l), m.sun_direction) < 1.0)
      near_sun += (double(l.rgb[0]) + l.rgb[1] + l.rgb[2]) * sg_integral(l.sharpness);
  EXPECT_NEAR(near_sun / (3.0 * m.sun_power), 1.0, kSky / kSun + kPowerTolerance);
}

TEST(ClothExtremes, UnderTheSunTheShadingMatchesTheReference) {
  const SunMap m = sun_map();
  const FittedLight f = fit_light(m.env);
  const Patch patch(spread_views());
  const Texels texels = map_texels(m.env);
  for (const std::uint32_t fabric : {BakedCloth::kLinen, BakedCloth::kSatin}) {
    const std::vector<float> shaded = shade(fabric, nullptr, f.lobes, patch);
    ASSERT_TRUE(all_finite_non_negative(shaded));
    const prt_cloth_params& params = baked_cloth().presets[fabric].params;
    // Against the fitted lobes themselves: the method alone.
    Texels lobes;
    for (const prt_cloth_lobe& l : f.lobes)
      if (l.rgb[0] + l.rgb[1] + l.rgb[2] > 0.0f)
        lobes.append(hemisphere_texels(l, reference_step()));
    const double method = relative_rms(shaded, reference(fabric, params, lobes, patch));
    // Against the map: the method and the fit.
    const double map = relative_rms(shaded, reference(fabric, params, texels, patch));
    EXPECT_LE(method, kSlack * moderate_error(fabric));
    EXPECT_LE(map, kSlack * moderate_error(fabric));
  }
}

}  // namespace
