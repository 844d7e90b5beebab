// SPDX-License-Identifier: MIT
// Which technique prt-view draws a blob with: the runtime says which sections the blob holds
// (prt_asset_techniques); the first of the viewer's table wins unless --technique picks one. A
// blob with none, or without the one named, fails naming what it holds; --help lists the
// techniques and their own options.
#include <gtest/gtest.h>
#include <prt/format/blob_writer.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "sh/sh_blob_test_util.hpp"
#include "viewer/viewer_test_util.hpp"
#include "wavelet/wavelet_blob_test_util.hpp"

namespace {

using namespace prt_view_test;

// A blob holding an `sh` and a `wavelet` section over the same 10 vertices (one triangle).
std::string blob_with_both() {
  const std::uint32_t vertices = 10;
  const prt_test::Transfer sh = prt_test::random_transfer(3, vertices, 3, 8, 5);
  const prt_test::WvltTransfer wavelet =
      prt_test::wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, vertices, 30, 6);
  prt::format::BlobWriter writer;
  std::vector<float> positions(3 * vertices);
  for (std::size_t i = 0; i < positions.size(); ++i) positions[i] = float(i % 7) * 0.25f;
  const std::uint32_t triangle[3] = {0, 1, 2};
  prt::format::SectionOptions required;
  required.required = true;
  writer.add_section(PRT_BLOB_TAG_VPOS, positions.data(), positions.size() * 4, vertices, required);
  writer.add_section(PRT_BLOB_TAG_TRIS, triangle, sizeof triangle, 1, required);
  const prt_test::Bytes shtr = prt_test::encode(sh), wvlt = prt_test::wvlt_encode(wavelet);
  writer.add_section(PRT_BLOB_TAG_SHTR, shtr.data(), shtr.size(), vertices, required);
  writer.add_section(PRT_BLOB_TAG_WVLT, wvlt.data(), wvlt.size(), vertices, required);
  return write_blob("both.prtk", writer.finish());
}

prt_test::CommandResult view_frames(const std::string& blob, const std::string& extra,
                                    const std::string& name) {
  return run_view(
      quote(blob) + " --env " + quote(write_test_sky()) + " --headless --frames 2 " + extra, name);
}

TEST(PrtViewTechnique, BlobWithSeveralIsDrawnWithTheFirstUnlessOneIsNamed) {
  const std::string blob = blob_with_both();
  const prt_test::CommandResult first = view_frames(blob, "", "both_default");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("both.prtk: 10 vertices, 1 triangles, sh order 3"), std::string::npos)
      << first.output;
  const prt_test::CommandResult named = view_frames(blob, "--technique wavelet", "both_wavelet");
  ASSERT_EQ(named.exit_code, 0) << named.output;
  EXPECT_NE(named.output.find("both.prtk: 10 vertices, 1 triangles, wavelet cube 16"),
            std::string::npos)
      << named.output;
  EXPECT_EQ(named.output.find("sh order"), std::string::npos) << named.output;
  const prt_test::CommandResult sh = view_frames(blob, "--technique sh", "both_sh");
  ASSERT_EQ(sh.exit_code, 0) << sh.output;
  EXPECT_NE(sh.output.find("sh order 3"), std::string::npos) << sh.output;
}

TEST(PrtViewTechnique, MeshOnlyBlobFailsSayingItHoldsNoTechnique) {
  const prt_test::CommandResult run = view_frames(golden("tiny.prtk"), "", "mesh_only");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(
      run.output.find("tiny.prtk: nothing prt-view can draw: the blob holds only a mesh, no "
                      "technique section (prt-view draws sh, wavelet, pose, cloth, shadowfield)"),
      std::string::npos)
      << run.output;
}

TEST(PrtViewTechnique, NamedTechniqueTheBlobLacksFailsNamingWhatItHolds) {
  const prt_test::CommandResult run =
      view_frames(golden("sh_quad.prtk"), "--technique wavelet", "lacks_wavelet");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("sh_quad.prtk: no `wavelet` section to draw (the blob holds sh)"),
            std::string::npos)
      << run.output;
  const prt_test::CommandResult wavelet =
      view_frames(golden("wavelet_quad.prtk"), "--technique sh", "lacks_sh");
  EXPECT_EQ(wavelet.exit_code, 1) << wavelet.output;
  EXPECT_NE(wavelet.output.find("no `sh` section to draw (the blob holds wavelet)"),
            std::string::npos)
      << wavelet.output;
}

TEST(PrtViewTechnique, UnknownTechniqueNameIsABadArgument) {
  const prt_test::CommandResult run =
      view_frames(golden("sh_quad.prtk"), "--technique marble", "unknown_technique");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("--technique"), std::string::npos) << run.output;
}

TEST(PrtViewTechnique, HelpListsTheTechniquesAndTheirOptions) {
  const prt_test::CommandResult run = run_view("--help", "help");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  for (const char* text : {"--technique", "wavelet options:", "--light-coefficients",
                           "Techniques: sh, wavelet, pose, cloth, shadowfield. A blob holding "
                           "several is drawn with the "
                           "first of them unless --technique picks another"})
    EXPECT_NE(run.output.find(text), std::string::npos) << text << "\n" << run.output;
}

// The golden cloth blob (linen_plain, velvet) drawn per vertex with the fabric and lobe count
// the command line gives; a fabric the blob lacks is refused.
TEST(PrtViewTechnique, ClothDrawsTheFabricItIsGiven) {
  const prt_test::CommandResult run = view_frames(
      golden("cloth_quad.prtk"), "--fabric 1 --cloth-lobes 4 --backend cpu", "cloth_velvet");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("cloth_quad.prtk: 8 vertices, 4 triangles, cloth: 2 fabrics (drawn "
                            "as 1, velvet)"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("fitted with 4 lobes"), std::string::npos) << run.output;
  const prt_test::CommandResult missing =
      view_frames(golden("cloth_quad.prtk"), "--fabric 2", "cloth_no_fabric");
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_NE(missing.output.find("has 2 fabrics, no fabric 2"), std::string::npos) << missing.output;
}

TEST(PrtViewTechnique, AnotherTechniquesOptionIsIgnoredWithAWarning) {
  const prt_test::CommandResult run =
      view_frames(golden("sh_quad.prtk"), "--light-coefficients 5", "foreign_option");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("prt-view: --light-coefficients is a `wavelet` option: ignored, the "
                            "blob is drawn with `sh`"),
            std::string::npos)
      << run.output;
  const prt_test::CommandResult own =
      view_frames(golden("wavelet_quad.prtk"), "--light-coefficients 5", "own_option");
  EXPECT_EQ(own.exit_code, 0) << own.output;
  EXPECT_EQ(own.output.find("ignored"), std::string::npos) << own.output;
  EXPECT_NE(own.output.find("6 + 5 light coefficients kept"), std::string::npos) << own.output;
}

// The golden shadowfield blob (the quad scene as one glossy object) drawn as one instance in its
// own frame: the header line, and the same radiance from the scalar and the best CPU backend
// (the SIMD kernels sum in another order: float roundings apart).
TEST(PrtViewTechnique, ShadowfieldDrawsItsObjectAlone) {
  const std::string blob = golden("shadowfield_quad.prtk");
  const prt_test::CommandResult run = view_frames(blob, "--backend cpu", "shadowfield_header");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("shadowfield_quad.prtk: 8 vertices, 4 triangles, shadowfield order 3, "
                            "glossy (2 BRDF term(s)), basis 2, 8-bit; one instance"),
            std::string::npos)
      << run.output;
  const std::string sky = write_test_sky();
  const std::vector<float> cpu = view_vertices(blob, sky, "shadowfield_cpu", "--backend cpu");
  const std::vector<float> best = view_vertices(blob, sky, "shadowfield_auto", "--backend auto");
  ASSERT_EQ(cpu.size(), 24u);
  ASSERT_EQ(best.size(), 24u);
  EXPECT_LT(relative_difference(best, cpu), 5e-7);
  for (const float x : cpu) EXPECT_TRUE(std::isfinite(x));
}

}  // namespace
