// SPDX-License-Identifier: MIT
// prt-bake reference end to end: the white furnace through the command line, read back from its
// .npy output, and its JSON report.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "prt/baker/demo_scene.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

namespace fs = std::filesystem;

fs::path output_dir() {
  const fs::path dir = fs::path(PRT_TEST_OUTPUT_DIR) / "reference_cli";
  fs::create_directories(dir);
  return dir;
}

void write_obj(const Mesh& mesh, const fs::path& path) {
  std::ofstream out(path);
  out.precision(9);
  for (const glm::vec3& p : mesh.positions) out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (const glm::vec3& n : mesh.normals) out << "vn " << n.x << ' ' << n.y << ' ' << n.z << '\n';
  for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
    out << 'f';
    for (int k = 0; k < 3; ++k)
      out << ' ' << mesh.indices[i + k] + 1 << "//" << mesh.indices[i + k] + 1;
    out << '\n';
  }
}

std::string read_all(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

// Reads a float32 [N,3] .npy written by prt-bake.
std::vector<float> read_npy_n3(const fs::path& path, std::size_t* rows) {
  const std::string bytes = read_all(path);
  EXPECT_GE(bytes.size(), 10u);
  if (bytes.size() < 10) return {};
  const std::size_t header_len =
      static_cast<unsigned char>(bytes[8]) | (static_cast<unsigned char>(bytes[9]) << 8);
  const std::string header = bytes.substr(10, header_len);
  const std::size_t shape = header.find("'shape': (");
  EXPECT_NE(shape, std::string::npos);
  *rows = std::stoul(header.substr(shape + 10));
  EXPECT_NE(header.find("'shape': (" + std::to_string(*rows) + ", 3)"), std::string::npos);
  std::vector<float> values(*rows * 3);
  EXPECT_EQ(bytes.size(), 10 + header_len + values.size() * 4);
  std::memcpy(values.data(), bytes.data() + 10 + header_len,
              std::min(values.size() * 4, bytes.size() - 10 - header_len));
  return values;
}

int run(const std::string& args) {
  const std::string command = std::string("\"") + PRT_BAKE_EXE + "\" " + args;
  return std::system(command.c_str());
}

TEST(ReferenceCommand, WhiteFurnaceThroughTheCommandLine) {
  const fs::path dir = output_dir();
  const Mesh sphere = test::make_icosphere(2, 1.5f);
  write_obj(sphere, dir / "sphere.obj");
  write_envmap_hdr(io::constant_envmap(glm::vec3(1.0f)), (dir / "white.hdr").string());

  for (const int bounces : {0, 2}) {
    const fs::path npy = dir / ("sphere_" + std::to_string(bounces) + ".npy");
    const fs::path report = dir / ("report_" + std::to_string(bounces) + ".json");
    fs::remove(npy);
    ASSERT_EQ(run("reference \"" + (dir / "sphere.obj").string() + "\" --env \"" +
                  (dir / "white.hdr").string() + "\" --albedo 0.8,0.8,0.8 --spp 1024 --bounces " +
                  std::to_string(bounces) + " --vertex-out \"" + npy.string() + "\" --report \"" +
                  report.string() + "\" --threads 2 --quiet"),
              0);
    std::size_t rows = 0;
    const std::vector<float> values = read_npy_n3(npy, &rows);
    ASSERT_EQ(rows, sphere.vertex_count());
    for (std::size_t i = 0; i < values.size(); ++i) ASSERT_NEAR(values[i], 0.8f, 0.008f) << i;
    const std::string json = read_all(report);
    EXPECT_NE(json.find("\"relative_rmse\""), std::string::npos) << json;
    EXPECT_NE(json.find("\"rays_per_second\""), std::string::npos) << json;
  }
}

TEST(ReferenceCommand, WritesPngAndHdrImages) {
  const fs::path dir = output_dir();
  write_glb(make_demo_scene(), (dir / "demo.glb").string());
  write_envmap_hdr(make_demo_sky(64), (dir / "sky.hdr").string());
  for (const char* name : {"demo.png", "demo.hdr"}) {
    const fs::path image = dir / name;
    fs::remove(image);
    ASSERT_EQ(run("reference \"" + (dir / "demo.glb").string() + "\" --env \"" +
                  (dir / "sky.hdr").string() + "\" --image-out \"" + image.string() +
                  "\" --image-size 40x30 --image-spp 2 --bounces 1 --quiet"),
              0);
    int w = 0, h = 0, channels = 0;
    void* data = std::string(name).find(".hdr") != std::string::npos
                     ? static_cast<void*>(stbi_loadf(image.string().c_str(), &w, &h, &channels, 3))
                     : static_cast<void*>(stbi_load(image.string().c_str(), &w, &h, &channels, 3));
    ASSERT_NE(data, nullptr) << name;
    EXPECT_EQ(w, 40);
    EXPECT_EQ(h, 30);
    stbi_image_free(data);
  }
}

TEST(ReferenceCommand, BadArgumentsFailWithNonZeroExit) {
  const fs::path dir = output_dir();
  write_obj(test::make_icosphere(1), dir / "small.obj");
  const std::string scene = "\"" + (dir / "small.obj").string() + "\"";
  EXPECT_NE(run("reference " + scene + " --albedo 0.5,0.5 --quiet 2>/dev/null"), 0);
  EXPECT_NE(run("reference " + scene + " --image-out x.png --image-size 10 --quiet 2>/dev/null"),
            0);
  EXPECT_NE(run("reference " + scene + " --env \"" + (dir / "missing.hdr").string() +
                "\" --quiet 2>/dev/null"),
            0);
  EXPECT_NE(run("reference " + scene + " --spp 1 --quiet 2>/dev/null"), 0);
}

}  // namespace
}  // namespace prt::bake
