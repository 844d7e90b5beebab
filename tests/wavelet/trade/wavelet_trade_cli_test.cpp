// SPDX-License-Identifier: MIT
// prt-bake trade wavelet end to end on a tiny scene (a box on a grid, the demo sky) with tiny
// settings: the rows the sweep design calls for, the reference cache, determinism of everything
// but the timings, the float/quantised relation, and clear errors for bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "support/trade_cli.hpp"

namespace {

namespace fs = std::filesystem;

using prt_test::CommandResult;
using Table = prt_test::CsvTable;

class WaveletTradeCli : public prt_test::TradeCliTest {
 protected:
  void SetUp() override {
    prt_test::TradeCliTest::SetUp();
    if (HasFatalFailure()) return;
    scene_ = (dir_ / "box_on_ground.obj").string();
    write_box_on_ground(scene_);
  }
  // A 9 x 9 ground grid with a box standing on it (a few hundred vertices): shadows to measure,
  // yet every bake takes a fraction of a second.
  static void write_box_on_ground(const std::string& path) {
    std::ofstream obj(path);
    const int n = 9;
    for (int z = 0; z <= n; ++z) {
      for (int x = 0; x <= n; ++x)
        obj << "v " << -1.0 + 2.0 * x / n << " 0 " << -1.0 + 2.0 * z / n << "\n";
    }
    for (int z = 0; z < n; ++z) {
      for (int x = 0; x < n; ++x) {
        const int a = 1 + z * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
        obj << "f " << a << ' ' << c << ' ' << b << "\nf " << b << ' ' << c << ' ' << d << "\n";
      }
    }
    // The box: 8 corners after the grid's (n+1)^2 vertices, faces wound outwards.
    const int o = (n + 1) * (n + 1);
    for (int i = 0; i < 8; ++i)
      obj << "v " << ((i & 1) ? 0.3 : -0.3) << ' ' << ((i & 2) ? 0.6 : 0.0) << ' '
          << ((i & 4) ? 0.3 : -0.3) << "\n";
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
      obj << "f " << o + 1 + f[0] << ' ' << o + 1 + f[1] << ' ' << o + 1 + f[2] << "\n";
      obj << "f " << o + 1 + f[0] << ' ' << o + 1 + f[2] << ' ' << o + 1 + f[3] << "\n";
    }
  }
  std::string trade_arguments(const std::string& out, int threads) const override {
    return "--threads " + std::to_string(threads) + " trade wavelet " + quoted(scene_) + " --env " +
           quoted(sky_) + " --out-dir " + quoted(out) + " --cache-dir " + quoted(dir_ / "cache") +
           " --sizes 16 --base-size 16 --keeps 20,64 --base-keep 64 --light-terms 0,all"
           " --paraboloid-sizes 16 --sh-orders 2,3 --sh-bits 8,16 --sh-rays 16 --ref-spp 16"
           " --frames 2 --albedo 0.8,0.8,0.8";
  }
  std::string scene_;
};

std::string key(const std::map<std::string, std::string>& row) {
  return row.at("technique") + "/" + row.at("param") + "/" + row.at("size") + "/" + row.at("keep") +
         "/" + row.at("quantizer") + "/" + row.at("light_terms") + "/" + row.at("sh_order");
}

TEST_F(WaveletTradeCli, SweepsCachesAndRepeatsItself) {
  const Table a = run_trade("a", 2, false);
  ASSERT_FALSE(a.empty());

  // Cube 16 (96 blocks... 6 of 256): N sweep at K = 64 (default_wavelet_keep's floor), K sweep
  // {20, 64} x {float, vertex, band}, M sweep {0, all} at K 64 band, param at 16 (cube and
  // paraboloid); sh orders {2, 3} x {8, 16} bits. One map.
  // Every setting shades better than black (relative RMSE 1); more kept coefficients, more light
  // detail terms and a higher sh order are closer to the reference, by far more than its noise.
  const auto [sweeps, error] = swept(a, key);
  EXPECT_LT(error.at("wavelet/cube/16/64/band/all/"), error.at("wavelet/cube/16/20/band/all/"));
  EXPECT_LT(error.at("wavelet/cube/16/64/float/all/"), error.at("wavelet/cube/16/20/float/all/"));
  EXPECT_LT(error.at("wavelet/cube/16/64/band/all/"), error.at("wavelet/cube/16/64/band/0/"));
  EXPECT_LT(error.at("sh////8-bit grey//3"), error.at("sh////8-bit grey//2"));
  const std::map<std::string, std::string> expected = {
      {"wavelet/cube/16/20/float/all/", "K"},  {"wavelet/cube/16/20/vertex/all/", "K"},
      {"wavelet/cube/16/20/band/all/", "K"},   {"wavelet/cube/16/64/float/all/", "K"},
      {"wavelet/cube/16/64/vertex/all/", "K"}, {"wavelet/cube/16/64/band/all/", "N+K+M+param"},
      {"wavelet/cube/16/64/band/0/", "M"},     {"wavelet/dual-paraboloid/16/64/band/all/", "param"},
      {"sh////8-bit grey//2", "sh"},           {"sh////16-bit grey//2", "sh"},
      {"sh////8-bit grey//3", "sh"},           {"sh////16-bit grey//3", "sh"}};
  EXPECT_EQ(sweeps, expected);

  // Bytes per vertex follow SPEC §7.2 and §7.1: 12 vs + 4 rs + 2 B counts + 2 per pair (the
  // section's fixed header and band scales spread over the vertices), n^2 b/8 for grey sh.
  for (const auto& row : a) {
    if (row.at("quantizer") == "float") {
      EXPECT_EQ(row.at("transfer_bytes_per_vertex"), "") << key(row);
      continue;
    }
    const double bytes = std::stod(row.at("transfer_bytes_per_vertex"));
    const double vertices = std::stod(row.at("vertices"));
    if (row.at("technique") == "sh") {
      const double n = std::stod(row.at("sh_order"));
      const double bits = row.at("quantizer").rfind("8-bit", 0) == 0 ? 8 : 16;
      const double raw = 32 + 8 * n * n + vertices * n * n * bits / 8;
      EXPECT_NEAR(bytes, raw / vertices, 4 / vertices + 0.01) << key(row);
    } else {
      const double faces = row.at("param") == "cube" ? 6 : 2, size = 16;
      const double blocks = faces * size * size / 256,
                   pairs = std::stod(row.at("pairs_per_vertex"));
      const double raw = 32 + 4 * faces * 5 + vertices * (12 + 4 + 2 * blocks + 2 * pairs) + 4;
      EXPECT_NEAR(bytes, raw / vertices, 4 / vertices + 0.02) << key(row);
      EXPECT_LE(pairs, std::stod(row.at("keep"))) << key(row);
    }
  }

  // Second run, on one thread: references from the cache, the same numbers but for the timings.
  const Table b = run_trade("b", 1, true);
  ASSERT_FALSE(b.empty());
  expect_same_but_timings(
      a, b,
      {"shade_cpu_ms", "shade_simd_ms", "light_update_ms", "bake_seconds", "rays_per_second"});
}

TEST_F(WaveletTradeCli, BadInputGivesAClearError) {
  const std::string base =
      "trade wavelet " + quoted(scene_) + " --out-dir " + quoted(dir_ / "x") + " ";
  const CommandResult missing_map = run_bake(base + "--env nothere.hdr", dir_ / "x.log");
  EXPECT_NE(missing_map.exit_code, 0);
  EXPECT_NE(missing_map.output.find("nothere.hdr"), std::string::npos) << missing_map.output;
  const CommandResult bad_size =
      run_bake(base + "--env " + quoted(sky_) + " --sizes 16,48", dir_ / "y.log");
  EXPECT_NE(bad_size.exit_code, 0);
  EXPECT_NE(bad_size.output.find("--sizes: 48"), std::string::npos) << bad_size.output;
  const CommandResult bad_terms =
      run_bake(base + "--env " + quoted(sky_) + " --light-terms 10,most", dir_ / "z.log");
  EXPECT_NE(bad_terms.exit_code, 0);
  EXPECT_NE(bad_terms.output.find("'most'"), std::string::npos) << bad_terms.output;
  const CommandResult foreign =
      run_bake(base + "--env " + quoted(sky_) + " --orders 2,3", dir_ / "w.log");
  EXPECT_NE(foreign.exit_code, 0);
  EXPECT_NE(foreign.output.find("--orders"), std::string::npos) << foreign.output;
  EXPECT_FALSE(fs::exists(dir_ / "x" / "trade.csv"));
}

// --help lists the sweep's flags and the shared ones with wavelet's defaults (2048 reference
// samples, 10 frames), not sh's own trade flags.
TEST_F(WaveletTradeCli, HelpListsWaveletSweepFlagsOnly) {
  const CommandResult help = run_bake("trade wavelet --help", dir_ / "help.log");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  for (const char* flag : {"--sizes",          "--base-size",
                           "--keeps",          "--base-keep",
                           "--light-terms",    "--paraboloid-sizes",
                           "--no-paraboloid",  "--quantizer",
                           "--samples",        "--sh-orders",
                           "--sh-rays",        "--sh-bits",
                           "--vertex-stride",  "--env",
                           "--out-dir",        "--cache-dir",
                           "1073741824]=2048", "--frames INT=10",
                           "--albedo",         "--seed"})
    EXPECT_NE(help.output.find(flag), std::string::npos) << flag << "\n" << help.output;
  for (const char* flag : {"--orders", "--base-order", "--base-rays", "--bits "})
    EXPECT_EQ(help.output.find(flag), std::string::npos) << flag << "\n" << help.output;
}

}  // namespace
