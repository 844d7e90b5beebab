// Baker-side SH projection (prt::bake::project_env_sh) and `prt-bake env-sh`: constant maps in
// every mapping, agreement with the runtime's lat-long projection, the published Eucalyptus
// Grove coefficients (Ramamoorthi and Hanrahan 2001) from rnl_probe.hdr.
#include <gtest/gtest.h>
#include <prt/prt_sh.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "prt/baker/sh/env_sh.hpp"
#include "sh/sh_test_util.hpp"
#include "support/command.hpp"
#include "support/published_sh9.hpp"

namespace {

using prt::io::EnvMap;
using prt::io::EnvMapping;
using prt_sh_test::kPi;

const std::array<float, 3> kRadiance = {0.25f, 1.0f, 3.0f};

// A w x h map of constant radiance; cross padding cells get a huge value that must be ignored.
EnvMap ConstantMap(int w, int h, EnvMapping mapping) {
  std::vector<float> rgb(size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int col = mapping == EnvMapping::VerticalCross ? x / (w / 3) : 1;
      const int row = mapping == EnvMapping::VerticalCross ? y / (h / 4) : 1;
      const bool padding = mapping == EnvMapping::VerticalCross && col != 1 && row != 1;
      for (int c = 0; c < 3; ++c) rgb[(size_t(y) * w + x) * 3 + c] = padding ? 1e6f : kRadiance[c];
    }
  return EnvMap(w, h, std::move(rgb), mapping, "constant");
}

// The DC term is sqrt(4 pi) L times the texels' total solid angle over 4 pi (SPEC §12): exact
// but for float rounding in lat-long and cross, a midpoint rule with an error falling as 1/W^2
// in the probe. The higher terms are the quadrature's residue: each texel's harmonics taken at
// its centre, an error of the order of the texel's area times their curvature.
void ExpectConstantProjection(const EnvMap& map) {
  const auto sh = prt::bake::project_env_sh(map, 6);
  const double w = map.width();
  const double dc_tolerance = map.mapping() == EnvMapping::AngularProbe ? 0.2 / (w * w) : 1e-6;
  for (int c = 0; c < 3; ++c) {
    const double dc = std::sqrt(4.0 * kPi) * kRadiance[c];
    EXPECT_NEAR(sh.at(0, c), dc, dc_tolerance * dc) << prt::io::env_mapping_name(map.mapping());
    for (uint32_t i = 1; i < 36; ++i)
      EXPECT_NEAR(sh.at(i, c), 0.0, 1e-3 * dc)
          << prt::io::env_mapping_name(map.mapping()) << " coefficient " << i;
  }
}

TEST(EnvSh, ConstantMapGivesOnlyDcInEveryMapping) {
  ExpectConstantProjection(ConstantMap(128, 64, EnvMapping::LatLong));
  ExpectConstantProjection(ConstantMap(96, 128, EnvMapping::VerticalCross));
  ExpectConstantProjection(ConstantMap(128, 128, EnvMapping::AngularProbe));
}

TEST(EnvSh, LatLongAgreesWithRuntimeProjection) {
  const int w = 128, h = 64;
  std::vector<float> rgb(size_t(w) * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = float(1.0 + 0.7 * std::sin(0.013 * i));
  const EnvMap map(w, h, rgb, EnvMapping::LatLong, "pattern");
  const auto sh = prt::bake::project_env_sh(map, 8);
  std::vector<float> runtime(64 * 3);
  ASSERT_EQ(prt_sh_test::ProjectLatLong(8, w, h, rgb.data(), w * 3, runtime.data()), PRT_OK);
  for (size_t i = 0; i < runtime.size(); ++i) EXPECT_NEAR(sh.rgb[i], runtime[i], 1e-4) << i;
}

TEST(EnvSh, RejectsBadOrder) {
  const EnvMap map = ConstantMap(8, 4, EnvMapping::LatLong);
  EXPECT_THROW(prt::bake::project_env_sh(map, 0), prt::bake::Error);
  EXPECT_THROW(prt::bake::project_env_sh(map, PRT_SH_MAX_ORDER + 1), prt::bake::Error);
}

std::filesystem::path SharedAssets() {
  return std::filesystem::path(PRT_SHARED_DIR) / "assets";
}

// The table's function f(w) = sum RH_lm Y'_lm(w), projected onto our basis by a quadrature
// exact for band 2 (Gauss-Legendre in cos theta x uniform phi): an independent frame change.
std::vector<double> TableInOurFrame(const std::vector<std::array<double, 3>>& table) {
  const auto gl = prt_sh_test::GaussLegendre(4);
  const int phi_steps = 8;
  std::vector<double> ours(27, 0.0);
  for (size_t a = 0; a < gl.nodes.size(); ++a)
    for (int b = 0; b < phi_steps; ++b) {
      const double z = gl.nodes[a], s = std::sqrt(1 - z * z), phi = 2 * kPi * (b + 0.5) / phi_steps;
      const double w[3] = {s * std::cos(phi), z, s * std::sin(phi)};  // any parametrisation
      const auto rh = prt_test::published_sh9_basis_world(w[0], w[1], w[2]);
      const float wf[3] = {float(w[0]), float(w[1]), float(w[2])};
      float y[9];
      EXPECT_EQ(prt_sh_eval(3, wf, y), PRT_OK);
      const double weight = gl.weights[a] * 2 * kPi / phi_steps;
      for (int c = 0; c < 3; ++c) {
        double f = 0.0;
        for (int i = 0; i < 9; ++i) f += table[i][c] * rh[i];
        for (int i = 0; i < 9; ++i) ours[i * 3 + c] += weight * f * y[i];
      }
    }
  return ours;
}

std::vector<std::array<double, 3>> EucalyptusTable(const std::filesystem::path& json_path) {
  std::ifstream in(json_path);
  const auto j = nlohmann::json::parse(in);
  const auto& coeffs = j.at("environments").at("eucalyptus_grove").at("coefficients");
  std::vector<std::array<double, 3>> table(9);
  for (const auto& [name, entry] : coeffs.items()) {
    const int l = entry.at("l"), m = entry.at("m");
    const auto rgb = entry.at("rgb");
    table[l * (l + 1) + m] = {rgb[0], rgb[1], rgb[2]};
  }
  return table;
}

TEST(EnvSh, ProbeReproducesPublishedEucalyptusGroveCoefficients) {
  const auto probe = SharedAssets() / "envmaps" / "rnl_probe.hdr";
  const auto table_path = SharedAssets() / "tables" / "sh9_irradiance_envmaps.json";
  if (!std::filesystem::exists(probe) || !std::filesystem::exists(table_path))
    GTEST_SKIP() << "shared assets not found under " << SharedAssets();
  // MANIFEST: the tabulated values are 1/10 of the raw projection.
  auto table = EucalyptusTable(table_path);
  for (auto& rgb : table)
    for (auto& v : rgb) v *= 10.0;
  const auto expected = TableInOurFrame(table);
  const EnvMap map = prt::io::load_envmap(probe.string(), EnvMapping::Auto);
  const auto sh = prt::bake::project_env_sh(map, 3);
  double largest = 0.0;
  for (double v : expected) largest = std::max(largest, std::abs(v));
  for (int i = 0; i < 27; ++i)
    EXPECT_NEAR(sh.rgb[i], expected[i], 0.01 * largest)
        << "coefficient " << i / 3 << " channel " << i % 3;
}

// The hand-derived l <= 2 frame mapping written in prt_sh.h / SPEC agrees with the quadrature.
TEST(EnvSh, DocumentedTableFrameMappingMatchesQuadrature) {
  std::vector<std::array<double, 3>> table(9);
  for (int i = 0; i < 9; ++i) table[i] = {0.1 * (i + 1), -0.05 * i, std::sin(i + 0.5)};
  const auto quad = TableInOurFrame(table);
  const double h = std::sqrt(3.0) / 2.0;
  for (int c = 0; c < 3; ++c) {
    auto rh = [&](int l, int m) { return table[l * (l + 1) + m][c]; };
    const double doc[9] = {rh(0, 0),
                           rh(1, 0),
                           rh(1, -1),
                           rh(1, 1),
                           rh(2, 1),
                           rh(2, -1),
                           -0.5 * rh(2, 0) - h * rh(2, 2),
                           rh(2, -2),
                           -h * rh(2, 0) + 0.5 * rh(2, 2)};
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(quad[i * 3 + c], doc[i], 1e-5) << i;
  }
}

#ifdef PRT_BAKE_EXE
TEST(EnvShCli, PrintsJsonMatchingTheLibrary) {
  const auto dir = std::filesystem::path(PRT_TEST_SCRATCH) / "env_sh_cli";
  std::filesystem::create_directories(dir);
  // A tiny lat-long Radiance file (flat RGBE, 8 x 4, two values).
  const auto map_path = dir / "tiny.hdr";
  {
    std::ofstream out(map_path, std::ios::binary);
    out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n";
    for (int i = 0; i < 32; ++i) {
      const unsigned char texel[4] = {128, 64, static_cast<unsigned char>(i < 16 ? 32 : 128), 129};
      out.write(reinterpret_cast<const char*>(texel), 4);
    }
  }
  // stdout and stderr together: a tiny map that loads cleanly prints nothing but the JSON.
  const prt_test::CommandResult r = prt_test::run_command(
      PRT_BAKE_EXE, "env-sh " + prt_test::shell_quote(map_path.string()) + " --order 4",
      dir / "out.json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j.at("order"), 4);
  EXPECT_EQ(j.at("mapping"), "latlong");
  EXPECT_TRUE(j.contains("frame"));
  EXPECT_TRUE(j.contains("convention"));
  const auto& coeffs = j.at("coefficients");
  ASSERT_EQ(coeffs.size(), 16u);
  const EnvMap map = prt::io::load_envmap(map_path.string(), EnvMapping::Auto);
  const auto sh = prt::bake::project_env_sh(map, 4);
  for (uint32_t i = 0; i < 16; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(coeffs[i][c].get<double>(), sh.at(i, c));
  // A bad order is refused with a non-zero exit.
  const prt_test::CommandResult bad = prt_test::run_command(
      PRT_BAKE_EXE, "env-sh " + prt_test::shell_quote(map_path.string()) + " --order 0",
      dir / "bad.log");
  EXPECT_NE(bad.exit_code, 0) << bad.output;
}
#endif

}  // namespace
