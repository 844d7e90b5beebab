// SPDX-License-Identifier: MIT
// Environment maps: every mapping's geometry is checked against analytic facts (total solid
// angle 4π, where the front/right/up/back directions land, seams of the cross), the two
// Debevec files of the same scene against each other (probe vs cross), and the probe against
// the published SH9 numbers of Ramamoorthi & Hanrahan 2001.
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "prt/io/envmap.hpp"
#include "support/published_sh9.hpp"
#include "support/test_files.hpp"

namespace prt::io {
namespace {

using prt_test::shared_asset;
using prt_test::TempDir;

constexpr double kPi = 3.14159265358979323846;

EnvMap random_map(int width, int height, EnvMapping mapping, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(0.0f, 4.0f);
  std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3);
  for (float& v : rgb) v = value(rng);
  return EnvMap(width, height, std::move(rgb), mapping, "random");
}

double total_solid_angle(const EnvMap& map) {
  double sum = 0.0;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      float w = 0.0f;
      if (map.texel(x, y, nullptr, &w)) sum += w;
    }
  }
  return sum;
}

// How far total_solid_angle may be from 4 pi (SPEC §12): the lat-long and cross solid angles are
// exact, so their float rounding; the probe's are the Jacobian at each texel centre, a midpoint
// rule whose error falls as 1/W^2 (the Jacobian vanishes at the rim, so the rim texels taken
// whole or not at all cost little more).
double solid_angle_tolerance(const EnvMap& map) {
  const double w = map.width();
  return 4.0 * kPi * (map.mapping() == EnvMapping::AngularProbe ? 0.2 / (w * w) : 1e-6);
}

glm::vec3 texel_dir(const EnvMap& map, int x, int y) {
  glm::vec3 d(0.0f);
  EXPECT_TRUE(map.texel(x, y, &d, nullptr)) << x << "," << y;
  return d;
}

void expect_near_dir(const glm::vec3& got, const glm::vec3& want, float tol) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

TEST(EnvMap, ParsesMappingNames) {
  EXPECT_EQ(parse_env_mapping("latlong"), EnvMapping::LatLong);
  EXPECT_EQ(parse_env_mapping("cross"), EnvMapping::VerticalCross);
  EXPECT_EQ(parse_env_mapping("probe"), EnvMapping::AngularProbe);
  EXPECT_EQ(parse_env_mapping("auto"), EnvMapping::Auto);
  EXPECT_THROW(parse_env_mapping("cubemap"), Error);
}

TEST(EnvMap, DetectsMappingFromShape) {
  EXPECT_EQ(random_map(64, 32, EnvMapping::Auto).mapping(), EnvMapping::LatLong);
  EXPECT_EQ(random_map(48, 64, EnvMapping::Auto).mapping(), EnvMapping::VerticalCross);
  EXPECT_EQ(random_map(40, 40, EnvMapping::Auto).mapping(), EnvMapping::AngularProbe);
  EXPECT_THROW(random_map(30, 7, EnvMapping::Auto), Error);
  // The override wins where the shape allows it, and is refused where it does not.
  EXPECT_EQ(random_map(64, 64, EnvMapping::LatLong).mapping(), EnvMapping::LatLong);
  EXPECT_THROW(random_map(64, 32, EnvMapping::VerticalCross), Error);
  EXPECT_THROW(random_map(64, 32, EnvMapping::AngularProbe), Error);
}

TEST(EnvMap, SolidAnglesSumToFourPi) {
  for (const EnvMap& map :
       {random_map(256, 128, EnvMapping::LatLong), random_map(192, 256, EnvMapping::VerticalCross),
        random_map(256, 256, EnvMapping::AngularProbe),
        random_map(33, 33, EnvMapping::AngularProbe)}) {
    EXPECT_NEAR(total_solid_angle(map), 4.0 * kPi, solid_angle_tolerance(map))
        << env_mapping_name(map.mapping()) << " " << map.width();
  }
}

TEST(EnvMap, CrossPaddingIsNotPartOfTheMap) {
  const EnvMap map = random_map(48, 64, EnvMapping::VerticalCross);
  int inside = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 48; ++x) inside += map.texel(x, y, nullptr, nullptr) ? 1 : 0;
  }
  EXPECT_EQ(inside, 6 * 16 * 16);
  EXPECT_FALSE(map.texel(0, 0, nullptr, nullptr));
  EXPECT_FALSE(map.texel(40, 60, nullptr, nullptr));
}

// Front = -Z at the image centre, right = +X, up = +Y, for every mapping.
TEST(EnvMap, LatLongOrientation) {
  const EnvMap map = random_map(512, 256, EnvMapping::LatLong);
  const float tol = 0.02f;
  expect_near_dir(texel_dir(map, 256, 128), {0, 0, -1}, tol);
  expect_near_dir(texel_dir(map, 384, 128), {1, 0, 0}, tol);  // three quarters across: +X
  expect_near_dir(texel_dir(map, 128, 128), {-1, 0, 0}, tol);
  expect_near_dir(texel_dir(map, 0, 128), {0, 0, 1}, tol);  // the seam is behind
  expect_near_dir(texel_dir(map, 256, 0), {0, 1, 0}, tol);  // top row: up
  expect_near_dir(texel_dir(map, 256, 255), {0, -1, 0}, tol);
}

TEST(EnvMap, CrossOrientation) {
  const int f = 64;
  const EnvMap map = random_map(3 * f, 4 * f, EnvMapping::VerticalCross);
  const float tol = 0.03f;
  auto centre = [&](int col, int row) { return texel_dir(map, col * f + f / 2, row * f + f / 2); };
  expect_near_dir(centre(1, 1), {0, 0, -1}, tol);  // front
  expect_near_dir(centre(2, 1), {1, 0, 0}, tol);   // right
  expect_near_dir(centre(0, 1), {-1, 0, 0}, tol);  // left
  expect_near_dir(centre(1, 0), {0, 1, 0}, tol);   // top
  expect_near_dir(centre(1, 2), {0, -1, 0}, tol);  // bottom
  expect_near_dir(centre(1, 3), {0, 0, 1}, tol);   // back
  // Within the front face: image right is +X and image up is +Y.
  EXPECT_GT(texel_dir(map, f + f - 1, f + f / 2).x, 0.5f);
  EXPECT_GT(texel_dir(map, f + f / 2, f).y, 0.5f);
  // The back face is stored upside down: its top row borders the bottom face (y < 0) and its
  // right column is +X, continuing the unfolded cross downwards.
  EXPECT_LT(texel_dir(map, f + f / 2, 3 * f).y, -0.5f);
  EXPECT_GT(texel_dir(map, 2 * f - 1, 3 * f + f / 2).x, 0.5f);
}

// Texels on both sides of a seam of the unfolded cross (and of the folded edges that are apart
// in the image) look in nearly the same direction.
TEST(EnvMap, CrossSeamsAreContinuous) {
  const int f = 64;
  const EnvMap map = random_map(3 * f, 4 * f, EnvMapping::VerticalCross);
  const float texel_angle = 2.0f / f * 1.5f;
  auto close = [&](int x0, int y0, int x1, int y1) {
    const float angle =
        std::acos(std::min(1.0f, glm::dot(texel_dir(map, x0, y0), texel_dir(map, x1, y1))));
    EXPECT_LT(angle, texel_angle) << "(" << x0 << "," << y0 << ") vs (" << x1 << "," << y1 << ")";
  };
  for (int k = 0; k < f; k += 7) {
    close(f + k, f - 1, f + k, f);          // top | front
    close(f + k, 2 * f - 1, f + k, 2 * f);  // front | bottom
    close(f + k, 3 * f - 1, f + k, 3 * f);  // bottom | back
    close(f - 1, f + k, f, f + k);          // left | front
    close(2 * f - 1, f + k, 2 * f, f + k);  // front | right
    close(f, k, k, f);                      // top's left edge | left's top edge
    close(2 * f - 1, k, 3 * f - 1 - k, f);  // top's right edge | right's top edge
    close(f + k, 0, f + k, 4 * f - 1);      // top's far edge | back's bottom edge
    close(0, f + k, f, 4 * f - 1 - k);      // left's left edge | back's left edge
  }
}

TEST(EnvMap, ProbeOrientation) {
  const EnvMap map = random_map(201, 201, EnvMapping::AngularProbe);
  const float tol = 0.03f;
  expect_near_dir(texel_dir(map, 100, 100), {0, 0, -1}, tol);  // centre: front
  expect_near_dir(texel_dir(map, 150, 100), {1, 0, 0}, tol);   // half way right: +X (θ = π/2)
  expect_near_dir(texel_dir(map, 100, 50), {0, 1, 0}, tol);    // half way up: +Y
  EXPECT_GT(texel_dir(map, 199, 100).z, 0.99f);                // the rim: behind
  EXPECT_FALSE(map.texel(0, 0, nullptr, nullptr));             // corners are outside the disc
}

TEST(EnvMap, DirectionTexelDirectionRoundTrip) {
  std::mt19937 rng(11);
  std::normal_distribution<float> gauss;
  const EnvMap maps[] = {random_map(256, 128, EnvMapping::LatLong),
                         random_map(96, 128, EnvMapping::VerticalCross),
                         random_map(128, 128, EnvMapping::AngularProbe)};
  // Largest centre-to-corner angle of a texel in each mapping (see formats/SPEC.md).
  const float bounds[] = {static_cast<float>(kPi / 128), 2.0f / 32,
                          static_cast<float>(2 * kPi / 128)};
  for (int m = 0; m < 3; ++m) {
    for (int i = 0; i < 2000; ++i) {
      const glm::vec3 d = glm::normalize(glm::vec3(gauss(rng), gauss(rng), gauss(rng)));
      int x = -1, y = -1;
      maps[m].texel_of(d, &x, &y);
      glm::vec3 back;
      ASSERT_TRUE(maps[m].texel(x, y, &back, nullptr)) << env_mapping_name(maps[m].mapping());
      EXPECT_LT(std::acos(std::min(1.0f, glm::dot(d, back))), bounds[m])
          << env_mapping_name(maps[m].mapping()) << " dir " << d.x << "," << d.y << "," << d.z;
    }
  }
}

// At a texel centre, bilinear interpolation returns the texel itself.
TEST(EnvMap, RadianceAtTexelCentreIsTheTexel) {
  for (const EnvMap& map :
       {random_map(64, 32, EnvMapping::LatLong), random_map(48, 64, EnvMapping::VerticalCross),
        random_map(64, 64, EnvMapping::AngularProbe)}) {
    for (int y = 0; y < map.height(); y += 3) {
      for (int x = 0; x < map.width(); x += 3) {
        glm::vec3 d;
        if (!map.texel(x, y, &d, nullptr)) continue;
        const glm::vec3 want = map.texel_value(x, y), got = map.radiance(d);
        // The direction -> texel round trip is exact but for float rounding, a few millionths
        // of a texel, times neighbour differences of up to 4.
        EXPECT_NEAR(got.r, want.r, 2e-4f) << env_mapping_name(map.mapping()) << x << "," << y;
        EXPECT_NEAR(got.b, want.b, 2e-4f);
      }
    }
  }
}

TEST(EnvMap, ConstantMapIsConstantEverywhere) {
  const glm::vec3 value(0.25f, 1.0f, 3.5f);
  const EnvMap map = constant_envmap(value);
  std::mt19937 rng(3);
  std::normal_distribution<float> gauss;
  for (int i = 0; i < 500; ++i) {
    const glm::vec3 got =
        map.radiance(glm::normalize(glm::vec3(gauss(rng), gauss(rng), gauss(rng))));
    EXPECT_FLOAT_EQ(got.r, value.r);
    EXPECT_FLOAT_EQ(got.g, value.g);
    EXPECT_FLOAT_EQ(got.b, value.b);
  }
  EXPECT_EQ(map.radiance({0, 1, 0}), value);  // the poles too
  EXPECT_EQ(map.radiance({0, -1, 0}), value);
  EXPECT_NEAR(total_solid_angle(map), 4.0 * kPi, 1e-4);
}

TEST(EnvMap, SanitisesNanInfAndNegativeTexels) {
  std::vector<float> rgb(4 * 2 * 3, 1.0f);
  rgb[0] = std::nanf("");                            // texel 0
  rgb[4] = std::numeric_limits<float>::infinity();   // texel 1
  rgb[8] = -std::numeric_limits<float>::infinity();  // texel 2
  rgb[9] = -0.5f;                                    // texel 3
  rgb[10] = std::nanf("");                           // texel 3 again: counted once
  const EnvMap map(4, 2, rgb, EnvMapping::LatLong, "bad texels");
  EXPECT_EQ(map.sanitized_texels(), 4u);
  for (float v : map.pixels()) {
    EXPECT_TRUE(std::isfinite(v));
    EXPECT_GE(v, 0.0f);
  }
  EXPECT_EQ(map.texel_value(0, 0), glm::vec3(0.0f, 1.0f, 1.0f));
  EXPECT_EQ(map.texel_value(3, 0), glm::vec3(0.0f, 0.0f, 1.0f));
  EXPECT_EQ(map.texel_value(1, 1), glm::vec3(1.0f));
  std::vector<float> clean(12, 2.0f);
  EXPECT_EQ(sanitize_radiance(clean), 0u);
}

TEST(EnvMap, LoadsAWrittenHdrFile) {
  const TempDir dir("envmap_load");
  const std::string path = dir.file("small.hdr");
  std::vector<float> rgb(8 * 4 * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.5f + 0.25f * static_cast<float>(i % 7);
  ASSERT_NE(stbi_write_hdr(path.c_str(), 8, 4, 3, rgb.data()), 0);
  std::vector<std::string> warnings;
  const MessageHook messages = [&](MessageLevel level, const std::string& text) {
    if (level == MessageLevel::Warning) warnings.push_back(text);
  };
  const EnvMap map = load_envmap(path, EnvMapping::Auto, messages);
  EXPECT_EQ(map.mapping(), EnvMapping::LatLong);
  ASSERT_EQ(map.pixels().size(), rgb.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    EXPECT_NEAR(map.pixels()[i], rgb[i], rgb[i] / 128.0f);  // RGBE: 8-bit shared-exponent mantissa
  }
  EXPECT_TRUE(warnings.empty());
}

// RGBE's largest exponent, 255, decodes to 2^119 .. 2^127 per channel (m * 2^(e - 136)): finite
// and accepted, but said in one warning with the count and the largest value. Flat encoding
// (under 8 wide), bytes written by hand.
TEST(EnvMap, WarnsAboutTexelsAtTheLargestRgbeExponent) {
  const TempDir dir("envmap_top_exponent");
  const unsigned char texels[8][4] = {
      {128, 128, 128, 129},  // 1.0
      {128, 64, 32, 255},    // 2^126, 2^125, 2^124: counted
      {255, 0, 0, 255},      // 255 * 2^119, the largest: counted
      {255, 255, 255, 254},  // 255 * 2^118, just below 2^126 but exponent 254: not counted
      {1, 0, 0, 255},        // 2^119, exponent 255 with a small mantissa: counted
      {64, 64, 64, 130},     // 1.0
      {64, 64, 64, 130},    {64, 64, 64, 130}};
  std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n";
  bytes.append(reinterpret_cast<const char*>(texels), sizeof texels);
  const std::string path = dir.write("top_exponent.hdr", bytes);
  std::vector<std::string> warnings;
  const EnvMap map =
      load_envmap(path, EnvMapping::LatLong, [&](MessageLevel level, const std::string& text) {
        if (level == MessageLevel::Warning) warnings.push_back(text);
      });
  EXPECT_EQ(map.texel_value(2, 0).r, std::ldexp(255.0f, 119));
  EXPECT_EQ(map.texel_value(0, 0), glm::vec3(1.0f));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find(path + ": 3 texels have the largest RGBE exponent (255), values up "
                                    "to 1.69e+38"),
            std::string::npos)
      << warnings[0];

  // Run-length encoded (8 wide, as stb writes it): five texels of ~1.5e38 (exponent 255).
  std::vector<float> rgb(8 * 4 * 3, 0.5f);
  for (int i = 9; i < 14; ++i) rgb[3 * i] = 1.5e38f;
  const std::string rle = dir.file("top_exponent_rle.hdr");
  ASSERT_NE(stbi_write_hdr(rle.c_str(), 8, 4, 3, rgb.data()), 0);
  warnings.clear();
  load_envmap(rle, EnvMapping::Auto, [&](MessageLevel level, const std::string& text) {
    if (level == MessageLevel::Warning) warnings.push_back(text);
  });
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find(": 5 texels have the largest RGBE exponent"), std::string::npos)
      << warnings[0];
}

// ---- the two Debevec files of the Eucalyptus Grove --------------------------------------------

using Sh9 = std::array<glm::dvec3, 9>;

// Projects in the table's frame, which is (x, y, -z) of ours (its probe looks along +z).
Sh9 project_sh9(const EnvMap& map) {
  Sh9 sh{};
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      glm::vec3 d;
      float w = 0.0f;
      if (!map.texel(x, y, &d, &w)) continue;
      const auto basis = prt_test::published_sh9_basis_world(d.x, d.y, d.z);
      const glm::dvec3 radiance(map.texel_value(x, y));
      for (int k = 0; k < 9; ++k) sh[k] += radiance * (basis[k] * w);
    }
  }
  return sh;
}

double largest(const Sh9& sh) {
  double m = 0.0;
  for (const auto& c : sh) m = std::max({m, std::abs(c.x), std::abs(c.y), std::abs(c.z)});
  return m;
}

TEST(EnvMapAssets, ProbeAndCrossOfTheSameSceneAgree) {
  const std::string probe_path = shared_asset("envmaps/rnl_probe.hdr");
  const std::string cross_path = shared_asset("envmaps/rnl_cross.hdr");
  if (probe_path.empty() || cross_path.empty()) GTEST_SKIP() << "shared assets not found";
  const Sh9 probe = project_sh9(load_envmap(probe_path, EnvMapping::Auto));
  const Sh9 cross = project_sh9(load_envmap(cross_path, EnvMapping::Auto));
  const glm::dvec3 exposure = probe[0] / cross[0];  // the files may differ in exposure
  // Two resamplings of one scene agree to a few times 1e-5 of the largest coefficient; turning
  // either mapping by half a texel moves them apart by over ten times that.
  const double tol = 1e-4 * largest(probe);
  for (int k = 0; k < 9; ++k) {
    const glm::dvec3 scaled = cross[k] * exposure;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(scaled[c], probe[k][c], tol) << "coefficient " << k << " channel " << c;
    }
  }
}

TEST(EnvMapAssets, ProbeReproducesPublishedEucalyptusGroveSh9) {
  const std::string probe_path = shared_asset("envmaps/rnl_probe.hdr");
  const std::string table_path = shared_asset("tables/sh9_irradiance_envmaps.json");
  if (probe_path.empty() || table_path.empty()) GTEST_SKIP() << "shared assets not found";
  const auto table = nlohmann::json::parse(std::ifstream(table_path));
  const auto& published = table["environments"]["eucalyptus_grove"]["coefficients"];
  const char* names[9] = {"L00", "L1m1", "L10", "L11", "L2m2", "L2m1", "L20", "L21", "L22"};
  const Sh9 sh = project_sh9(load_envmap(probe_path, EnvMapping::Auto));
  // The table holds 1/10 of the raw projection (its "scale" note).
  Sh9 want{};
  for (int k = 0; k < 9; ++k) {
    for (int c = 0; c < 3; ++c) want[k][c] = 10.0 * published[names[k]]["rgb"][c].get<double>();
  }
  const double tol = 0.01 * largest(want);
  for (int k = 0; k < 9; ++k) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(sh[k][c], want[k][c], tol) << names[k] << " channel " << c;
    }
  }
}

TEST(EnvMapAssets, EveryShippedMapLoadsWithTheRightMapping) {
  struct Case {
    const char* file;
    EnvMapping mapping;
    int width, height;
  };
  const Case cases[] = {{"envmaps/grace_cross.hdr", EnvMapping::VerticalCross, 768, 1024},
                        {"envmaps/rnl_cross.hdr", EnvMapping::VerticalCross, 768, 1024},
                        {"envmaps/rnl_probe.hdr", EnvMapping::AngularProbe, 900, 900},
                        {"envmaps/spiaggia_di_mondello_1k.hdr", EnvMapping::LatLong, 1024, 512}};
  for (const Case& c : cases) {
    const std::string path = shared_asset(c.file);
    if (path.empty()) GTEST_SKIP() << "shared assets not found";
    const EnvMap map = load_envmap(path, EnvMapping::Auto);
    EXPECT_EQ(map.mapping(), c.mapping) << c.file;
    EXPECT_EQ(map.width(), c.width);
    EXPECT_EQ(map.height(), c.height);
    EXPECT_EQ(map.sanitized_texels(), 0u);
    EXPECT_NEAR(total_solid_angle(map), 4.0 * kPi, solid_angle_tolerance(map)) << c.file;
  }
}

// The sun of the Mondello map: MANIFEST says it holds half the luminous power in 7.5e-4 sr.
TEST(EnvMapAssets, MondelloSunHoldsHalfThePower) {
  const std::string path = shared_asset("envmaps/spiaggia_di_mondello_1k.hdr");
  if (path.empty()) GTEST_SKIP() << "shared assets not found";
  const EnvMap map = load_envmap(path, EnvMapping::Auto);
  std::vector<std::pair<double, double>> texels;  // (luminance, solid angle)
  double total = 0.0;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      float w = 0.0f;
      map.texel(x, y, nullptr, &w);
      const glm::vec3 v = map.texel_value(x, y);
      const double lum = 0.2126 * v.r + 0.7152 * v.g + 0.0722 * v.b;
      texels.emplace_back(lum, w);
      total += lum * w;
    }
  }
  std::sort(texels.begin(), texels.end(), std::greater<>());
  double power = 0.0, area = 0.0;
  for (const auto& [lum, w] : texels) {
    if (power >= 0.5 * total) break;
    power += lum * w;
    area += w;
  }
  EXPECT_NEAR(area, 7.5e-4, 0.05e-4);  // MANIFEST's figure, to its two digits
}

}  // namespace
}  // namespace prt::io
