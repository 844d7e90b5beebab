// SPDX-License-Identifier: MIT
// Turning the environment through the runtime's SH rotation, the baker's projection, the
// reference renderer and prt-bake reference --env-rotate, against an independent construction:
// a lat-long map turned 90 degrees about +Y is the same map with its columns shifted by a quarter
// of the width (io/turned_maps.hpp derives the sign; tests/io/env_rotation_test.cpp checks the
// EnvMap itself).
#include <gtest/gtest.h>

#include <prt/prt.hpp>

#include <stb_image_write.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "io/turned_maps.hpp"
#include "prt/baker/demo_scene.hpp"
#include "prt/baker/reference.hpp"
#include "prt/baker/sh/env_sh.hpp"
#include "support/command.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

using io::test::asymmetric_pixels;
using io::test::kHeight;
using io::test::kWidth;
using io::test::shifted_by_quarter;
using io::test::shifted_map;
using io::test::turned_map;

// The runtime's SH rotation of the original map's projection equals the projection of the
// shifted map: ties prt_sh_rotate's convention to the renderer's.
TEST(EnvRotation, RuntimeShRotationMatchesShiftedProjection) {
  constexpr std::uint32_t kOrder = 6;
  const std::vector<float> original = asymmetric_pixels(), shifted = shifted_by_quarter(original);
  std::vector<float> turned(kOrder * kOrder * 3), expected(turned.size());
  const prt_env_image original_env = prt::latlong_env(kWidth, kHeight, original.data());
  const prt_env_image shifted_env = prt::latlong_env(kWidth, kHeight, shifted.data());
  ASSERT_EQ(prt_sh_project(kOrder, &original_env, turned.data()), PRT_OK);
  ASSERT_EQ(prt_sh_project(kOrder, &shifted_env, expected.data()), PRT_OK);
  float r[9];
  io::rotation_about_y_row_major(90.0, r);
  ASSERT_EQ(prt_sh_rotate(kOrder, r, turned.data(), turned.data(), 3), PRT_OK);
  float largest = 0.0f;
  for (const float v : expected) largest = std::max(largest, std::abs(v));
  for (std::size_t i = 0; i < turned.size(); ++i) {
    EXPECT_NEAR(turned[i], expected[i], 1e-4f * largest) << "coefficient " << i / 3;
  }
  // The baker's projection through the turned EnvMap's texels agrees too.
  const std::vector<float> baker = project_env_sh(turned_map(90.0), kOrder).to_float();
  for (std::size_t i = 0; i < turned.size(); ++i) {
    EXPECT_NEAR(baker[i], expected[i], 1e-4f * largest) << "coefficient " << i / 3;
  }
}

// Per-vertex reference radiance of a small occluding scene: the turned map and the shifted map
// are the same lighting, so the two renders agree within their own noise estimate.
TEST(EnvRotation, ReferenceRadianceUnderTurnedMapMatchesShiftedMap) {
  const Scene scene = test::scene_of(
      {test::make_icosphere(2, 0.5f, glm::vec3(0.0f, 0.5f, 0.0f)), test::make_plane(2.0f, 8)});
  ReferenceSettings settings;
  settings.spp = 256;
  settings.bounces = 1;
  settings.override_albedo = true;
  settings.albedo = glm::vec3(0.6f);
  const io::EnvMap turned = turned_map(90.0), shifted = shifted_map(), unturned = turned_map(0.0);
  const VertexRadiance a =
      ReferenceRenderer(scene, turned, settings, Context{}).render_vertices({});
  settings.seed = 1;  // independent samples
  const VertexRadiance b =
      ReferenceRenderer(scene, shifted, settings, Context{}).render_vertices({});
  const VertexRadiance c =
      ReferenceRenderer(scene, unturned, settings, Context{}).render_vertices({});
  double diff = 0.0, norm = 0.0, diff_unturned = 0.0;
  for (std::size_t v = 0; v < a.radiance.size(); ++v) {
    const glm::dvec3 d = glm::dvec3(a.radiance[v]) - glm::dvec3(b.radiance[v]);
    const glm::dvec3 e = glm::dvec3(c.radiance[v]) - glm::dvec3(b.radiance[v]);
    diff += glm::dot(d, d);
    diff_unturned += glm::dot(e, e);
    norm += glm::dot(glm::dvec3(b.radiance[v]), glm::dvec3(b.radiance[v]));
  }
  const double relative = std::sqrt(diff / norm);
  const double noise = std::hypot(a.relative_rmse, b.relative_rmse);
  EXPECT_LT(relative, 3.0 * noise) << "noise " << noise;
  // And the rotation matters: without it the difference is far above the noise.
  EXPECT_GT(std::sqrt(diff_unturned / norm), 10.0 * noise);
}

// prt-bake reference --env-rotate 90 on a map equals no rotation on its quarter-shifted copy
// (the RGBE files hold the same texels, permuted), and the report states the rotation.
TEST(EnvRotation, ReferenceCommandTurnsTheEnvironment) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(PRT_TEST_OUTPUT_DIR) / "env_rotation";
  fs::create_directories(dir);
  write_glb(test::scene_of({test::make_icosphere(2, 0.5f, glm::vec3(0.0f, 0.5f, 0.0f)),
                            test::make_plane(2.0f, 8)}),
            (dir / "scene.glb").string());
  const std::vector<float> original = asymmetric_pixels(), shifted = shifted_by_quarter(original);
  ASSERT_TRUE(stbi_write_hdr((dir / "original.hdr").c_str(), kWidth, kHeight, 3, original.data()));
  ASSERT_TRUE(stbi_write_hdr((dir / "shifted.hdr").c_str(), kWidth, kHeight, 3, shifted.data()));
  auto render = [&](const std::string& env, const std::string& extra, const std::string& name) {
    auto quoted = [&](const std::string& file) {
      return prt_test::shell_quote((dir / file).string());
    };
    const prt_test::CommandResult r = prt_test::run_command(
        PRT_BAKE_EXE,
        "reference " + quoted("scene.glb") + " --env " + quoted(env) + " --spp 128 --vertex-out " +
            quoted(name + ".npy") + " --report " + quoted(name + ".json") + " --quiet " + extra,
        dir / (name + ".log"));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const prt_test::NpyArray npy = prt_test::read_npy_f32(dir / (name + ".npy"));
    EXPECT_EQ(npy.columns, 3u) << name;
    return npy.values;
  };
  const std::vector<float> turned = render("original.hdr", "--env-rotate 90", "turned");
  const std::vector<float> expected = render("shifted.hdr", "--seed 1", "shifted");
  ASSERT_EQ(turned.size(), expected.size());
  ASSERT_FALSE(turned.empty());
  double diff = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < turned.size(); ++i) {
    diff += (double(turned[i]) - expected[i]) * (double(turned[i]) - expected[i]);
    norm += double(expected[i]) * expected[i];
  }
  // Two independent renders of the same lighting differ by their combined noise, which each
  // report estimates (relative_rmse); a wrong turn differs by far more (the map is asymmetric).
  auto noise_of = [&](const std::string& name) {
    const std::string text = prt_test::read_text(dir / (name + ".json"));
    const std::size_t at = text.find("\"relative_rmse\":");
    return at == std::string::npos ? 0.0 : std::atof(text.c_str() + at + 16);
  };
  const double noise = std::hypot(noise_of("turned"), noise_of("shifted"));
  EXPECT_GT(noise, 0.0);
  EXPECT_LT(std::sqrt(diff / norm), 3.0 * noise) << "noise " << noise;
  const std::vector<float> unturned = render("original.hdr", "--seed 2", "unturned");
  double diff_unturned = 0.0;
  for (std::size_t i = 0; i < turned.size(); ++i) {
    diff_unturned += (double(unturned[i]) - expected[i]) * (double(unturned[i]) - expected[i]);
  }
  EXPECT_GT(std::sqrt(diff_unturned / norm), 4.0 * noise);
  const std::string json = prt_test::read_text(dir / "turned.json");
  EXPECT_NE(json.find("\"rotate_degrees\": 90"), std::string::npos) << json;
}

}  // namespace
}  // namespace prt::bake
