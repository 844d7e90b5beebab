// SPDX-License-Identifier: MIT
// prt-bake reference SCENE --env MAP: the Monte Carlo ground truth (per-vertex radiance and a
// camera image) every technique is measured against. Parses options and reports; the work is in
// prt/baker/reference.hpp.
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"
#include "prt/baker/reference.hpp"
#include "prt/baker/text.hpp"

namespace prt::bake::cli {
namespace {

struct ReferenceOptions {
  std::string scene, env, env_mapping = "auto", albedo, vertex_out, report, brdf = "lambert", eye;
  std::vector<std::string> image_outs;  // one render, written to each (.png and/or .hdr)
  std::string image_size = "640x480";
  ReferenceSettings settings;
  bool exposure_given = false;
  float exposure_ev = 0.0f;
  double env_rotate_degrees = 0.0;
};

void parse_image_size(const std::string& text, int* width, int* height) {
  char x = 0, rest = 0;
  std::istringstream in(text);
  if (!(in >> *width >> x >> *height) || (x != 'x' && x != 'X') || (in >> rest) || *width < 1 ||
      *height < 1 || *width > 16384 || *height > 16384) {
    throw Error("--image-size: expected WxH (e.g. 640x480), got '" + text + "'");
  }
}

glm::vec3 parse_eye(const std::string& text) {
  glm::vec3 p;
  char comma1 = 0, comma2 = 0, rest = 0;
  std::istringstream in(text);
  if (!(in >> p.x >> comma1 >> p.y >> comma2 >> p.z) || comma1 != ',' || comma2 != ',' ||
      (in >> rest) || !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
    throw Error("--eye: expected x,y,z (e.g. 0,1,5), got '" + text + "'");
  }
  return p;
}

// The image's camera: from the eye at the scene's centre when there is one, else framing it.
io::Camera image_camera(const EmbreeScene& rays, const std::optional<glm::vec3>& eye,
                        float aspect) {
  const glm::vec3 centre = 0.5f * (rays.bounds_lo() + rays.bounds_hi());
  if (eye && glm::length(*eye - centre) > 0.0f) {
    return io::Camera::look_at(*eye, centre, 40.0f, aspect);
  }
  return io::Camera::auto_frame(rays.bounds_lo(), rays.bounds_hi(), aspect);
}

std::string join(const std::vector<std::string>& paths) {
  std::string text;
  for (const std::string& path : paths) text += (text.empty() ? "" : ", ") + path;
  return text;
}

void run_reference(const ReferenceOptions& options, const CommandEnv& env) {
  const Context ctx = env.context();
  ReferenceSettings settings = options.settings;
  if (!options.albedo.empty()) {
    settings.override_albedo = true;
    settings.albedo = parse_albedo(options.albedo);
  }
  settings.brdf = parse_surface_brdf(options.brdf);
  std::optional<glm::vec3> eye;
  if (!options.eye.empty()) eye = parse_eye(options.eye);
  int width = 0, height = 0;
  parse_image_size(options.image_size, &width, &height);
  const io::EnvMapping mapping = io::parse_env_mapping(options.env_mapping);

  const Scene scene = import_scene(options.scene, ctx);
  io::EnvMap env_map = options.env.empty()
                           ? io::constant_envmap(glm::vec3(1.0f))
                           : io::load_envmap(options.env, mapping, ctx.io_messages());
  if (options.env.empty()) ctx.info("no --env: a constant white environment of radiance 1");
  env_map.set_rotation(io::rotation_about_y(options.env_rotate_degrees));
  const ReferenceRenderer renderer(scene, env_map, settings, ctx);

  ReferenceReport report;
  report.scene = options.scene;
  report.env = options.env.empty() ? "constant 1" : options.env;
  report.env_mapping = io::env_mapping_name(env_map.mapping());
  report.env_rotate_degrees = options.env_rotate_degrees;
  report.vertices = scene.vertex_count();
  report.triangles = scene.triangle_count();
  report.dropped_triangles = renderer.embree_scene().dropped_triangles();
  report.settings = settings;
  report.eye = eye;
  report.threads = ctx.thread_count();

  const bool want_vertices = !options.vertex_out.empty() || options.image_outs.empty();
  if (want_vertices) {
    VertexRadiance result = renderer.render_vertices(ctx, eye);
    ctx.info(std::to_string(scene.vertex_count()) + " vertices, " + std::to_string(settings.spp) +
             " spp, " + std::to_string(settings.bounces) + " bounces: " +
             format("estimated relative RMSE %.3f %% (two independent halves); ",
                    100.0 * result.relative_rmse) +
             format("%.3g rays in %.1f s (%.2f Mrays/s)", static_cast<double>(result.stats.rays),
                    result.stats.seconds, result.stats.rays_per_second() * 1e-6));
    if (!options.vertex_out.empty()) {
      io::write_npy_vec3(options.vertex_out, result.radiance);
      ctx.info("wrote " + options.vertex_out);
    }
    result.radiance.clear();
    report.has_vertices = true;
    report.vertex_result = std::move(result);
  }
  if (!options.image_outs.empty()) {
    const io::Camera camera =
        image_camera(renderer.embree_scene(), eye, static_cast<float>(width) / height);
    const io::LinearImage image =
        renderer.render_image(camera, width, height, ctx, &report.image_stats);
    const float ev = options.exposure_given ? options.exposure_ev : io::auto_exposure_ev(image);
    for (const std::string& path : options.image_outs) io::write_image(path, image, ev);
    ctx.info("wrote " + join(options.image_outs) + " (" + std::to_string(width) + "x" +
             std::to_string(height) + ", " + std::to_string(settings.image_spp) + " spp, " +
             format("exposure %+.2f EV, %.1f s)", ev, report.image_stats.seconds));
    report.has_image = true;
    report.image_width = width;
    report.image_height = height;
    report.exposure_ev = ev;
  }
  if (!options.report.empty()) {
    write_reference_report(options.report, report);
    ctx.info("wrote " + options.report);
  }
}

}  // namespace

void add_reference_command(CLI::App& app, CommandEnv& env) {
  auto options = std::make_shared<ReferenceOptions>();
  ReferenceSettings& s = options->settings;
  auto* cmd = app.add_subcommand(
      "reference", "Path-trace the ground truth: per-vertex outgoing radiance and a camera image");
  cmd->add_option("SCENE", options->scene, "Scene file (.gltf, .glb, .obj)")->required();
  cmd->add_option("--env", options->env,
                  "Environment map (.hdr); default: constant white of radiance 1");
  cmd->add_option("--env-mapping", options->env_mapping, "auto|latlong|cross|probe")
      ->capture_default_str();
  cmd->add_option("--env-rotate", options->env_rotate_degrees,
                  "Turn the environment about world +Y by DEG degrees (light from d comes from "
                  "R d, R = [[c,0,s],[0,1,0],[-s,0,c]], as prt_sh_rotate and prt-view --rotate)")
      ->check(CLI::Range(-1e6, 1e6))
      ->capture_default_str();
  cmd->add_option("--albedo", options->albedo,
                  "Diffuse albedo r,g,b for every surface "
                  "(default: from the materials)");
  cmd->add_option("--brdf", options->brdf,
                  "BRDF of every surface, times its albedo: lambert, phong:N[,specular[,diffuse]] "
                  "or ggx:ALPHA[,F0]")
      ->capture_default_str();
  cmd->add_option("--eye", options->eye,
                  "Eye position x,y,z: vertex radiance towards it (default: along each normal) "
                  "and the image's viewpoint");
  cmd->add_option("--bounces", s.bounces, "Indirect bounces (0 = direct light with visibility)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  cmd->add_option("--spp", s.spp, "Samples per vertex (>= 2)")
      ->check(CLI::Range(2u, 1u << 30))
      ->capture_default_str();
  cmd->add_option("--seed", s.seed, "Random seed (same seed, same result, any thread count)")
      ->capture_default_str();
  cmd->add_option("--vertex-out", options->vertex_out,
                  "Write per-vertex linear radiance, float32 [V,3], as .npy");
  cmd->add_option("--image-out", options->image_outs,
                  "Write a camera image: .png (tone-mapped sRGB) or .hdr (linear); repeat the "
                  "flag to write one render to several files")
      ->allow_extra_args(false);
  cmd->add_option("--image-size", options->image_size, "Image size WxH")->capture_default_str();
  cmd->add_option("--image-spp", s.image_spp, "Samples per pixel")
      ->check(CLI::Range(1u, 1u << 20))
      ->capture_default_str();
  cmd->add_option("--exposure", options->exposure_ev, "Exposure in EV (default: automatic)")
      ->each([options](const std::string&) { options->exposure_given = true; });
  cmd->add_option("--report", options->report,
                  "Write a JSON report (settings, rays, seconds, rays/s, estimated noise)");
  cmd->callback([&env, options] { run_reference(*options, env); });
}

}  // namespace prt::bake::cli
