// SPDX-License-Identifier: MIT
// prt-view on `pose` blobs (the frozen golden hinge, and a random section built here) under maps
// written here. Expected values come from elsewhere: per-vertex radiance recomputed here as dot
// products of the runtime's transfer at the bind pose (prt_pose_transfer, another entry point
// than the shading prt-view calls) with the map's SH light turned into the model frame by the
// rule of formats/SPEC.md §7.3 (L' = rotate(L, R_mᵀ), R_m from prt_pose_skin), and properties
// (a full turn is no turn, backends agree, GL is refused with the runtime's reason).
#include <gtest/gtest.h>
#include <prt/prt.hpp>

#include <string>
#include <vector>

#include "pose/pose_blob.hpp"
#include "viewer/viewer_test_util.hpp"

namespace {

using namespace prt_view_test;

const std::string kBlob = golden("pose_hinge.prtk");  // 8 vertices, 2 joints, model 1

// A `pose` blob built here: 37 vertices (no SIMD width divides it), 3 joints, model 1.
std::string odd_pose_blob() {
  const prt_test::PoseSection s = prt_test::random_section(4, 37, 3, 2, 5, 16, 1, 11);
  return write_blob("odd_pose.prtk", prt_test::pose_blob(s));
}

// Σ_c t[v][c] · L'[c] in double, t from prt_pose_transfer (scalar backend) at the bind pose.
std::vector<float> shade_independently(const std::string& blob, const std::string& map) {
  int width = 0, height = 0;
  const std::vector<float> pixels = read_hdr(map, &width, &height);
  auto [context, made] = prt::create_context();
  EXPECT_EQ(made, PRT_OK);
  auto [owned, loaded] = prt::load_asset_file(context.get(), blob.c_str(), PRT_VALIDATE_FULL);
  EXPECT_EQ(loaded, PRT_OK) << blob;
  if (!owned) return {};
  const prt_asset* asset = owned.get();
  prt_pose_info info = prt::sized<prt_pose_info>();
  EXPECT_EQ(prt_pose_get_info(asset, &info), PRT_OK);
  const std::uint32_t n2 = info.order * info.order, vertices = info.vertex_count;
  std::vector<float> light(3u * n2);
  const prt_env_image env = prt::latlong_env(width, height, pixels.data());
  EXPECT_EQ(prt_sh_project(info.order, &env, light.data()), PRT_OK);
  std::vector<float> rotations(4u * info.joint_count);
  EXPECT_EQ(prt_pose_bind_pose(asset, rotations.data(), nullptr, nullptr), PRT_OK);
  prt_pose_input pose = prt::sized<prt_pose_input>();
  pose.joint_rotations = rotations.data();
  float frame[12];
  EXPECT_EQ(prt_pose_skin(asset, &pose, 0, 0, nullptr, nullptr, frame), PRT_OK);
  const float model_from_world[9] = {frame[0], frame[4], frame[8], frame[1], frame[5],
                                     frame[9], frame[2], frame[6], frame[10]};
  EXPECT_EQ(prt_sh_rotate(info.order, model_from_world, light.data(), light.data(), 3), PRT_OK);
  std::vector<float> transfer(std::size_t(vertices) * n2), radiance(3u * vertices);
  EXPECT_EQ(prt_pose_transfer(asset, PRT_BACKEND_CPU, &pose, nullptr, 0, vertices, transfer.data()),
            PRT_OK);
  for (std::uint32_t v = 0; v < vertices; ++v)
    for (int ch = 0; ch < 3; ++ch) {
      double sum = 0.0;
      for (std::uint32_t c = 0; c < n2; ++c)
        sum += double(transfer[std::size_t(v) * n2 + c]) * light[3 * c + ch];
      radiance[3 * v + ch] = float(sum);
    }
  return radiance;
}

TEST(PrtViewPose, VertexOutMatchesDotProductsOfTheRuntimesTransfer) {
  const std::string sky = write_test_sky();
  for (const std::string& blob : {kBlob, odd_pose_blob()}) {
    const std::vector<float> shaded = view_vertices(blob, sky, "pose_cpu", "--backend cpu");
    const std::vector<float> expected = shade_independently(blob, sky);
    ASSERT_EQ(shaded.size(), expected.size()) << blob;
    ASSERT_FALSE(shaded.empty());
    EXPECT_LT(relative_difference(shaded, expected), 1e-5) << blob;  // float sums vs double
  }
}

TEST(PrtViewPose, PrintsThePoseHeader) {
  const prt_test::CommandResult run = run_view(
      quote(kBlob) + " --env " + quote(write_test_sky()) + " --headless --frames 2", "pose_header");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("pose_hinge.prtk: 8 vertices, "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find(" 2 joints, pose order "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("residual model PCA(1, 3)"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("rotated 0 deg about +Y (prt_sh_rotate)"), std::string::npos)
      << run.output;
}

TEST(PrtViewPose, FullTurnEqualsNoTurnAndAQuarterTurnDoesNot) {
  const std::string sky = write_test_sky();
  const std::string blob = odd_pose_blob();
  const std::vector<float> a = view_vertices(blob, sky, "pose_turn0", "--backend cpu");
  const std::vector<float> b =
      view_vertices(blob, sky, "pose_turn360", "--backend cpu --rotate 360");
  const std::vector<float> c = view_vertices(blob, sky, "pose_turn90", "--backend cpu --rotate 90");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), c.size());
  ASSERT_FALSE(a.empty());
  EXPECT_LT(relative_difference(b, a), 1e-5);
  EXPECT_GT(relative_difference(c, a), 1e-2);
}

TEST(PrtViewPose, BackendsAgreeAndGlIsRefused) {
  const std::string sky = write_test_sky();
  const std::string blob = odd_pose_blob();
  const std::vector<float> cpu = view_vertices(blob, sky, "pose_agree_cpu", "--backend cpu");
  const std::vector<float> best = view_vertices(blob, sky, "pose_agree_auto", "--backend auto");
  ASSERT_EQ(cpu.size(), best.size());
  EXPECT_LT(relative_difference(best, cpu), 1e-5);
  if (!PRT_VIEW_HAS_GL) GTEST_SKIP() << "built without the headless GL helper";
  const prt_test::CommandResult gl = run_view(
      quote(blob) + " --env " + quote(sky) + " --headless --frames 2 --backend gl", "pose_gl");
  EXPECT_EQ(gl.exit_code, 1) << gl.output;
  EXPECT_NE(gl.output.find("PRT_ERROR_UNSUPPORTED_BACKEND"), std::string::npos) << gl.output;
}

}  // namespace
