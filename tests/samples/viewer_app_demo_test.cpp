// SPDX-License-Identifier: MIT
// prt-viewer on real bakes: the demo scene baked with `sh` (order 4) and `wavelet` (cube 16) by
// the viewer tests' fixture (tests/viewer/bake_demo_blob.cmake), thousands of vertices.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "samples/viewer_app_test_util.hpp"

namespace {

using namespace prt_viewer_app_test;

std::string demo(const std::string& name) {
  return std::string(PRT_VIEWER_DEMO_DIR) + "/" + name;
}

// cpu, simd and gl shade the demo scene's thousands of vertices alike; measured: at most one
// step at a few pixels.
TEST(PrtViewerDemo, ShAndWaveletBakesLookTheSameOnEveryBackendInAWindow) {
  PRT_SKIP_WITHOUT_WINDOWS();
  for (const char* blob : {"demo_sh4.prtk", "demo_wavelet16.prtk"}) {
    const Picture cpu = screenshot(demo(blob), demo("demo_sky.hdr"), std::string(blob) + "_cpu",
                                   "--backend cpu", true, "480x270");
    ASSERT_FALSE(cpu.rgb.empty());
    // The scene fills the frame's middle.
    EXPECT_GT(centre_coverage(cpu), 0.6) << blob;
    std::vector<std::string> others;
    if (PRT_TEST_SIMD_COMPILED) others.push_back("simd");
    if (PRT_TEST_GL_COMPILED) others.push_back("gl");
    for (const std::string& backend : others) {
      const Picture other =
          screenshot(demo(blob), demo("demo_sky.hdr"), std::string(blob) + "_" + backend,
                     "--backend " + backend, true, "480x270");
      const Difference d = difference(cpu, other);
      std::printf("%s: %s vs cpu: largest difference %d, %zu pixels differ\n", blob,
                  backend.c_str(), d.largest, d.pixels);
      EXPECT_LE(d.largest, 2) << blob << " " << backend;
      EXPECT_LT(d.pixels, cpu.rgb.size() / 3 / 100) << blob << " " << backend;
    }
  }
}

// Under the demo's sun, wavelet's sharp shadows differ from sh's blurred ones: the split screen
// shows each technique on its side of the divider.
TEST(PrtViewerDemo, SplitScreenShowsShLeftAndWaveletRight) {
  const std::string sky = demo("demo_sky.hdr");
  const std::string fixed = "--backend cpu --exposure 0";
  const Picture sh = screenshot(demo("demo_sh4.prtk"), sky, "demo_sh", fixed, false, "480x270");
  const Picture wavelet =
      screenshot(demo("demo_wavelet16.prtk"), sky, "demo_wavelet", fixed, false, "480x270");
  const Picture split =
      screenshot(demo("demo_sh4.prtk"), sky, "demo_split",
                 quote(demo("demo_wavelet16.prtk")) + " --compare split --divider 0.5 " + fixed,
                 false, "480x270");
  EXPECT_LE(difference(split, sh, 0, 240).largest, 1);
  EXPECT_LE(difference(split, wavelet, 240).largest, 1);
  const Difference techniques = difference(sh, wavelet, 240);
  std::printf("sh and wavelet differ at %zu of %d pixels right of the divider\n", techniques.pixels,
              240 * 270);
  EXPECT_GT(techniques.pixels, 1000u);
  EXPECT_EQ(difference(split, sh, 240).pixels, techniques.pixels);
}

}  // namespace
