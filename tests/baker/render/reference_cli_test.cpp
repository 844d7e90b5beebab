// SPDX-License-Identifier: MIT
// prt-bake reference end to end: the white furnace through the command line, read back from its
// .npy output, and its JSON report.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "prt/baker/demo_scene.hpp"
#include "support/command.hpp"
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

// prt-bake with `arguments` (shell words), its output kept in the test's folder.
prt_test::CommandResult run(const std::string& arguments) {
  return prt_test::run_command(PRT_BAKE_EXE, arguments, output_dir() / "command.log");
}

std::string quoted(const fs::path& path) {
  return prt_test::shell_quote(path.string());
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
    const prt_test::CommandResult r = run(
        "reference " + quoted(dir / "sphere.obj") + " --env " + quoted(dir / "white.hdr") +
        " --albedo 0.8,0.8,0.8 --spp 1024 --bounces " + std::to_string(bounces) + " --vertex-out " +
        quoted(npy) + " --report " + quoted(report) + " --threads 2 --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const prt_test::NpyArray values = prt_test::read_npy_f32(npy);
    ASSERT_EQ(values.rows, sphere.vertex_count());
    ASSERT_EQ(values.columns, 3u);
    for (std::size_t i = 0; i < values.values.size(); ++i)
      ASSERT_NEAR(values.values[i], 0.8f, 0.008f) << i;
    const std::string json = prt_test::read_text(report);
    EXPECT_NE(json.find("\"relative_rmse\""), std::string::npos) << json;
    EXPECT_NE(json.find("\"rays_per_second\""), std::string::npos) << json;
  }
}

// Phong of exponent 0 is the constant 1/pi, as Lambert, but is sampled through the glossy lobe:
// in the white furnace a vertex facing the eye reflects its albedo, one facing away nothing.
TEST(ReferenceCommand, GlossyFurnaceWithAnEyeThroughTheCommandLine) {
  const fs::path dir = output_dir();
  const Mesh sphere = test::make_icosphere(2, 1.5f);
  write_obj(sphere, dir / "glossy_sphere.obj");
  const fs::path npy = dir / "glossy_sphere.npy", report = dir / "glossy_report.json",
                 image = dir / "glossy_sphere.hdr";
  fs::remove(npy);
  fs::remove(image);
  const glm::vec3 eye(1.0f, 2.0f, 6.0f);
  const prt_test::CommandResult r =
      run("reference " + quoted(dir / "glossy_sphere.obj") +
          " --albedo 0.8,0.8,0.8 --brdf phong:0 --eye 1,2,6 --spp 1024 --vertex-out " +
          quoted(npy) + " --report " + quoted(report) + " --image-out " + quoted(image) +
          " --image-size 16x12 --image-spp 4 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const prt_test::NpyArray values = prt_test::read_npy_f32(npy);
  ASSERT_EQ(values.rows, sphere.vertex_count());
  // Lobe sampling fits a constant BRDF worse than cosine sampling: each vertex within about 4.5
  // times the spread over vertices measured at 1024 spp, their mean within 4 standard errors.
  double sum = 0.0;
  std::size_t facing = 0;
  for (std::size_t v = 0; v < sphere.vertex_count(); ++v) {
    const bool faces_eye = glm::dot(sphere.normals[v], eye - sphere.positions[v]) > 0.0f;
    for (int c = 0; c < 3; ++c) {
      ASSERT_NEAR(values.values[3 * v + c], faces_eye ? 0.8f : 0.0f, 0.015f) << v;
    }
    if (faces_eye) sum += values.values[3 * v + 1], ++facing;
  }
  ASSERT_GT(facing, 0u);
  EXPECT_NEAR(sum / facing, 0.8, 0.0017);
  const std::string json = prt_test::read_text(report);
  EXPECT_NE(json.find("\"phong:0,1,0\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"eye\""), std::string::npos) << json;
  EXPECT_TRUE(fs::exists(image));  // seen from the eye
}

TEST(ReferenceCommand, WritesPngAndHdrImages) {
  const fs::path dir = output_dir();
  write_glb(make_demo_scene(), (dir / "demo.glb").string());
  write_envmap_hdr(make_demo_sky(64), (dir / "sky.hdr").string());
  for (const char* name : {"demo.png", "demo.hdr"}) {
    const fs::path image = dir / name;
    fs::remove(image);
    const prt_test::CommandResult r = run(
        "reference " + quoted(dir / "demo.glb") + " --env " + quoted(dir / "sky.hdr") +
        " --image-out " + quoted(image) + " --image-size 40x30 --image-spp 2 --bounces 1 --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.output;
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
  const std::string scene = quoted(dir / "small.obj");
  for (const std::string& bad :
       {std::string("--albedo 0.5,0.5"), std::string("--image-out x.png --image-size 10"),
        "--env " + quoted(dir / "missing.hdr"), std::string("--spp 1"),
        std::string("--brdf phong:x"), std::string("--brdf ggx:0"), std::string("--eye 1,2")}) {
    const prt_test::CommandResult r = run("reference " + scene + " " + bad + " --quiet");
    EXPECT_NE(r.exit_code, 0) << bad << "\n" << r.output;
  }
}

}  // namespace
}  // namespace prt::bake
