// SPDX-License-Identifier: MIT
// prt-view: draws a blob lit by an environment map with vertex colours shaded by the runtime,
// through the technique the blob holds (view_techniques.hpp; the table is techniques.cpp).
// Headless for now (a small CPU rasteriser writes the image; the windowed GLFW viewer comes
// later). Exit status: 0 ok, 1 failure (the message names the file and the problem), 2 bad
// arguments.
//
//   prt-view BLOB --env MAP --headless --out IMG.png [--rotate DEG] [--backend auto|cpu|simd|gl]
//            [--vertex-out V.npy] [--reference REF.npy --error-out HEAT.png] [--frames N]
//            [--technique NAME] [technique options, e.g. --light-coefficients M] ...
//   prt-view --montage OUT.png --montage-columns N IMG.png...   (tiles PNGs, for the demo)
#include <prt/prt.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "blob_scene.hpp"
#include "compare.hpp"
#include "env_image.hpp"
#include "prt/io/envmap.hpp"
#include "prt/io/image_io.hpp"
#include "prt/io/radiance_error.hpp"
#include "rasterizer.hpp"
#include "vertex_shading.hpp"
#include "view_techniques.hpp"

namespace prt::view {
namespace {

struct Options {
  std::vector<std::string> inputs;  // the blob, or the montage's images
  std::string env, env_mapping = "auto", backend = "auto", out, vertex_out, size = "640x480";
  std::string reference, error_out, montage;
  double rotate_degrees = 0.0;
  bool headless = false, exposure_given = false;
  float exposure_ev = 0.0f, error_scale = 0.25f;
  int frames = 1, supersample = 2, montage_columns = 3;
  int width = 0, height = 0;  // from --size
};

void parse_size(const std::string& text, int* width, int* height) {
  char x = 0, rest = 0;
  std::istringstream in(text);
  if (!(in >> *width >> x >> *height) || (x != 'x' && x != 'X') || (in >> rest) || *width < 1 ||
      *height < 1 || *width > 16384 || *height > 16384) {
    throw CLI::ValidationError("--size", "expected WxH (e.g. 640x480), got '" + text + "'");
  }
}

std::vector<glm::vec3> as_vec3(const std::vector<float>& rgb) {
  std::vector<glm::vec3> values(rgb.size() / 3);
  for (std::size_t v = 0; v < values.size(); ++v) {
    values[v] = {rgb[3 * v], rgb[3 * v + 1], rgb[3 * v + 2]};
  }
  return values;
}

RasterMesh raster_mesh(const BlobMesh& mesh) {
  return {mesh.positions, mesh.vertex_count, mesh.indices, mesh.triangle_count};
}

// The comparison with --reference: prints the error and draws the heat map.
void compare_with_reference(const Options& options, const std::vector<glm::vec3>& shaded,
                            const prt::io::Camera& camera, int width, int height,
                            const RasterMesh& mesh) {
  const std::vector<glm::vec3> reference = prt::io::read_npy_vec3(options.reference);
  if (reference.size() != shaded.size()) {
    throw ViewerError(options.reference + ": " + std::to_string(reference.size()) +
                      " vertices, the blob has " + std::to_string(shaded.size()));
  }
  const double error = prt::io::relative_rmse(shaded, reference);
  std::printf("error vs %s: relative RMSE %.5f (%.2f %%)\n", options.reference.c_str(), error,
              100.0 * error);
  if (options.error_out.empty()) return;
  const std::vector<float> vertex_error = relative_vertex_error(shaded, reference);
  std::vector<glm::vec3> colours(vertex_error.size());
  for (std::size_t v = 0; v < colours.size(); ++v) {
    colours[v] = heat_colour(vertex_error[v], options.error_scale);
  }
  const glm::vec3 backdrop(0.25f);  // mid grey: tells "no surface" from "no error" (black)
  const prt::io::LinearImage heat =
      render_mesh(camera, width, height, options.supersample, mesh, colours.data(),
                  [&](const glm::vec3&) { return backdrop; });
  prt::io::write_display_png(options.error_out, heat);
  std::printf(
      "wrote %s: per-vertex |x - ref| / mean |ref|, colour scale 0 (black) .. %.3g (white): "
      "black, blue, magenta, orange, yellow, white\n",
      options.error_out.c_str(), options.error_scale);
}

int run(const Options& options, const ViewTechniques& techniques, const CLI::App& app) {
  if (!options.montage.empty()) {
    prt::io::write_montage(options.montage, options.inputs, options.montage_columns, 4);
    std::printf("wrote %s (%zu images, %d per row)\n", options.montage.c_str(),
                options.inputs.size(), options.montage_columns);
    return 0;
  }
  const int width = options.width, height = options.height;
  const ViewBackend backend = parse_backend(options.backend);

  const BlobScene scene(options.inputs.front());
  ViewTechnique& technique = techniques.choose(scene);
  techniques.warn_unused_options(app, technique);
  scene.check_shaded_vertices(technique.section_tag(), technique.open(scene));
  const prt::io::MessageHook warnings = [](prt::io::MessageLevel level, const std::string& text) {
    if (level == prt::io::MessageLevel::Warning)
      std::fprintf(stderr, "prt-view: %s\n", text.c_str());
  };
  prt::io::EnvMap map =
      prt::io::load_envmap(options.env, prt::io::parse_env_mapping(options.env_mapping), warnings);
  technique.describe(scene);
  technique.prepare_light(scene, {&map, options.env, options.rotate_degrees});
  const ShadingRun run = shade_vertices(scene, technique, backend, options.frames);
  std::printf("shading: backend %s (%s), %zu frame(s), median %.4f ms per frame (%u vertices)\n",
              run.backend.c_str(), run.isa.c_str(), run.frame_ms.size(), run.median_ms,
              scene.vertex_count());
  const std::vector<glm::vec3> shaded = as_vec3(run.radiance);
  if (!options.vertex_out.empty()) {
    prt::io::write_npy_vec3(options.vertex_out, shaded);
    std::printf("wrote %s\n", options.vertex_out.c_str());
  }

  const RasterMesh mesh = raster_mesh(scene.mesh());
  glm::vec3 lo, hi;
  triangle_bounds(mesh, &lo, &hi);
  const prt::io::Camera camera =
      prt::io::Camera::auto_frame(lo, hi, static_cast<float>(width) / height);
  if (!options.reference.empty())
    compare_with_reference(options, shaded, camera, width, height, mesh);

  if (!options.out.empty()) {
    // The background is the environment as the reference renderer shows it (turned the same
    // way), so the two images differ only where the shading does.
    map.set_rotation(prt::io::rotation_about_y(options.rotate_degrees));
    const prt::io::LinearImage image =
        render_mesh(camera, width, height, options.supersample, mesh, shaded.data(),
                    [&](const glm::vec3& dir) { return map.radiance(dir); });
    const float ev =
        options.exposure_given ? options.exposure_ev : prt::io::auto_exposure_ev(image);
    prt::io::write_image(options.out, image, ev);
    std::printf("wrote %s (%dx%d, exposure %+.2f EV)\n", options.out.c_str(), width, height, ev);
  }
  return 0;
}

void add_options(CLI::App& app, Options& o) {
  app.add_option("INPUT", o.inputs, "The baked blob (.prtk); with --montage, the PNGs to tile")
      ->required();
  app.add_option("--env", o.env, "Environment map (.hdr): lat-long, vertical cross or probe");
  app.add_option("--env-mapping", o.env_mapping, "auto|latlong|cross|probe")
      ->check(CLI::IsMember({"auto", "latlong", "cross", "probe"}))
      ->capture_default_str();
  app.add_option("--rotate", o.rotate_degrees,
                 "Turn the light about world +Y by DEG degrees (light from d comes from R d, "
                 "R = [[c,0,s],[0,1,0],[-s,0,c]], formats/SPEC.md; as prt-bake reference "
                 "--env-rotate)")
      ->check(CLI::Range(-1e6, 1e6))
      ->capture_default_str();
  app.add_option("--backend", o.backend, "auto|cpu|simd|gl (auto: the runtime's best CPU backend)")
      ->check(CLI::IsMember({"auto", "cpu", "simd", "gl"}))
      ->capture_default_str();
  app.add_flag("--headless", o.headless, "Render to files without a window (required for now)");
  app.add_option("--out", o.out, "Image to write: .png (tone-mapped sRGB) or .hdr (linear)");
  app.add_option("--vertex-out", o.vertex_out,
                 "Write per-vertex radiance, float32 [V,3] .npy (as prt-bake reference)");
  app.add_option("--size", o.size, "Image size WxH")->capture_default_str();
  app.add_option("--exposure", o.exposure_ev,
                 "Exposure in EV (default: automatic, as the "
                 "reference renderer meters)")
      ->each([&o](const std::string&) { o.exposure_given = true; });
  app.add_option("--supersample", o.supersample, "Samples per pixel along each axis")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  app.add_option("--reference", o.reference,
                 "prt-bake reference --vertex-out of the same scene: print the relative RMSE");
  app.add_option("--error-out", o.error_out, "With --reference: write an error heat map (.png)");
  app.add_option("--error-scale", o.error_scale,
                 "Heat map: relative error shown as white (default 0.25 = 25 % of the mean)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--frames", o.frames, "Shade N times and print the median time per frame")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--montage", o.montage, "Tile the INPUT PNGs into this PNG and exit");
  app.add_option("--montage-columns", o.montage_columns, "Tiles per row of --montage")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
}

// Rules CLI11 cannot express as single-option checks.
void check_combination(Options& o) {
  if (!o.montage.empty()) return;
  parse_size(o.size, &o.width, &o.height);
  if (o.inputs.size() != 1) throw CLI::ValidationError("INPUT", "expected exactly one blob");
  if (o.env.empty()) throw CLI::RequiredError("--env");
  if (!o.headless) {
    throw CLI::ValidationError("--headless",
                               "the windowed viewer is not built yet: pass --headless");
  }
  if (o.out.empty() && o.vertex_out.empty() && o.reference.empty() && o.frames <= 1) {
    throw CLI::ValidationError("--out",
                               "nothing to do: give --out, --vertex-out, --reference "
                               "or --frames");
  }
  if (!o.error_out.empty() && o.reference.empty()) {
    throw CLI::ValidationError("--error-out", "needs --reference");
  }
}

}  // namespace
}  // namespace prt::view

int main(int argc, char** argv) {
  CLI::App app{
      "prt-view: a blob shaded by the prtkit runtime under an environment map "
      "(prtkit " PRT_VERSION_STRING ")"};
  prt::view::Options options;
  prt::view::add_options(app, options);
  try {
    prt::view::ViewTechniques techniques;
    app.footer("Techniques: " + techniques.names() +
               ". A blob holding several is drawn with the first of them unless --technique "
               "picks another; each technique's own options are listed under its name.");
    techniques.add_options(app);
    try {
      app.parse(argc, argv);
      prt::view::check_combination(options);
    } catch (const CLI::ParseError& e) {
      const int code = app.exit(e);
      return code == 0 ? 0 : 2;
    }
    return prt::view::run(options, techniques, app);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt-view: %s\n", e.what());
    return 1;
  }
}
