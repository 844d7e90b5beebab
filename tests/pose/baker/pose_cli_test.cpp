// SPDX-License-Identifier: MIT
// `prt-bake bake pose` end to end on the golden hinge (formats/golden/scenes/hinge.gltf): the
// blob loads at full validation with the header asked for, the same bytes for 1 and 2 threads,
// the report carries the model and the self-check, and an unknown clip fails without a blob.
#include <gtest/gtest.h>

#include <prt/prt.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>
#include <nlohmann/json.hpp>

#include "support/command.hpp"

namespace prt::bake {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(::testing::TempDir()) /
                       ("prt_pose_cli_test_" + std::to_string(::getpid()) + "_" + test->name());
  fs::create_directories(dir);
  return dir;
}

prt_test::CommandResult run_bake(const std::string& arguments) {
  return prt_test::run_command(PRT_BAKE_EXE, arguments, temp_dir() / "command.log");
}

std::string hinge() {
  return prt_test::shell_quote(std::string(PRT_SOURCE_DIR) + "/formats/golden/scenes/hinge.gltf");
}

std::vector<char> bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(PoseBakeCommand, HingeBlobLoadsWithTheHeaderAskedFor) {
  const fs::path blob = temp_dir() / "hinge.prtk", report = temp_dir() / "hinge.json";
  const prt_test::CommandResult bake =
      run_bake("--quiet bake pose " + hinge() + " --order 3 --rays 32 --rate 4 --basis-dims 2 " +
               "--model direct --bits 8 --threads 2 -o " + prt_test::shell_quote(blob.string()) +
               " --report " + prt_test::shell_quote(report.string()));
  ASSERT_EQ(bake.exit_code, 0) << bake.output;
  prt_context* raw = nullptr;
  ASSERT_EQ(prt_context_create(nullptr, &raw), PRT_OK);
  const prt::ContextPtr context(raw);
  prt_asset* asset = nullptr;
  ASSERT_EQ(prt_asset_load_file(raw, blob.string().c_str(), PRT_VALIDATE_FULL, &asset), PRT_OK);
  const prt::AssetPtr owned(asset);
  prt_pose_info info = prt::sized<prt_pose_info>();
  ASSERT_EQ(prt_pose_get_info(asset, &info), PRT_OK);
  EXPECT_EQ(info.order, 3u);
  EXPECT_EQ(info.vertex_count, 8u);
  EXPECT_EQ(info.joint_count, 2u);
  EXPECT_EQ(info.basis_dims, 2u);
  EXPECT_EQ(info.model, PRT_POSE_MODEL_DIRECT);
  EXPECT_EQ(info.bits, 8u);

  std::ifstream in(report);
  const nlohmann::json json = nlohmann::json::parse(in);
  EXPECT_EQ(json["technique"], "pose");
  EXPECT_EQ(json["training"]["frames"], 5);  // clip of 1 s at 4 per second: 0 .. 1 s
  EXPECT_EQ(json["training"]["clips"], nlohmann::json::array({"swing"}));
  EXPECT_EQ(json["model"]["basis_dims"], 2);
  EXPECT_EQ(json["model"]["model_bytes"], info.model_bytes);
  EXPECT_TRUE(json["self_check"]["passed"].get<bool>());

  const fs::path one_thread = temp_dir() / "hinge_1.prtk";
  ASSERT_EQ(run_bake("--quiet bake pose " + hinge() + " --order 3 --rays 32 --rate 4 " +
                     "--basis-dims 2 --model direct --bits 8 --threads 1 -o " +
                     prt_test::shell_quote(one_thread.string()))
                .exit_code,
            0);
  EXPECT_EQ(bytes_of(blob), bytes_of(one_thread));
}

TEST(PoseBakeCommand, AnUnknownClipFailsWithoutABlob) {
  const fs::path blob = temp_dir() / "none.prtk";
  const prt_test::CommandResult bake = run_bake("--quiet bake pose " + hinge() +
                                                " --clips walk --rays 8 -o " +
                                                prt_test::shell_quote(blob.string()));
  EXPECT_NE(bake.exit_code, 0);
  EXPECT_NE(bake.output.find("walk"), std::string::npos) << bake.output;
  EXPECT_NE(bake.output.find("swing"), std::string::npos) << bake.output;
  EXPECT_FALSE(fs::exists(blob));
}

}  // namespace
}  // namespace prt::bake
