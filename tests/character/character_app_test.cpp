// SPDX-License-Identifier: MIT
// prt-character headless on CesiumMan baked here with its ground truth (prt-bake bake pose
// --ground-truth, few rays): it writes the picture, plays the clip at a fixed step, and its
// split-view error figure on a training frame is the one computed here another way: under a
// constant sky only the SH band-0 coefficient lights a vertex (L' = L after any rotation), so the
// relative RMSE of radiance is that of coefficient 0 between prt_pose_transfer (a runtime entry
// point the app does not call) at the frame's joint rotations and the baked transfer, both read
// here.
#include <gtest/gtest.h>
#include <stb_image.h>
#include <prt/prt.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "support/command.hpp"
#include "support/shared_bake.hpp"
#include "support/test_files.hpp"

namespace {

const prt_test::TempDir& scratch() {
  static const prt_test::TempDir dir("character");
  return dir;
}

// A 32 x 16 lat-long map of constant radiance 1 (RGBE 128 128 128 129), flat scanlines.
std::string constant_sky() {
  std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16 +X 32\n";
  for (int i = 0; i < 32 * 16; ++i) bytes += std::string("\x80\x80\x80\x81", 4);
  return scratch().write("constant.hdr", bytes);
}

// Bakes CesiumMan and its ground truth to `prefix`.prtk and `prefix`'s files.
bool bake_cesium(const std::string& scene, const std::string& prefix) {
  const prt_test::CommandResult run = prt_test::run_command(
      PRT_BAKE_EXE,
      "bake pose " + prt_test::shell_quote(scene) + " --rays 64 --rate 10 --ground-truth " +
          prt_test::shell_quote(prefix) + " -o " + prt_test::shell_quote(prefix + ".prtk"),
      scratch().file("bake.log"));
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return run.exit_code == 0;
}

// Where the tests' bake is made: under ctest, in the folder PRT_CHARACTER_BAKE names, by the
// fixture test CharacterBake (tests/character/CMakeLists.txt); by hand, in the scratch folder.
const char* const kBakeVariable = "PRT_CHARACTER_BAKE";

// The CesiumMan bake and its ground truth into `folder`/cesium.
bool bake_cesium_into(const std::string& folder) {
  return bake_cesium(prt_test::shared_asset("characters/CesiumMan.glb"), folder + "/cesium");
}

// The bake's prefix, made once ("" without the shared assets or when the bake failed).
const std::string& bake() {
  static const std::string prefix = [] {
    if (prt_test::shared_asset("characters/CesiumMan.glb").empty()) return std::string();
    const std::string folder =
        prt_test::shared_bake_folder(kBakeVariable, scratch().dir(), bake_cesium_into);
    return folder.empty() ? folder : folder + "/cesium";
  }();
  return prefix;
}

TEST(CharacterBake, MakesTheBakeTheOtherTestsShare) {
  if (prt_test::shared_asset("characters/CesiumMan.glb").empty())
    GTEST_SKIP() << "shared assets (CesiumMan.glb) not found";
  prt_test::make_shared_bake(kBakeVariable, bake_cesium_into);
}

#define BAKE_OR_SKIP()                                                           \
  if (bake().empty()) GTEST_SKIP() << "shared assets (CesiumMan.glb) not found"; \
  const std::string prefix = bake()

prt_test::CommandResult character(const std::string& prefix, const std::string& extra,
                                  const std::string& name) {
  return prt_test::run_command(PRT_CHARACTER_EXE,
                               prt_test::shell_quote(prefix + ".prtk") + " --ground-truth " +
                                   prt_test::shell_quote(prefix) + " --env " +
                                   prt_test::shell_quote(constant_sky()) +
                                   " --headless --size 160x120 --supersample 1 " + extra,
                               scratch().file(name + ".log"));
}

// The figure of the line "vs baked frame F (...): relative RMSE X", or NaN.
double printed_rmse(const std::string& output) {
  const std::size_t at = output.find("relative RMSE ");
  return at == std::string::npos ? std::nan("") : std::atof(output.c_str() + at + 14);
}

std::vector<float> read_npy_f32(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 10) return {};
  const std::size_t start =
      10 + (static_cast<unsigned char>(bytes[8]) | static_cast<unsigned char>(bytes[9]) << 8);
  std::vector<float> values((bytes.size() - start) / 4);
  std::memcpy(values.data(), bytes.data() + start, values.size() * 4);
  return values;
}

// sqrt(Σ_v (t_runtime[v][0] - t_baked[v][0])² / Σ_v t_baked[v][0]²) at baked frame f.
double band0_rmse(const std::string& prefix, std::uint32_t f) {
  auto [context, made] = prt::create_context();
  EXPECT_EQ(made, PRT_OK);
  auto [asset, loaded] =
      prt::load_asset_file(context.get(), (prefix + ".prtk").c_str(), PRT_VALIDATE_FULL);
  EXPECT_EQ(loaded, PRT_OK);
  if (!asset) return std::nan("");
  prt_pose_info info = prt::sized<prt_pose_info>();
  EXPECT_EQ(prt_pose_get_info(asset.get(), &info), PRT_OK);
  const std::size_t n2 = std::size_t(info.order) * info.order, V = info.vertex_count;
  const std::vector<float> baked = read_npy_f32(prefix + ".transfer.npy");
  const std::vector<float> rotations = read_npy_f32(prefix + ".rotations.npy");
  EXPECT_GE(baked.size(), (f + 1) * V * n2);
  EXPECT_GE(rotations.size(), (f + 1) * 4u * info.joint_count);
  prt_pose_input pose = prt::sized<prt_pose_input>();
  pose.joint_rotations = rotations.data() + std::size_t(f) * 4 * info.joint_count;
  std::vector<float> transfer(V * n2);
  EXPECT_EQ(prt_pose_transfer(asset.get(), PRT_BACKEND_CPU, &pose, nullptr, 0, info.vertex_count,
                              transfer.data()),
            PRT_OK);
  double diff = 0.0, norm = 0.0;
  for (std::size_t v = 0; v < V; ++v) {
    const double a = transfer[v * n2], b = baked[(f * V + v) * n2];
    diff += (a - b) * (a - b);
    norm += b * b;
  }
  return std::sqrt(diff / norm);
}

TEST(Character, SplitViewOnATrainingFrameWritesThePictureAndTheIndependentError) {
  BAKE_OR_SKIP();
  const std::string shot = scratch().file("split.png");
  const prt_test::CommandResult run = character(
      prefix, "--frame 5 --frames 3 --screenshot " + prt_test::shell_quote(shot), "split");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  int width = 0, height = 0, channels = 0;
  unsigned char* pixels = stbi_load(shot.c_str(), &width, &height, &channels, 3);
  ASSERT_NE(pixels, nullptr) << shot;
  stbi_image_free(pixels);
  EXPECT_EQ(width, 160);
  EXPECT_EQ(height, 120);
  EXPECT_NE(run.output.find("vs baked frame 5 (clip 0, 0.500 s): relative RMSE"), std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find("another pose"), std::string::npos) << run.output;
  const double printed = printed_rmse(run.output), expected = band0_rmse(prefix, 5);
  ASSERT_TRUE(std::isfinite(printed)) << run.output;
  EXPECT_GT(printed, 0.0);
  // Float shading against double sums here, the figure printed to 5 digits, and the
  // quadrature's leak of a constant map into the higher bands: measured 3e-4 of the figure.
  EXPECT_NEAR(printed, expected, 1e-3 * expected) << run.output;
  EXPECT_LT(printed, 0.2) << "a training frame the model was fitted to";
}

// A fixed step of 0.1 s from 0 lands on baked frame 6 after six frames (the bake's --rate 10).
TEST(Character, PlaysTheClipAtAFixedStep) {
  BAKE_OR_SKIP();
  const prt_test::CommandResult run = character(prefix, "--time-step 0.1 --frames 6", "play");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("vs baked frame 6 (clip 0, 0.600 s): relative RMSE"), std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find("another pose"), std::string::npos) << run.output;
}

// Between baked frames, and for a joint posed by hand, there is no ground truth of that pose:
// the figure is against the nearest baked frame and says so; the hand pose changes the picture.
TEST(Character, BetweenFramesAndByHandItComparesWithTheNearestFrameAndSaysSo) {
  BAKE_OR_SKIP();
  const std::string a = scratch().file("frame5.png"), b = scratch().file("hand.png");
  const prt_test::CommandResult between = character(prefix, "--time 0.47 --pause", "between");
  ASSERT_EQ(between.exit_code, 0) << between.output;
  EXPECT_NE(between.output.find("vs baked frame 5 (clip 0, 0.500 s), another pose"),
            std::string::npos)
      << between.output;
  const prt_test::CommandResult plain = character(
      prefix, "--frame 5 --compare single --screenshot " + prt_test::shell_quote(a), "plain");
  const prt_test::CommandResult hand = character(
      prefix,
      "--frame 5 --compare single --pose 3:120,0,0 --screenshot " + prt_test::shell_quote(b),
      "hand");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  ASSERT_EQ(hand.exit_code, 0) << hand.output;
  EXPECT_NE(prt_test::read_text(a), prt_test::read_text(b));
}

TEST(Character, MissingGroundTruthAndGlFailNamingWhy) {
  BAKE_OR_SKIP();
  const prt_test::CommandResult missing =
      prt_test::run_command(PRT_CHARACTER_EXE,
                            prt_test::shell_quote(prefix + ".prtk") + " --ground-truth " +
                                prt_test::shell_quote(prefix + "_none") + " --env " +
                                prt_test::shell_quote(constant_sky()) + " --headless",
                            scratch().file("missing.log"));
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_NE(missing.output.find("cesium_none.transfer.npy: cannot open"), std::string::npos)
      << missing.output;
  const prt_test::CommandResult gl = character(prefix, "--frame 2 --backend gl --frames 2", "gl");
  EXPECT_EQ(gl.exit_code, 1) << gl.output;  // a --frames run exits 1 after a report
  EXPECT_NE(gl.output.find("pose has no GL backend yet"), std::string::npos) << gl.output;
}

// Another blob's ground truth: the shapes say so, naming the file.
TEST(Character, GroundTruthOfAnotherBlobFailsNamingTheShapes) {
  BAKE_OR_SKIP();
  const std::string hinge = std::string(PRT_GOLDEN_DIR) + "/1.0/pose_hinge.prtk";
  const prt_test::CommandResult run = prt_test::run_command(
      PRT_CHARACTER_EXE,
      prt_test::shell_quote(hinge) + " --ground-truth " + prt_test::shell_quote(prefix) +
          " --env " + prt_test::shell_quote(constant_sky()) + " --headless",
      scratch().file("other_blob.log"));
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(
      run.output.find("cesium.transfer.npy: is [21 x 3273 x 36], the blob needs [frames x 8 x"),
      std::string::npos)
      << run.output;
}

TEST(Character, BadOptionsExitTwo) {
  BAKE_OR_SKIP();
  const prt_test::CommandResult run = character(prefix, "--pose 3:1,2", "bad_pose");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("expected J:X,Y,Z"), std::string::npos) << run.output;
}

}  // namespace
