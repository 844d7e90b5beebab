// SPDX-License-Identifier: MIT
// Every shared character and its Draco copy trains and evaluates with `prt-bake bake pose` at its
// defaults (residual model, clip cross-validation, clamping): the bake's self-check through the
// runtime passes, and the runtime shades a mid-clip pose and that pose twice as far from the
// bind pose on the scalar and SIMD backends with finite values and t_00 between 0 and the
// unoccluded value ρ (A_0/π) y_00 = ρ/(2√π). Nothing below names a joint or a clip.
#include <gtest/gtest.h>

#include <prt/prt.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "prt/baker/animation.hpp"
#include "prt/baker/scene.hpp"
#include "support/command.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

namespace fs = std::filesystem;

struct Character {
  const char* path;  // under ../shared/assets
};

const Character kCharacters[] = {
    {"characters/CesiumMan.glb"},    {"characters/Fox.glb"},
    {"characters/RiggedFigure.glb"}, {"characters/RiggedSimple/RiggedSimple.gltf"},
    {"characters/SimpleSkin.gltf"},  {"draco/CesiumMan_Draco.glb"},
    {"draco/Fox_Draco.glb"}};

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) /
                       ("prt_pose_characters_" + std::to_string(::getpid()) + "_" + name);
  fs::create_directories(dir);
  return dir;
}

// The first clip's joint rotations halfway through it, in the skin's joint order.
std::vector<glm::quat> mid_clip_rotations(const Scene& scene) {
  ScenePose pose(scene);
  const Animation& clip = scene.animations.front();
  pose.apply(clip, 0.5f * clip.duration);
  std::vector<glm::quat> out;
  for (int node : scene.skins.front().joints)
    out.push_back(pose.local(static_cast<std::size_t>(node)).rotation);
  return out;
}

// q = b exp(s log(b^-1 q)): the rotation whose feature (SPEC §7.3) is s times q's.
glm::dquat scaled_from_bind(const glm::dquat& b, const glm::dquat& q, double s) {
  glm::dquat r = glm::conjugate(b) * q;
  if (r.w < 0.0) r = -r;
  const glm::dvec3 axis(r.x, r.y, r.z);
  const double len = glm::length(axis);
  if (len == 0.0) return b;
  const double angle = s * 2.0 * std::atan2(len, r.w);
  const glm::dvec3 u = axis / len;
  const glm::dquat e(std::cos(0.5 * angle), u * std::sin(0.5 * angle));
  return b * e;
}

class PoseCharacter : public ::testing::TestWithParam<Character> {};

TEST_P(PoseCharacter, TrainsAndEvaluatesAtTwiceItsPose) {
  const std::string file = prt_test::shared_asset(GetParam().path);
  if (file.empty()) GTEST_SKIP() << "shared assets not found";
  const fs::path dir = temp_dir(fs::path(GetParam().path).stem().string());
  const fs::path blob = dir / "pose.prtk", report = dir / "pose.json";
  const prt_test::CommandResult bake = prt_test::run_command(
      PRT_BAKE_EXE,
      "--quiet bake pose " + prt_test::shell_quote(file) + " --rays 16 --rate 4 --threads 2 -o " +
          prt_test::shell_quote(blob.string()) + " --report " +
          prt_test::shell_quote(report.string()),
      dir / "bake.log");
  ASSERT_EQ(bake.exit_code, 0) << bake.output;
  std::ifstream in(report);
  const nlohmann::json json = nlohmann::json::parse(in);
  EXPECT_TRUE(json["self_check"]["passed"].get<bool>()) << json["self_check"].dump();

  prt_context* raw = nullptr;
  ASSERT_EQ(prt_context_create(nullptr, &raw), PRT_OK);
  const prt::ContextPtr context(raw);
  prt_asset* asset = nullptr;
  ASSERT_EQ(prt_asset_load_file(raw, blob.string().c_str(), PRT_VALIDATE_FULL, &asset), PRT_OK)
      << prt_context_last_message(raw);
  const prt::AssetPtr owned(asset);
  prt_pose_info info = prt::sized<prt_pose_info>();
  ASSERT_EQ(prt_pose_get_info(asset, &info), PRT_OK);
  EXPECT_EQ(info.model, PRT_POSE_MODEL_RESIDUAL);

  const Scene scene = import_scene(file, Context{});
  const std::vector<glm::quat> mid = mid_clip_rotations(scene);
  ASSERT_EQ(mid.size(), info.joint_count);
  std::vector<float> bind(4 * info.joint_count);
  ASSERT_EQ(prt_pose_bind_pose(asset, bind.data(), nullptr, nullptr), PRT_OK);
  const std::size_t n2 = std::size_t(info.order) * info.order;
  const double unoccluded = info.albedo / (2.0 * std::sqrt(3.14159265358979323846));
  for (double scale : {1.0, 2.0}) {
    std::vector<float> rotations;
    for (std::size_t j = 0; j < mid.size(); ++j) {
      const glm::dquat b(bind[4 * j + 3], bind[4 * j], bind[4 * j + 1], bind[4 * j + 2]);
      const glm::dquat q(mid[j].w, mid[j].x, mid[j].y, mid[j].z);
      const glm::dquat s = scaled_from_bind(glm::normalize(b), glm::normalize(q), scale);
      rotations.insert(rotations.end(), {float(s.x), float(s.y), float(s.z), float(s.w)});
    }
    prt_pose_input pose = prt::sized<prt_pose_input>();
    pose.joint_rotations = rotations.data();
    for (prt_backend backend : {PRT_BACKEND_CPU, PRT_BACKEND_SIMD}) {
      std::vector<float> t(info.vertex_count * n2);
      const prt_result r =
          prt_pose_transfer(asset, backend, &pose, nullptr, 0, info.vertex_count, t.data());
      if (backend == PRT_BACKEND_SIMD && r == PRT_ERROR_UNSUPPORTED_BACKEND) continue;
      ASSERT_EQ(r, PRT_OK) << prt_context_last_message(raw);
      std::size_t outside = 0;
      for (std::size_t v = 0; v < info.vertex_count; ++v) {
        for (std::size_t c = 0; c < n2; ++c) ASSERT_TRUE(std::isfinite(t[v * n2 + c])) << v;
        const double t00 = t[v * n2];
        // Float rounding of the SIMD sum may cross the bounds by a few ulps of the value.
        outside += t00 < -1e-6 || t00 > unoccluded * (1.0 + 1e-6);
      }
      EXPECT_EQ(outside, 0u) << "scale " << scale << ", backend " << backend;
    }
  }
}

std::string character_name(const ::testing::TestParamInfo<Character>& info) {
  std::string name = fs::path(info.param.path).stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(SharedCharacters, PoseCharacter, ::testing::ValuesIn(kCharacters),
                         character_name);

}  // namespace
}  // namespace prt::bake
