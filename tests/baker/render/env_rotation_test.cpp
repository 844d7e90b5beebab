// SPDX-License-Identifier: MIT
// Turning the environment (EnvMap::set_rotation, prt-bake reference --env-rotate) against an
// independent construction: a lat-long map turned 90 degrees about +Y is the same map with its
// columns shifted by a quarter of the width.
//
// The sign, derived from the conventions (not fitted): with R = [[c,0,s],[0,1,0],[-s,0,c]] at 90
// degrees (c = 0, s = 1), light from d = (sin t sin p, cos t, -sin t cos p) (formats/SPEC.md §12)
// comes from R d = (-sin t cos p, cos t, -sin t sin p), which is the direction of azimuth
// p - 90 degrees. Since u = 0.5 + p / 2pi, light seen in column x of the original is seen in
// column x - W/4 of the turned map: turned(x, y) = original((x + W/4) mod W, y).
#include <gtest/gtest.h>

#include <prt/prt.hpp>

#include <stb_image_write.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/sh/env_sh.hpp"
#include "prt/baker/reference.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

constexpr int kWidth = 64, kHeight = 32;

// An environment with no symmetry about +Y: a smooth colour pattern and a small bright patch.
std::vector<float> asymmetric_pixels() {
  std::vector<float> rgb(kWidth * kHeight * 3);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      float* t = &rgb[(y * kWidth + x) * 3];
      const float u = (x + 0.5f) / kWidth, v = (y + 0.5f) / kHeight;
      t[0] = 0.2f + 0.8f * u * (1.0f - v);
      t[1] = 0.3f + 0.5f * std::sin(3.0f * u + 1.0f) * std::sin(3.14159f * v);
      t[2] = 0.1f + 0.6f * v * v;
      if (x >= 10 && x < 13 && y >= 8 && y < 10) t[0] += 40.0f, t[1] += 30.0f, t[2] += 20.0f;
    }
  }
  return rgb;
}

std::vector<float> shifted_by_quarter(const std::vector<float>& rgb) {
  std::vector<float> out(rgb.size());
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const int from = (x + kWidth / 4) % kWidth;
      for (int c = 0; c < 3; ++c) out[(y * kWidth + x) * 3 + c] = rgb[(y * kWidth + from) * 3 + c];
    }
  }
  return out;
}

EnvMap turned_map(double degrees) {
  EnvMap map(kWidth, kHeight, asymmetric_pixels(), EnvMapping::LatLong, "turned");
  map.set_rotation(rotation_about_y(degrees));
  return map;
}

EnvMap shifted_map() {
  return EnvMap(kWidth, kHeight, shifted_by_quarter(asymmetric_pixels()), EnvMapping::LatLong,
                "shifted");
}

TEST(EnvRotation, MatrixIsTheDocumentedOne) {
  float r[9];
  rotation_about_y_row_major(30.0, r);
  const float c = std::cos(30.0f * 3.14159265f / 180.0f),
              s = std::sin(30.0f * 3.14159265f / 180.0f);
  const float expected[9] = {c, 0, s, 0, 1, 0, -s, 0, c};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(r[i], expected[i], 1e-6f) << i;
  // Light from +X (the map's three-quarter column) comes from R(+X) = (c, 0, -s) afterwards.
  const glm::vec3 moved = rotation_about_y(30.0) * glm::vec3(1.0f, 0.0f, 0.0f);
  EXPECT_NEAR(moved.x, c, 1e-6f);
  EXPECT_NEAR(moved.z, -s, 1e-6f);
}

TEST(EnvRotation, QuarterTurnOfLatLongEqualsQuarterColumnShift) {
  const EnvMap turned = turned_map(90.0), shifted = shifted_map();
  std::mt19937 rng(7);
  std::normal_distribution<float> normal;
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 d = glm::normalize(glm::vec3(normal(rng), normal(rng), normal(rng)));
    const glm::vec3 a = turned.radiance(d), b = shifted.radiance(d);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1e-3f * (1.0f + b[c])) << i;
    int ax = 0, ay = 0, bx = 0, by = 0;
    turned.texel_of(d, &ax, &ay);
    shifted.texel_of(d, &bx, &by);
    // Nearest-texel lookups agree except on a texel border, where rounding may pick either side.
    if (ax != (bx + kWidth / 4) % kWidth || ay != by) {
      EXPECT_LT(glm::length(turned.texel_value(ax, ay) - shifted.texel_value(bx, by)) /
                    (1.0f + glm::length(shifted.texel_value(bx, by))),
                1.0f)
          << i;
    }
  }
  // Texel x of the turned map is seen where texel x - W/4 of the shifted map is.
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      glm::vec3 a, b;
      float wa = 0.0f, wb = 0.0f;
      ASSERT_TRUE(turned.texel(x, y, &a, &wa));
      ASSERT_TRUE(shifted.texel((x - kWidth / 4 + kWidth) % kWidth, y, &b, &wb));
      EXPECT_NEAR(glm::length(a - b), 0.0f, 1e-5f) << x << "," << y;
      EXPECT_FLOAT_EQ(wa, wb);
    }
  }
}

TEST(EnvRotation, FullTurnIsIdentityAndRejectsNonRotations) {
  const EnvMap turned = turned_map(360.0);
  EXPECT_FALSE(turned.rotated());
  EnvMap map = shifted_map();
  glm::mat3 mirror(1.0f);
  mirror[0][0] = -1.0f;
  EXPECT_THROW(map.set_rotation(mirror), Error);
  EXPECT_THROW(map.set_rotation(glm::mat3(2.0f)), Error);
}

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
  rotation_about_y_row_major(90.0, r);
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
  const EnvMap turned = turned_map(90.0), shifted = shifted_map(), unturned = turned_map(0.0);
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

// float32 [N,3] .npy as prt-bake writes it (header length from bytes 8-9, then raw floats).
std::vector<float> read_npy_floats(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
  if (bytes.size() < 10) return {};
  const std::size_t data =
      10 + (static_cast<unsigned char>(bytes[8]) | (static_cast<unsigned char>(bytes[9]) << 8));
  std::vector<float> values((bytes.size() - data) / 4);
  std::memcpy(values.data(), bytes.data() + data, values.size() * 4);
  return values;
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
    const std::string command = std::string("\"") + PRT_BAKE_EXE + "\" reference \"" +
                                (dir / "scene.glb").string() + "\" --env \"" +
                                (dir / env).string() + "\" --spp 128 --vertex-out \"" +
                                (dir / (name + ".npy")).string() + "\" --report \"" +
                                (dir / (name + ".json")).string() + "\" --quiet " + extra;
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return read_npy_floats(dir / (name + ".npy"));
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
    std::ifstream in(dir / (name + ".json"));
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
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
  std::ifstream report(dir / "turned.json");
  const std::string json((std::istreambuf_iterator<char>(report)),
                         std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"rotate_degrees\": 90"), std::string::npos) << json;
}

}  // namespace
}  // namespace prt::bake
