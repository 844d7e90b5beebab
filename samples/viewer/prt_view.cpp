// SPDX-License-Identifier: MIT
// prt-view: draws a blob lit by an environment map with vertex colours shaded by the runtime,
// through the technique the blob holds (view_techniques.hpp; the table is techniques.cpp).
// Headless for now (a small CPU rasteriser writes the image; the windowed GLFW viewer comes
// later). Exit status: 0 ok, 1 failure (the message names the file and the problem), 2 bad
// arguments.
//
//   prt-view BLOB --env MAP --headless --out IMG.png [--rotate DEG] [--backend auto|cpu|simd|gl]
//            [--vertex-out V.npy] [--reference REF.npy --error-out HEAT.png] [--frames N]
//            [--frame-bounds X0,Y0,Z0,X1,Y1,Z1] [--turn-frames N (--out with %d)]
//            [--technique NAME] [technique options, e.g. --light-coefficients M] ...
//   prt-view BLOB --env MAP --headless --radiance-in V.npy --out IMG.png ...  (given radiance)
//   prt-view --montage OUT.png --montage-columns N [--montage-labels A,B] [--montage-caption T]
//            IMG.png...   (tiles PNGs, for the demo)
//   prt-view --animation OUT.png --montage-columns N [--frame-ms MS] IMG.png...  (an APNG)
#include <prt/prt.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "blob_scene.hpp"
#include "compare.hpp"
#include "env_image.hpp"
#include "prt/io/apng.hpp"
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
  std::string reference, error_out, montage, animation, radiance_in, frame_bounds;
  std::string labels, caption;  // --montage-labels, --montage-caption
  double rotate_degrees = 0.0;
  bool headless = false, exposure_given = false;
  float exposure_ev = 0.0f, error_scale = 0.25f;
  int frames = 1, supersample = 2, montage_columns = 3, turn_frames = 1, frame_ms = 100;
  int width = 0, height = 0;      // from --size
  std::array<float, 6> bounds{};  // from --frame-bounds: lo xyz, hi xyz
};

void parse_size(const std::string& text, int* width, int* height) {
  char x = 0, rest = 0;
  std::istringstream in(text);
  if (!(in >> *width >> x >> *height) || (x != 'x' && x != 'X') || (in >> rest) || *width < 1 ||
      *height < 1 || *width > 16384 || *height > 16384) {
    throw CLI::ValidationError("--size", "expected WxH (e.g. 640x480), got '" + text + "'");
  }
}

void parse_bounds(const std::string& text, std::array<float, 6>* bounds) {
  std::istringstream in(text);
  char comma = 0, rest = 0;
  bool ok = true;
  for (int i = 0; i < 6 && ok; ++i) {
    ok = static_cast<bool>(in >> (*bounds)[i]) && std::isfinite((*bounds)[i]) &&
         (i == 5 || ((in >> comma) && comma == ','));
  }
  for (int i = 0; i < 3 && ok; ++i) ok = (*bounds)[i] <= (*bounds)[i + 3];
  if (!ok || (in >> rest)) {
    throw CLI::ValidationError(
        "--frame-bounds",
        "expected X0,Y0,Z0,X1,Y1,Z1 with X0 <= X1, Y0 <= Y1, Z0 <= Z1, got '" + text + "'");
  }
}

// One %d field (with an optional zero-padded width, e.g. %03d) and no other %.
bool is_frame_pattern(const std::string& path) {
  const std::size_t at = path.find('%');
  if (at == std::string::npos || path.find('%', at + 1) != std::string::npos) return false;
  std::size_t i = at + 1;
  while (i < path.size() && std::isdigit(static_cast<unsigned char>(path[i]))) ++i;
  return i < path.size() && path[i] == 'd' && i - at <= 3;
}

std::string frame_path(const std::string& pattern, int frame) {
  std::vector<char> text(pattern.size() + 32);
  std::snprintf(text.data(), text.size(), pattern.c_str(), frame);
  return text.data();
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

prt::io::Camera frame_camera(const Options& options, const RasterMesh& mesh) {
  const float aspect = static_cast<float>(options.width) / options.height;
  if (!options.frame_bounds.empty()) {
    const glm::vec3 lo(options.bounds[0], options.bounds[1], options.bounds[2]);
    const glm::vec3 hi(options.bounds[3], options.bounds[4], options.bounds[5]);
    return prt::io::Camera::frame_box(lo, hi, aspect);
  }
  glm::vec3 lo, hi;
  triangle_bounds(mesh, &lo, &hi);
  return prt::io::Camera::auto_frame(lo, hi, aspect);
}

// --radiance-in: per-vertex radiance computed elsewhere (e.g. prt-bake reference), drawn as is.
std::vector<glm::vec3> given_radiance(const Options& options, const BlobScene& scene) {
  std::vector<glm::vec3> radiance = prt::io::read_npy_vec3(options.radiance_in);
  if (radiance.size() != scene.vertex_count()) {
    throw ViewerError(options.radiance_in + ": " + std::to_string(radiance.size()) +
                      " vertices, the blob has " + std::to_string(scene.vertex_count()));
  }
  std::printf("radiance: %s (%zu vertices, not shaded by the runtime)\n",
              options.radiance_in.c_str(), radiance.size());
  return radiance;
}

// The technique's light for the map turned by `rotate_degrees`, and every vertex shaded.
std::vector<glm::vec3> shade(const Options& options, const BlobScene& scene,
                             ViewTechnique& technique, const prt::io::EnvMap& map,
                             double rotate_degrees, int frames) {
  technique.prepare_light(scene, {&map, options.env, rotate_degrees});
  const ShadingRun run = shade_vertices(scene, technique, parse_backend(options.backend), frames);
  std::printf("shading: backend %s (%s), %zu frame(s), median %.4f ms per frame (%u vertices)\n",
              run.backend.c_str(), run.isa.c_str(), run.frame_ms.size(), run.median_ms,
              scene.vertex_count());
  return as_vec3(run.radiance);
}

// Draws `shaded` with the environment turned by `rotate_degrees` behind it and writes `path`;
// returns the exposure used (metered on this image unless given).
float write_view(const Options& options, const std::string& path, const prt::io::Camera& camera,
                 const RasterMesh& mesh, prt::io::EnvMap& map, double rotate_degrees,
                 const std::vector<glm::vec3>& shaded, bool exposure_given, float exposure_ev) {
  // The background is the environment as the reference renderer shows it (turned the same
  // way), so the two images differ only where the shading does.
  map.set_rotation(prt::io::rotation_about_y(rotate_degrees));
  const prt::io::LinearImage image =
      render_mesh(camera, options.width, options.height, options.supersample, mesh, shaded.data(),
                  [&](const glm::vec3& dir) { return map.radiance(dir); });
  map.set_rotation(glm::mat3(1.0f));  // the techniques turn the light themselves
  const float ev = exposure_given ? exposure_ev : prt::io::auto_exposure_ev(image);
  prt::io::write_image(path, image, ev);
  std::printf("wrote %s (%dx%d, exposure %+.2f EV)\n", path.c_str(), options.width, options.height,
              ev);
  return ev;
}

// --turn-frames N: the light turned a full circle in N steps from --rotate, one image each. The
// exposure of the first holds for all, so brightness changes as the light turns.
void write_turning(const Options& options, const BlobScene& scene, ViewTechnique& technique,
                   prt::io::EnvMap& map, const prt::io::Camera& camera, const RasterMesh& mesh) {
  bool exposure_given = options.exposure_given;
  float ev = options.exposure_ev;
  for (int k = 0; k < options.turn_frames; ++k) {
    const double degrees = options.rotate_degrees + 360.0 * k / options.turn_frames;
    const std::vector<glm::vec3> shaded = shade(options, scene, technique, map, degrees, 1);
    ev = write_view(options, frame_path(options.out, k), camera, mesh, map, degrees, shaded,
                    exposure_given, ev);
    exposure_given = true;
  }
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  return parts;
}

// `text` with its lines broken at spaces so each fits `width` pixels at `scale`.
std::string wrapped(const std::string& text, int width, int scale) {
  std::string out;
  for (const std::string& line : split(text, '\n')) {
    std::string current;
    for (const std::string& word : split(line, ' ')) {
      const std::string longer = current.empty() ? word : current + " " + word;
      if (!current.empty() && prt::io::text_width(longer, scale) > width) {
        out += current + "\n";
        current = word;
      } else {
        current = longer;
      }
    }
    out += current + "\n";
  }
  if (!out.empty()) out.pop_back();
  return out;
}

// The montage with a row of column labels above the tiles and the caption below (wrapped to the
// montage's width), white on black; a font pixel is 1/90 of the tile height (at least 1 pixel),
// or less where a label would not fit its column.
prt::io::Rgb8Image labelled(const prt::io::Rgb8Image& tiles, int tile_width, int tile_height,
                            int gap, const Options& options) {
  const std::vector<std::string> labels = split(options.labels, ',');
  // One text size, smaller where a label would be wider than its column.
  int scale = std::max(1, tile_height / 90);
  for (const std::string& label : labels) {
    while (scale > 1 && prt::io::text_width(label, scale) > tile_width - 2) --scale;
  }
  const int label_strip = labels.empty() ? 0 : 12 * scale;
  const std::string caption = wrapped(options.caption, tiles.width - 6 * scale, scale);
  const int caption_strip = caption.empty() ? 0 : prt::io::text_height(caption, scale) + 6 * scale;
  prt::io::Rgb8Image out;
  out.width = tiles.width;
  out.height = label_strip + tiles.height + caption_strip;
  out.rgb.assign(static_cast<std::size_t>(out.width) * out.height * 3, 0);
  std::copy(tiles.rgb.begin(), tiles.rgb.end(),
            out.rgb.begin() + static_cast<std::ptrdiff_t>(label_strip) * out.width * 3);
  const std::uint8_t white[3] = {255, 255, 255};
  for (std::size_t c = 0; c < labels.size(); ++c) {
    const int centre = static_cast<int>(c) * (tile_width + gap) + tile_width / 2;
    prt::io::draw_text(out, centre - prt::io::text_width(labels[c], scale) / 2, 3 * scale, scale,
                       labels[c], white);
  }
  if (!caption.empty())
    prt::io::draw_text(out, 3 * scale, label_strip + tiles.height + 3 * scale, scale, caption,
                       white);
  return out;
}

constexpr int kGap = 4;  // black pixels between tiles

void write_montage(const Options& options) {
  if (options.labels.empty() && options.caption.empty()) {
    prt::io::write_montage(options.montage, options.inputs, options.montage_columns, kGap);
  } else {
    std::vector<prt::io::Rgb8Image> tiles;
    for (const std::string& path : options.inputs) tiles.push_back(prt::io::read_rgb8(path));
    const prt::io::Rgb8Image grid = prt::io::tile_rgb8(tiles, options.montage_columns, kGap);
    prt::io::write_rgb8_png(options.montage,
                            labelled(grid, tiles[0].width, tiles[0].height, kGap, options));
  }
  std::printf("wrote %s (%zu images, %d per row)\n", options.montage.c_str(), options.inputs.size(),
              options.montage_columns);
}

// Tiles each run of --montage-columns inputs into one frame of an animated PNG, labelled and
// captioned as a montage.
void write_animation(const Options& options) {
  const std::size_t per_frame = static_cast<std::size_t>(options.montage_columns);
  if (options.inputs.size() % per_frame != 0) {
    throw ViewerError(options.animation + ": " + std::to_string(options.inputs.size()) +
                      " images do not make whole frames of " + std::to_string(per_frame));
  }
  std::vector<prt::io::Rgb8Image> frames;
  for (std::size_t first = 0; first < options.inputs.size(); first += per_frame) {
    std::vector<prt::io::Rgb8Image> tiles;
    for (std::size_t i = first; i < first + per_frame; ++i)
      tiles.push_back(prt::io::read_rgb8(options.inputs[i]));
    const prt::io::Rgb8Image grid = prt::io::tile_rgb8(tiles, options.montage_columns, kGap);
    const bool text = !options.labels.empty() || !options.caption.empty();
    frames.push_back(text ? labelled(grid, tiles[0].width, tiles[0].height, kGap, options) : grid);
  }
  prt::io::write_apng(options.animation, frames, options.frame_ms);
  std::printf("wrote %s (%zu frames of %dx%d, %d ms each)\n", options.animation.c_str(),
              frames.size(), frames[0].width, frames[0].height, options.frame_ms);
}

int run(const Options& options, const ViewTechniques& techniques, const CLI::App& app) {
  if (!options.montage.empty()) {
    write_montage(options);
    return 0;
  }
  if (!options.animation.empty()) {
    write_animation(options);
    return 0;
  }

  const BlobScene scene(options.inputs.front());
  const prt::io::MessageHook warnings = [](prt::io::MessageLevel level, const std::string& text) {
    if (level == prt::io::MessageLevel::Warning)
      std::fprintf(stderr, "prt-view: %s\n", text.c_str());
  };
  prt::io::EnvMap map =
      prt::io::load_envmap(options.env, prt::io::parse_env_mapping(options.env_mapping), warnings);
  const RasterMesh mesh = raster_mesh(scene.mesh());
  const prt::io::Camera camera = frame_camera(options, mesh);

  std::vector<glm::vec3> shaded;
  if (!options.radiance_in.empty()) {
    shaded = given_radiance(options, scene);
  } else {
    ViewTechnique& technique = techniques.choose(scene);
    techniques.warn_unused_options(app, technique);
    scene.check_shaded_vertices(technique.section_tag(), technique.open(scene));
    technique.set_eye(&camera.eye.x);
    technique.describe(scene);
    if (options.turn_frames > 1) {
      write_turning(options, scene, technique, map, camera, mesh);
      return 0;
    }
    shaded = shade(options, scene, technique, map, options.rotate_degrees, options.frames);
  }
  if (!options.vertex_out.empty()) {
    prt::io::write_npy_vec3(options.vertex_out, shaded);
    std::printf("wrote %s\n", options.vertex_out.c_str());
  }
  if (!options.reference.empty())
    compare_with_reference(options, shaded, camera, options.width, options.height, mesh);
  if (!options.out.empty()) {
    write_view(options, options.out, camera, mesh, map, options.rotate_degrees, shaded,
               options.exposure_given, options.exposure_ev);
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
  app.add_option("--radiance-in", o.radiance_in,
                 "Draw this per-vertex radiance (float32 [V,3] .npy, e.g. prt-bake reference "
                 "--vertex-out) instead of shading with the runtime; the blob gives the mesh");
  app.add_option("--frame-bounds", o.frame_bounds,
                 "Frame the box X0,Y0,Z0,X1,Y1,Z1 so it fills the image (default: the bounding "
                 "sphere of the whole mesh, as prt-bake reference frames it)");
  app.add_option("--turn-frames", o.turn_frames,
                 "Write N images, the light turned a full circle from --rotate; --out names "
                 "them with one %d field (e.g. turn_%03d.png); one exposure for all")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--montage", o.montage, "Tile the INPUT PNGs into this PNG and exit");
  app.add_option("--montage-labels", o.labels,
                 "Comma-separated labels written above the columns of --montage or --animation");
  app.add_option("--montage-caption", o.caption,
                 "Text written below --montage or each --animation frame (\\n starts a line)")
      ->transform([](std::string text) {
        for (std::size_t at; (at = text.find("\\n")) != std::string::npos;)
          text.replace(at, 2, "\n");
        return text;
      });
  app.add_option("--animation", o.animation,
                 "Write an animated PNG of the INPUT PNGs and exit: each --montage-columns of "
                 "them side by side make one frame");
  app.add_option("--frame-ms", o.frame_ms, "Time per frame of --animation in milliseconds")
      ->check(CLI::Range(1, 65535))
      ->capture_default_str();
  app.add_option("--montage-columns", o.montage_columns,
                 "Tiles per row of --montage; images per frame of --animation")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
}

// Rules CLI11 cannot express as single-option checks.
void check_combination(Options& o) {
  if (!o.montage.empty() && !o.animation.empty())
    throw CLI::ValidationError("--animation", "give --montage or --animation, not both");
  if (!o.montage.empty() || !o.animation.empty()) return;
  parse_size(o.size, &o.width, &o.height);
  if (!o.frame_bounds.empty()) parse_bounds(o.frame_bounds, &o.bounds);
  if (o.turn_frames > 1) {
    if (!o.radiance_in.empty())
      throw CLI::ValidationError("--turn-frames", "turns the light: not with --radiance-in");
    if (!is_frame_pattern(o.out)) {
      throw CLI::ValidationError(
          "--turn-frames", "--out must name the images with one %d field, e.g. turn_%03d.png");
    }
    if (!o.vertex_out.empty() || !o.reference.empty())
      throw CLI::ValidationError("--turn-frames",
                                 "writes images only: no --vertex-out or "
                                 "--reference");
  }
  if (o.inputs.size() != 1) throw CLI::ValidationError("INPUT", "expected exactly one blob");
  if (o.env.empty()) throw CLI::RequiredError("--env");
  if (!o.headless) {
    throw CLI::ValidationError("--headless",
                               "the windowed viewer is not built yet: pass --headless");
  }
  if (o.out.empty() && o.vertex_out.empty() && o.reference.empty() &&
      (o.frames <= 1 || !o.radiance_in.empty())) {
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
