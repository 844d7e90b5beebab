// SPDX-License-Identifier: MIT
// The C how-tos shade_sh, shade_wavelet and shade_pose on the golden blobs: how they fail (exit
// status and message, both checked) and properties of what they print (a full turn of the light is
// no turn, a quarter turn changes the shading, fewer light coefficients change it, a full turn of a
// joint is no turn). The shape of their
// output on the golden blobs is checked beside validate_blob's (tests/runtime).
#include <gtest/gtest.h>

#include <string>

#include "support/command.hpp"
#include "support/test_files.hpp"

namespace {

std::string golden(const std::string& name) {
  return std::string(PRT_GOLDEN_DIR) + "/1.0/" + name;
}

const prt_test::TempDir& scratch() {
  static const prt_test::TempDir dir("howto");
  return dir;
}

prt_test::CommandResult run(const char* executable, const std::string& arguments,
                            const std::string& name) {
  return prt_test::run_command(executable, arguments, scratch().file(name + ".log"));
}

// The "vertex N: rgb ..." lines of a run.
std::string vertex_lines(const prt_test::CommandResult& result) {
  const std::size_t first = result.output.find("vertex 0: rgb ");
  return first == std::string::npos ? std::string() : result.output.substr(first);
}

TEST(Howto, ShadeShFailsOnAFileThatIsNoBlobQuotingTheRuntime) {
  const prt_test::CommandResult result =
      run(PRT_HOWTO_SHADE_SH, prt_test::shell_quote(golden("../README.md")), "sh_not_blob");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("prtkit error (PRT_ERROR_BAD_MAGIC"), std::string::npos)
      << result.output;
}

TEST(Howto, ShadeShNeedsAnShBlob) {
  const prt_test::CommandResult result =
      run(PRT_HOWTO_SHADE_SH, prt_test::shell_quote(golden("wavelet_quad.prtk")), "sh_on_wavelet");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("wavelet_quad.prtk: no `sh` transfer: PRT_ERROR_NOT_FOUND"),
            std::string::npos)
      << result.output;
}

TEST(Howto, ShadeShRejectsBadArguments) {
  const std::string blob = prt_test::shell_quote(golden("sh_quad.prtk"));
  const prt_test::CommandResult degrees = run(PRT_HOWTO_SHADE_SH, blob + " north", "sh_degrees");
  EXPECT_EQ(degrees.exit_code, 2) << degrees.output;
  EXPECT_NE(degrees.output.find("DEGREES must be a number, got 'north'"), std::string::npos)
      << degrees.output;
  const prt_test::CommandResult none = run(PRT_HOWTO_SHADE_SH, "", "sh_no_arguments");
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("usage: "), std::string::npos) << none.output;
}

TEST(Howto, ShadeShFullTurnIsNoTurnAndAQuarterTurnIsNot) {
  const std::string blob = prt_test::shell_quote(golden("sh_quad.prtk"));
  const prt_test::CommandResult none = run(PRT_HOWTO_SHADE_SH, blob + " 0", "sh_0");
  const prt_test::CommandResult full = run(PRT_HOWTO_SHADE_SH, blob + " 360", "sh_360");
  const prt_test::CommandResult quarter = run(PRT_HOWTO_SHADE_SH, blob + " 90", "sh_90");
  ASSERT_EQ(none.exit_code, 0) << none.output;
  ASSERT_EQ(full.exit_code, 0) << full.output;
  ASSERT_EQ(quarter.exit_code, 0) << quarter.output;
  ASSERT_FALSE(vertex_lines(none).empty()) << none.output;
  EXPECT_EQ(vertex_lines(full), vertex_lines(none));  // printed to 6 digits: equal after rounding
  EXPECT_NE(vertex_lines(quarter), vertex_lines(none));
}

TEST(Howto, ShadeWaveletNeedsAWaveletBlob) {
  const prt_test::CommandResult result =
      run(PRT_HOWTO_SHADE_WAVELET, prt_test::shell_quote(golden("sh_quad.prtk")), "wavelet_on_sh");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("sh_quad.prtk: no `wavelet` transfer: PRT_ERROR_NOT_FOUND"),
            std::string::npos)
      << result.output;
}

TEST(Howto, ShadeWaveletRejectsABadM) {
  const prt_test::CommandResult result = run(
      PRT_HOWTO_SHADE_WAVELET, prt_test::shell_quote(golden("wavelet_quad.prtk")) + " lots", "m");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("usage: "), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("[M]"), std::string::npos) << result.output;
}

TEST(Howto, ShadeWaveletFewerLightCoefficientsChangeTheShading) {
  const std::string blob = prt_test::shell_quote(golden("wavelet_quad.prtk"));
  const prt_test::CommandResult all = run(PRT_HOWTO_SHADE_WAVELET, blob + " 100000", "m_all");
  const prt_test::CommandResult few = run(PRT_HOWTO_SHADE_WAVELET, blob + " 0", "m_0");
  ASSERT_EQ(all.exit_code, 0) << all.output;
  ASSERT_EQ(few.exit_code, 0) << few.output;
  EXPECT_NE(all.output.find("6 + 1530 light coefficients kept"), std::string::npos) << all.output;
  EXPECT_NE(few.output.find("6 + 0 light coefficients kept"), std::string::npos) << few.output;
  ASSERT_FALSE(vertex_lines(all).empty()) << all.output;
  EXPECT_NE(vertex_lines(few), vertex_lines(all));
}

TEST(Howto, ShadePoseRunsOnThePoseHinge) {
  const prt_test::CommandResult result =
      run(PRT_HOWTO_SHADE_POSE, prt_test::shell_quote(golden("pose_hinge.prtk")), "pose_default");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("pose_hinge.prtk: 8 vertices, 2 joints, residual model PCA(1, 3), "
                               "320 bytes; joint 1 bent 40 degrees; backend "),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("vertex 3: rgb "), std::string::npos) << result.output;
}

TEST(Howto, ShadePoseNeedsAPoseBlobAndAJointItHas) {
  const prt_test::CommandResult sh =
      run(PRT_HOWTO_SHADE_POSE, prt_test::shell_quote(golden("sh_quad.prtk")), "pose_on_sh");
  EXPECT_EQ(sh.exit_code, 1) << sh.output;
  EXPECT_NE(sh.output.find("sh_quad.prtk: no `pose` model: PRT_ERROR_NOT_FOUND"), std::string::npos)
      << sh.output;
  const std::string blob = prt_test::shell_quote(golden("pose_hinge.prtk"));
  const prt_test::CommandResult joint = run(PRT_HOWTO_SHADE_POSE, blob + " 2", "pose_joint");
  EXPECT_EQ(joint.exit_code, 1) << joint.output;
  EXPECT_NE(joint.output.find("JOINT must be below 2"), std::string::npos) << joint.output;
  const prt_test::CommandResult word = run(PRT_HOWTO_SHADE_POSE, blob + " 0 far", "pose_word");
  EXPECT_EQ(word.exit_code, 2) << word.output;
  EXPECT_NE(word.output.find("DEGREES must be a number, got 'far'"), std::string::npos)
      << word.output;
}

// Joint 0 is the hinge's model joint: turning it turns the model frame, so the light the runtime
// turns into that frame changes, unless the turn is a full one (the quaternion only negated).
TEST(Howto, ShadePoseFullTurnOfAJointIsNoTurnAndAQuarterTurnIsNot) {
  const std::string blob = prt_test::shell_quote(golden("pose_hinge.prtk"));
  const prt_test::CommandResult none = run(PRT_HOWTO_SHADE_POSE, blob + " 0 0", "pose_0");
  const prt_test::CommandResult full = run(PRT_HOWTO_SHADE_POSE, blob + " 0 360", "pose_360");
  const prt_test::CommandResult quarter = run(PRT_HOWTO_SHADE_POSE, blob + " 0 90", "pose_90");
  ASSERT_EQ(none.exit_code, 0) << none.output;
  ASSERT_EQ(full.exit_code, 0) << full.output;
  ASSERT_EQ(quarter.exit_code, 0) << quarter.output;
  ASSERT_FALSE(vertex_lines(none).empty()) << none.output;
  EXPECT_EQ(vertex_lines(full), vertex_lines(none));  // printed to 6 digits: equal after rounding
  EXPECT_NE(vertex_lines(quarter), vertex_lines(none));
}

}  // namespace
