// SPDX-License-Identifier: MIT
// prt-viewer's scene mode (samples/viewer/scene_view.hpp), headless: a scene manifest opens with
// prt_scene_load_file and every object is drawn, shaded by prt_scene_shade. Inputs: the golden
// manifest (formats/golden/1.0/scene_quads.prts: the five golden technique blobs beside it) and
// manifests written here with prt::format::write_scene_manifest next to copies of the golden
// blobs (a manifest names its blobs relative to its own folder). Checked through the
// screenshots: the objects cover the frame where the sky would show, each object alone is drawn
// where its blob is drawn by the blob mode, a right-drag turns the scene's light as --rotate
// does, and a manifest naming a missing blob exits 1 naming it.
#include <gtest/gtest.h>
#include <prt/format/scene_writer.hpp>
#include <prt/prt.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "samples/viewer_app_test_util.hpp"

namespace {

using namespace prt_viewer_app_test;
namespace fs = std::filesystem;

const char* const kGoldenBlobs[] = {"sh_quad.prtk", "wavelet_quad.prtk", "cloth_quad.prtk",
                                    "shadowfield_quad.prtk", "pose_hinge.prtk"};

// A fixed exposure, so that pictures of different contents are comparable, and no overlay, so
// that replayed mouse events reach the camera and the light rather than the panel.
const char* const kFixed = "--backend cpu --exposure 0 --no-overlay";

// The section tag of the blob's first technique, as the runtime reads it (what a manifest
// record names).
std::uint32_t technique_tag(const std::string& blob) {
  auto [context, made] = prt::create_context();
  auto [asset, loaded] = prt::load_asset_file(context.get(), blob.c_str(), PRT_VALIDATE_FULL);
  EXPECT_EQ(loaded, PRT_OK) << blob;
  if (!asset) return 0;
  const std::uint32_t techniques = prt_asset_techniques(asset.get());
  for (unsigned t = 1; t < 32; ++t) {
    if (!(techniques & (1u << t))) continue;
    prt_technique_info info = prt::sized<prt_technique_info>();
    if (prt_technique_get_info(prt_technique(t), &info) == PRT_OK) return info.section_tag;
  }
  ADD_FAILURE() << blob << " holds no technique";
  return 0;
}

// A folder `name` in the scratch folder with a manifest scene.prts naming `blobs` (paths relative
// to it, each an object named after its file and of the technique of the golden blob of that
// name, or `sh` where there is none), of which those in `present` are copied from the golden
// folder beside it. Returns the manifest's path.
std::string write_scene(const std::string& name, const std::vector<std::string>& blobs,
                        const std::vector<std::string>& present) {
  const fs::path folder = fs::path(scratch().file(name));
  fs::create_directories(folder);
  std::vector<prt::format::SceneManifestObject> objects;
  for (const std::string& blob : blobs) {
    prt::format::SceneManifestObject object;
    const std::string golden_blob = prt_view_test::golden(blob);
    object.technique_tag = technique_tag(
        fs::exists(golden_blob) ? golden_blob : prt_view_test::golden("sh_quad.prtk"));
    object.name = fs::path(blob).stem().string();
    object.blob = blob;
    objects.push_back(object);
  }
  for (const std::string& blob : present) {
    fs::create_directories((folder / blob).parent_path());
    fs::copy_file(prt_view_test::golden(blob), folder / blob, fs::copy_options::overwrite_existing);
  }
  const std::vector<std::uint8_t> bytes = prt::format::write_scene_manifest(objects);
  return scratch().write(name + "/scene.prts", std::string(bytes.begin(), bytes.end()));
}

// The uniform sky with the sun out of the picture: what is not an object is one colour.
const std::string& sun_map() {
  static const std::string path = sun_at_plus_x_map();
  return path;
}

double covered_fraction(const Picture& p) {
  const std::vector<bool> mask = covered(p);
  std::size_t hit = 0;
  for (bool m : mask) hit += m;
  return mask.empty() ? 0.0 : double(hit) / double(mask.size());
}

TEST(PrtViewerScene, GoldenManifestOpensAndEveryObjectIsListed) {
  const std::string manifest = prt_view_test::golden("scene_quads.prts");
  const std::string png = scratch().file("scene_golden.png");
  const prt_test::CommandResult run =
      run_viewer(quote(manifest) + " --env " + quote(sun_map()) +
                     " --size 320x240 --frames 2 --screenshot " + quote(png) + " " + kFixed,
                 "scene_golden");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("scene of 5 objects"), std::string::npos) << run.output;
  // Names and techniques come from the manifest and prt_technique_get_info.
  for (const char* line : {"sh_quad: sh,", "wavelet_quad: wavelet,", "cloth_quad: cloth,",
                           "shadowfield_quad: shadowfield,", "pose_hinge: pose,"})
    EXPECT_NE(run.output.find(line), std::string::npos) << line << "\n" << run.output;
  EXPECT_NE(run.output.find("prt_scene_set_environment"), std::string::npos) << run.output;
  const Picture p = read_picture(png);
  ASSERT_EQ(p.width, 320);
  ASSERT_EQ(p.height, 240);
  // The objects' box is framed (its corners inside a 5 % margin): the quads, seen from a little
  // above, span most of the frame's width, and are not sky.
  const std::vector<bool> mask = covered(p);
  int left = p.width, right = -1;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x)
      if (mask[std::size_t(y) * p.width + x]) left = std::min(left, x), right = std::max(right, x);
  const double all = covered_fraction(p), span = double(right - left + 1) / p.width;
  std::printf("golden scene: %.3f of the frame covered, %.3f of its width spanned\n", all, span);
  EXPECT_GT(all, 0.15);
  EXPECT_GT(span, 0.75);
}

// A scene opens without a map of the user's: the built-in sky lights it (what the demo scene a
// fresh checkout bakes is lit by), and the objects are drawn.
TEST(PrtViewerScene, WithoutAMapTheBuiltInSkyLightsTheScene) {
  const std::string manifest = prt_view_test::golden("scene_quads.prts");
  const std::string png = scratch().file("scene_builtin_sky.png");
  const prt_test::CommandResult run = run_viewer(
      quote(manifest) + " --size 320x240 --frames 2 --screenshot " + quote(png) + " " + kFixed,
      "scene_builtin_sky");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("lit by the built-in sky"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("builtin:sky"), std::string::npos) << run.output;
  const Picture p = read_picture(png);
  ASSERT_EQ(p.width, 320);
  std::size_t lit = 0;
  for (std::size_t i = 0; i + 2 < p.rgb.size(); i += 3) lit += p.rgb[i] + p.rgb[i + 1] > 0;
  EXPECT_GT(lit, p.rgb.size() / 3 / 2) << "the picture is mostly black";
}

// Each object alone in a scene is framed as the blob mode frames its blob (the same bounds), so
// the two pictures cover the same pixels: the scene draws the blob's mesh where it is.
TEST(PrtViewerScene, EachObjectAloneCoversWhatItsBlobCovers) {
  for (const char* blob : kGoldenBlobs) {
    const std::string name = fs::path(blob).stem().string();
    const std::string manifest = write_scene("one_" + name, {blob}, {blob});
    const Picture scene = screenshot(manifest, sun_map(), "one_" + name + "_scene", kFixed);
    const Picture single =
        screenshot(prt_view_test::golden(blob), sun_map(), "one_" + name + "_blob", kFixed);
    ASSERT_FALSE(scene.rgb.empty()) << blob;
    ASSERT_FALSE(single.rgb.empty()) << blob;
    const std::vector<bool> a = covered(scene), b = covered(single);
    std::size_t in_scene = 0, in_both = 0, in_blob = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      in_scene += a[i];
      in_blob += b[i];
      in_both += a[i] && b[i];
    }
    std::printf("%s: scene covers %zu pixels, blob mode %zu, both %zu\n", blob, in_scene, in_blob,
                in_both);
    EXPECT_GT(in_scene, a.size() / 10) << blob << ": the object is not drawn";
    // The same silhouette, but for pixels whose shading happens to match the sky's colour.
    EXPECT_GT(double(in_both), 0.95 * double(in_blob)) << blob;
    EXPECT_GT(double(in_both), 0.95 * double(in_scene)) << blob;
  }
}

// An `sh` object is shaded by the scene as by prt_sh_shade in the blob mode: the same picture.
// Turned, the scene is handed the map with its rotation set where the blob mode turns the
// projection with prt_sh_rotate: the same light, so the same picture within a step.
TEST(PrtViewerScene, ShObjectLooksAsItsBlobDoes) {
  const std::string manifest = write_scene("sh_alone", {"sh_quad.prtk"}, {"sh_quad.prtk"});
  const std::string sky = prt_view_test::write_test_sky();
  const std::string blob = prt_view_test::golden("sh_quad.prtk");
  for (const char* turn : {"0", "90"}) {
    const std::string extra = std::string(kFixed) + " --rotate " + turn;
    const Picture scene = screenshot(manifest, sky, std::string("sh_scene_") + turn, extra);
    const Picture single = screenshot(blob, sky, std::string("sh_blob_") + turn, extra);
    const Difference d = difference(scene, single);
    std::printf("sh quad turned %s: scene vs blob mode: largest %d, %zu pixels differ\n", turn,
                d.largest, d.pixels);
    EXPECT_LE(d.largest, 1) << turn;
  }
}

// A right-drag of 40 pixels turns the light by 10 degrees (0.25 a pixel), as --rotate 10 does:
// the scene is handed the turned environment when the turn changes.
TEST(PrtViewerScene, RightDragTurnsTheSceneLightAsRotateDoes) {
  const std::string manifest = prt_view_test::golden("scene_quads.prts");
  const std::string sky = prt_view_test::write_test_sky();
  const std::string drag = scratch().write(
      "scene_right_drag.txt", "0 move 100 100\n0 press right\n1 move 140 100\n1 release right\n");
  const Picture dragged = screenshot(manifest, sky, "scene_light_dragged",
                                     std::string(kFixed) + " --input-script " + quote(drag));
  const Picture rotated =
      screenshot(manifest, sky, "scene_light_rotated", std::string(kFixed) + " --rotate 10");
  const Picture still = screenshot(manifest, sky, "scene_light_still", kFixed);
  const Difference same = difference(dragged, rotated), moved = difference(dragged, still);
  std::printf("scene: drag vs --rotate 10: largest %d; drag vs no drag: %zu pixels differ\n",
              same.largest, moved.pixels);
  EXPECT_LE(same.largest, 1);
  EXPECT_GT(moved.pixels, 1000u) << "the drag should have turned the light";
}

// On every backend the option offers: cpu and simd as asked, gl said once and shaded with auto.
TEST(PrtViewerScene, ShadesOnEveryBackendOption) {
  const std::string manifest = prt_view_test::golden("scene_quads.prts");
  std::vector<std::string> backends = {"auto", "cpu"};
  if (PRT_TEST_SIMD_COMPILED) backends.push_back("simd");
  if (PRT_TEST_GL_COMPILED) backends.push_back("gl");
  for (const std::string& backend : backends) {
    const std::string png = scratch().file("scene_backend_" + backend + ".png");
    const prt_test::CommandResult run =
        run_viewer(quote(manifest) + " --env " + quote(sun_map()) + " --backend " + backend +
                       " --size 160x120 --frames 2 --screenshot " + quote(png),
                   "scene_backend_" + backend);
    EXPECT_EQ(run.exit_code, 0) << backend << "\n" << run.output;
    if (backend == "gl") {
      EXPECT_NE(run.output.find("a scene shades on the CPU-side backends"), std::string::npos)
          << run.output;
    }
  }
}

// A manifest that is a blob under another name is still opened as a scene (its SCNE section
// says so); a scene is shown alone (exit 2 beside a second blob).
TEST(PrtViewerScene, ManifestUnderAnotherNameOpensAndAComparisonIsRefused) {
  const fs::path folder = fs::path(scratch().file("renamed"));
  fs::create_directories(folder);
  for (const char* blob : kGoldenBlobs)
    fs::copy_file(prt_view_test::golden(blob), folder / blob, fs::copy_options::overwrite_existing);
  fs::copy_file(prt_view_test::golden("scene_quads.prts"), folder / "scene.prtk",
                fs::copy_options::overwrite_existing);
  const prt_test::CommandResult run =
      run_viewer(quote((folder / "scene.prtk").string()) + " --env " + quote(sun_map()) +
                     " --size 160x120 --frames 1",
                 "scene_renamed");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("scene of 5 objects"), std::string::npos) << run.output;

  const prt_test::CommandResult two =
      run_viewer(quote(prt_view_test::golden("scene_quads.prts")) + " " +
                     quote(prt_view_test::golden("sh_quad.prtk")) + " --env " + quote(sun_map()),
                 "scene_two");
  EXPECT_EQ(two.exit_code, 2) << two.output;
}

// A missing blob fails the load: exit 1, and the message (the runtime's) names the blob.
TEST(PrtViewerScene, ManifestNamingAMissingBlobExitsOneNamingIt) {
  const std::string manifest =
      write_scene("missing", {"sh_quad.prtk", "props/lamp.prtk"}, {"sh_quad.prtk"});
  const prt_test::CommandResult run =
      run_viewer(quote(manifest) + " --env " + quote(sun_map()) + " --size 160x120 --frames 1",
                 "scene_missing");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("props/lamp.prtk"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("prt-viewer: " + manifest), std::string::npos) << run.output;
}

}  // namespace
