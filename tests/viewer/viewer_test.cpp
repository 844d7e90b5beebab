// SPDX-License-Identifier: MIT
// prt-view end to end on the demo scene baked by the viewer_bake_demo_blob fixture. Expected
// values come from elsewhere: per-vertex radiance recomputed here from the decoded transfer and
// the runtime's projection (dot products written out, not prt_sh_shade), image sizes from the
// request, and properties (a full turn is no turn, backends agree, a reference of itself has no
// error, a quarter turn equals a quarter shift of the map's columns).
#include <gtest/gtest.h>
#include <prt/prt.hpp>
#include <stb_image.h>
#include <stb_image_write.h>

#include <sys/wait.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "prt/baker/sh/env_sh.hpp"
#include "prt/io/envmap.hpp"

namespace {

const std::string kDir = PRT_VIEW_TEST_DIR;
const std::string kBlob = kDir + "/demo_sh4.prtk";
const std::string kSky = kDir + "/demo_sky.hdr";

struct ViewRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

// Runs prt-view with `arguments` (after `environment`, e.g. "PRT_BACKEND=cpu", for the shell).
ViewRun run_view(const std::string& arguments, const std::string& name,
                 const std::string& environment = "") {
  const std::string log = kDir + "/" + name + ".log";
  const std::string command =
      environment + " \"" + PRT_VIEW_EXE + "\" " + arguments + " > \"" + log + "\" 2>&1";
  const int status = std::system(command.c_str());
  ViewRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  run.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return run;
}

// float32 [N,3] .npy as prt-bake reference writes it (read here without the viewer's code).
std::vector<float> read_npy(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  if (bytes.size() < 10 || bytes[6] != 1) return {};
  const std::size_t header = bytes[8] | (bytes[9] << 8);
  const std::string text(bytes.begin() + 10, bytes.begin() + 10 + static_cast<long>(header));
  if (text.find("'descr': '<f4'") == std::string::npos || text.find(", 3)") == std::string::npos)
    return {};
  std::vector<float> values((bytes.size() - 10 - header) / 4);
  std::memcpy(values.data(), bytes.data() + 10 + header, values.size() * 4);
  return values;
}

double relative_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double diff = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    diff += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    norm += double(b[i]) * b[i];
  }
  return std::sqrt(diff / norm);
}

// Per-vertex radiance computed here: decoded transfer . light (order² RGB coefficients, or
// empty: the runtime's projection of the lat-long `pixels`).
std::vector<float> shade_independently(std::vector<float> light, const std::vector<float>& pixels,
                                       int width, int height) {
  prt_context* context = nullptr;
  prt_asset* asset = nullptr;
  EXPECT_EQ(prt_context_create(nullptr, &context), PRT_OK);
  EXPECT_EQ(prt_asset_load_file(context, kBlob.c_str(), PRT_VALIDATE_FULL, &asset), PRT_OK);
  prt_sh_info info = prt::sized<prt_sh_info>();
  EXPECT_EQ(prt_sh_get_info(asset, &info), PRT_OK);
  const std::uint32_t n2 = info.order * info.order;
  std::vector<float> transfer(std::size_t(info.vertex_count) * info.channels * n2);
  if (light.empty()) {
    light.resize(3 * n2);
    const prt_env_image env = prt::latlong_env(width, height, pixels.data());
    EXPECT_EQ(prt_sh_project(info.order, &env, light.data()), PRT_OK);
  }
  EXPECT_EQ(light.size(), 3u * n2);
  EXPECT_EQ(prt_sh_decode_transfer(asset, 0, info.vertex_count, transfer.data()), PRT_OK);
  std::vector<float> radiance(3 * std::size_t(info.vertex_count));
  for (std::size_t v = 0; v < info.vertex_count; ++v) {
    for (std::uint32_t ch = 0; ch < 3; ++ch) {
      const float* t = &transfer[(v * info.channels + (info.channels == 3 ? ch : 0)) * n2];
      double sum = 0.0;
      for (std::uint32_t k = 0; k < n2; ++k) sum += double(t[k]) * light[3 * k + ch];
      radiance[3 * v + ch] = float(sum);
    }
  }
  prt_asset_destroy(asset);
  prt_context_destroy(context);
  return radiance;
}

std::vector<float> load_sky(int* width, int* height) {
  int channels = 0;
  float* data = stbi_loadf(kSky.c_str(), width, height, &channels, 3);
  EXPECT_NE(data, nullptr);
  std::vector<float> pixels(data, data + std::size_t(*width) * *height * 3);
  stbi_image_free(data);
  return pixels;
}

std::string vertex_run(const std::string& name, const std::string& extra) {
  const std::string out = kDir + "/" + name + ".npy";
  const ViewRun run =
      run_view(kBlob + " --env " + kSky + " --headless --vertex-out " + out + " " + extra, name);
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return out;
}

TEST(PrtView, WritesPngOfRequestedSize) {
  const std::string png = kDir + "/size.png";
  std::remove(png.c_str());
  const ViewRun run = run_view(
      kBlob + " --env " + kSky + " --headless --size 160x90 --out " + png + " --backend cpu",
      "size");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  int w = 0, h = 0, c = 0;
  ASSERT_TRUE(stbi_info(png.c_str(), &w, &h, &c)) << run.output;
  EXPECT_EQ(w, 160);
  EXPECT_EQ(h, 90);
  EXPECT_NE(run.output.find("wrote " + png), std::string::npos) << run.output;
}

TEST(PrtView, VertexOutMatchesDotProductsOfDecodedTransfer) {
  const std::vector<float> shaded = read_npy(vertex_run("cpu", "--backend cpu"));
  int width = 0, height = 0;
  const std::vector<float> pixels = load_sky(&width, &height);
  const std::vector<float> expected = shade_independently({}, pixels, width, height);
  ASSERT_EQ(shaded.size(), expected.size());
  // Float shading against double sums: rounding only.
  EXPECT_LT(relative_difference(shaded, expected), 1e-5);
}

// Cross and probe maps go through a cube resampling and prt_sh_project; the baker projects
// the same file texel by texel with each texel's exact solid angle (another method): the shaded
// radiance agrees to a few times the resampling error (the probe's, the larger); a resampling
// turned by half a probe texel differs by far more.
TEST(PrtView, CrossAndProbeMapsMatchTheBakersTexelProjection) {
  for (const char* name : {"rnl_cross.hdr", "rnl_probe.hdr"}) {
    const std::string map = std::string(PRT_SHARED_DIR) + "/assets/envmaps/" + name;
    if (!std::ifstream(map)) GTEST_SKIP() << map << " not found";
    const std::string out = kDir + "/" + name + ".npy";
    const ViewRun run = run_view(
        kBlob + " --env " + map + " --headless --backend cpu " + "--vertex-out " + out, name);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const prt::io::EnvMap env = prt::io::load_envmap(map, prt::io::EnvMapping::Auto);
    const std::vector<float> light = prt::bake::project_env_sh(env, 4).to_float();
    const std::vector<float> expected = shade_independently(light, {}, 0, 0);
    const std::vector<float> shaded = read_npy(out);
    ASSERT_EQ(shaded.size(), expected.size());
    const double difference = relative_difference(shaded, expected);
    std::printf("%s: relative RMS difference %.5f\n", name, difference);
    EXPECT_LT(difference, 1e-4) << name;
  }
}

TEST(PrtView, FullTurnEqualsNoTurn) {
  const std::vector<float> a = read_npy(vertex_run("turn0", "--backend cpu --rotate 0"));
  const std::vector<float> b = read_npy(vertex_run("turn360", "--backend cpu --rotate 360"));
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  EXPECT_LT(relative_difference(b, a), 1e-5);
}

// Turning the light a quarter about +Y equals shifting the lat-long columns by W/4 (derivation
// in tests/baker/render/env_rotation_test.cpp): turned(x) = original(x + W/4).
TEST(PrtView, QuarterTurnEqualsQuarterColumnShiftOfTheMap) {
  int width = 0, height = 0;
  const std::vector<float> pixels = load_sky(&width, &height);
  ASSERT_EQ(width % 4, 0);
  std::vector<float> shifted(pixels.size());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int from = (x + width / 4) % width;
      for (int c = 0; c < 3; ++c)
        shifted[(y * width + x) * 3 + c] = pixels[(y * width + from) * 3 + c];
    }
  }
  const std::string shifted_path = kDir + "/sky_shifted.hdr";
  ASSERT_TRUE(stbi_write_hdr(shifted_path.c_str(), width, height, 3, shifted.data()));
  const std::vector<float> turned = read_npy(vertex_run("turn90", "--backend cpu --rotate 90"));
  const std::string out = kDir + "/shifted.npy";
  const ViewRun run =
      run_view(kBlob + " --env " + shifted_path + " --headless --backend cpu --vertex-out " + out,
               "shifted");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<float> expected = read_npy(out);
  ASSERT_EQ(turned.size(), expected.size());
  // The SH of a turned light vary smoothly with the turn: rounding only, as for the full turn.
  EXPECT_LT(relative_difference(turned, expected), 1e-5);
  const std::vector<float> unturned = read_npy(vertex_run("turn0b", "--backend cpu"));
  EXPECT_GT(relative_difference(unturned, expected), 1e-2);  // the turn does something
}

TEST(PrtView, CpuAndAutoBackendsAgree) {
  const std::vector<float> cpu = read_npy(vertex_run("agree_cpu", "--backend cpu"));
  const std::vector<float> best = read_npy(vertex_run("agree_auto", "--backend auto"));
  ASSERT_EQ(cpu.size(), best.size());
  // SIMD sums in float (prt_sh_asset.h): rounding of a 16-term dot product.
  EXPECT_LT(relative_difference(best, cpu), 1e-5);
}

TEST(PrtView, GlBackendAgreesWithCpu) {
  if (!PRT_VIEW_HAS_GL) GTEST_SKIP() << "built without the headless GL helper";
  const std::vector<float> cpu = read_npy(vertex_run("gl_cpu", "--backend cpu"));
  const std::vector<float> gl = read_npy(vertex_run("gl_gl", "--backend gl --frames 3"));
  ASSERT_EQ(cpu.size(), gl.size());
  EXPECT_LT(relative_difference(gl, cpu), 1e-5);
}

TEST(PrtView, ReferenceOfItselfHasZeroErrorAndDrawsAHeatMap) {
  const std::string self = vertex_run("self", "--backend cpu");
  const std::string heat = kDir + "/heat.png";
  const ViewRun run =
      run_view(kBlob + " --env " + kSky + " --headless --backend cpu --size 64x48 " +
                   "--reference " + self + " --error-out " + heat + " --frames 3",
               "self_compare");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("relative RMSE 0.00000 (0.00 %)"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("3 frame(s), median"), std::string::npos) << run.output;
  int w = 0, h = 0, c = 0;
  EXPECT_TRUE(stbi_info(heat.c_str(), &w, &h, &c));
  EXPECT_EQ(w, 64);
}

TEST(PrtView, BadBlobFailsNamingTheFile) {
  const std::string not_blob = kDir + "/not_a_blob.prtk";
  std::ofstream(not_blob) << "hello";
  const ViewRun run = run_view(not_blob + " --env " + kSky + " --headless --out x.png", "bad_blob");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("not_a_blob.prtk: "), std::string::npos) << run.output;
}

TEST(PrtView, MissingMapFailsNamingTheFile) {
  const ViewRun run =
      run_view(kBlob + " --env " + kDir + "/no_such_sky.hdr --headless --out x.png", "missing_map");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("no_such_sky.hdr: cannot open file"), std::string::npos) << run.output;
}

// A backend the context may not use (limited here through PRT_BACKEND, as on a CPU without
// SSE4.1) fails with the runtime's result and reason, not a crash or a silent fallback.
TEST(PrtView, UnusableBackendFailsWithTheRuntimesReason) {
  for (const char* backend : {"simd", "gl"}) {
    if (!PRT_VIEW_HAS_GL && std::string(backend) == "gl") continue;
    const ViewRun run =
        run_view(kBlob + " --env " + kSky + " --headless --frames 2 --backend " + backend,
                 std::string("limited_") + backend, "PRT_BACKEND=cpu");
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find(std::string("backend ") + backend + ": "), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("PRT_ERROR_UNSUPPORTED_BACKEND"), std::string::npos) << run.output;
  }
}

TEST(PrtView, BadArgumentsExitTwo) {
  EXPECT_EQ(
      run_view(kBlob + " --env " + kSky + " --headless --backend vulkan --out x.png", "bad_backend")
          .exit_code,
      2);
  EXPECT_EQ(run_view(kBlob + " --env " + kSky + " --out x.png", "no_headless").exit_code, 2);
  EXPECT_EQ(run_view(kBlob + " --headless --out x.png", "no_env").exit_code, 2);
  EXPECT_EQ(run_view(kBlob + " --env " + kSky + " --headless --size 12 --out x.png", "bad_size")
                .exit_code,
            2);
}

TEST(PrtView, MontageTilesImages) {
  const std::string a = kDir + "/tile_a.png", b = kDir + "/tile_b.png", out = kDir + "/tiles.png";
  const unsigned char red[3 * 4 * 2] = {255, 0, 0, 255, 0, 0, 255, 0, 0, 255, 0, 0,
                                        255, 0, 0, 255, 0, 0, 255, 0, 0, 255, 0, 0};
  ASSERT_TRUE(stbi_write_png(a.c_str(), 4, 2, 3, red, 12));
  ASSERT_TRUE(stbi_write_png(b.c_str(), 4, 2, 3, red, 12));
  const ViewRun run =
      run_view("--montage " + out + " --montage-columns 1 " + a + " " + b, "montage");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  int w = 0, h = 0, c = 0;
  ASSERT_TRUE(stbi_info(out.c_str(), &w, &h, &c));
  EXPECT_EQ(w, 4);
  EXPECT_EQ(h, 2 + 4 + 2);  // two tiles and a 4-pixel gap
}

}  // namespace
