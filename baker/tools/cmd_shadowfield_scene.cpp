// SPDX-License-Identifier: MIT
// The `shadowfield` scenes on the command line (docs/shadowfield/scenes.md, accuracy.md):
//   shadowfield-scene NAME -o DIR       bakes every object of a preset, writes DIR/scene.json;
//   shadowfield-reference SCENE.json    the path-traced per-vertex radiance at a time (.npy);
//   shadowfield-measure SCENE.json      the runtime against the reference per bounce count.
// The reference rebuilds the preset's meshes and exact BRDFs by the file's name: the blobs hold
// the meshes but only the separated BRDF, and the ground truth must not depend on the bake.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"
#include "prt/baker/shadowfield/shadowfield_bake.hpp"
#include "prt/baker/shadowfield/shadowfield_measure.hpp"
#include "prt/baker/text.hpp"
#include "prt/io/image_io.hpp"

namespace prt::bake::cli {
namespace {

namespace fs = std::filesystem;

// Writes through `write` to a temporary name beside `path`, then renames it: a reader never sees
// a half-written file.
template <typename Write>
void write_then_rename(const std::string& path, Write write) {
  const std::string temporary = path + ".partial";
  write(temporary);
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error) throw Error("renaming " + temporary + " to " + path + ": " + error.message());
}

void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!out) throw Error("cannot write " + path);
}

std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read " + path);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in),
                                   std::istreambuf_iterator<char>());
}

glm::vec3 parse_point(const std::string& text) {
  glm::vec3 p;
  char comma1 = 0, comma2 = 0, rest = 0;
  std::istringstream in(text);
  if (!(in >> p.x >> comma1 >> p.y >> comma2 >> p.z) || comma1 != ',' || comma2 != ',' ||
      (in >> rest) || !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
    throw Error("--eye: expected x,y,z (e.g. 0,1,5), got '" + text + "'");
  }
  return p;
}

// ---- shadowfield-scene ---------------------------------------------------------------------

struct SceneOptions {
  std::string name, dir, shared = "../shared";
  ShadowfieldBakeSettings bake;
  std::uint32_t rays = 1024;  // the fields' and transfer's directions per point
};

void run_shadowfield_scene(const SceneOptions& options, const CommandEnv& env) {
  const Context ctx = env.context();
  ShadowfieldBakeSettings settings = options.bake;
  settings.fields.field_directions = settings.fields.transfer_rays = options.rays;
  settings.srf.directions = options.rays;
  check_shadowfield_bake_settings(settings);
  const ShadowfieldSceneDescription description =
      make_shadowfield_scene(options.name, options.shared);
  fs::create_directories(options.dir);
  std::vector<std::string> blob_names;
  std::uint64_t total_bytes = 0;
  for (std::size_t o = 0; o < description.objects.size(); ++o) {
    const ShadowfieldSceneObject& object = description.objects[o];
    ctx.info(format("[%zu/%zu] baking %s (%zu vertices)", o + 1, description.objects.size(),
                    object.name.c_str(), object.mesh.vertex_count()));
    const ShadowfieldBakeResult baked = bake_shadowfield_object(
        object.mesh, make_shadowfield_material(object.material, settings.brdf), settings, ctx);
    const std::vector<std::uint8_t> blob = shadowfield_blob_of(
        baked.object, settings.bits, "shadowfield scene " + description.name + ": " + object.name);
    const std::string blob_name = object.name + ".prtk";
    write_then_rename(options.dir + "/" + blob_name,
                      [&](const std::string& path) { write_bytes(path, blob); });
    blob_names.push_back(blob_name);
    total_bytes += blob.size();
    ctx.info(format("  %s: %zu bytes (fields %.1f s, transfer %.1f s)", blob_name.c_str(),
                    blob.size(), baked.seconds_fields, baked.seconds_transfer));
  }
  const std::string json = options.dir + "/scene.json";
  write_then_rename(json, [&](const std::string& path) {
    write_shadowfield_scene_json(description, blob_names, path);
  });
  ctx.info(format("wrote %s and %zu blobs, %.2f MB in all (%zu instanced vertices)", json.c_str(),
                  blob_names.size(), double(total_bytes) * 1e-6,
                  description.instanced_vertex_count()));
}

void add_scene_subcommand(CLI::App& app, CommandEnv& env) {
  auto options = std::make_shared<SceneOptions>();
  ShadowfieldBakeSettings& s = options->bake;
  auto* cmd = app.add_subcommand(
      "shadowfield-scene", "Bake every object of a shadowfield preset and write its scene.json");
  cmd->add_option("NAME", options->name, "Preset: teapot, bunny, room or procedural")->required();
  cmd->add_option("-o,--out", options->dir, "Output folder (created if missing)")->required();
  cmd->add_option("--shared", options->shared, "The shared assets folder")->capture_default_str();
  cmd->add_option("--bits", s.bits, "Quantisation of the blobs, 8 or 16")->capture_default_str();
  cmd->add_option("--order", s.fields.order, "SH order n, 2..6")->capture_default_str();
  cmd->add_option("--basis", s.basis.size, "Surface-radiance basis size N")->capture_default_str();
  cmd->add_option("--lights", s.basis.lights, "Training lights of the basis")
      ->capture_default_str();
  cmd->add_option("--terms", s.brdf.terms, "BRDF terms K of glossy materials")
      ->capture_default_str();
  cmd->add_option("--rays", options->rays, "Directions per field point and per vertex")
      ->capture_default_str();
  cmd->add_option("--oof-shells", s.fields.oof_shells, "Occlusion field shells")
      ->capture_default_str();
  cmd->add_option("--oof-face", s.fields.oof_face_size, "Occlusion field cube face size")
      ->capture_default_str();
  cmd->add_option("--srf-shells", s.srf.shells, "Source radiance field shells")
      ->capture_default_str();
  cmd->add_option("--srf-face", s.srf.face_size, "Source radiance field cube face size")
      ->capture_default_str();
  cmd->callback([options, &env] { run_shadowfield_scene(*options, env); });
}

// ---- the scene file back: description, environment, blobs -----------------------------------

struct LoadedScene {
  ShadowfieldSceneDescription description;
  std::vector<std::string> blob_paths;
};

// The preset the file names (meshes, exact materials), with the file's instances, camera and
// environment. Throws Error when the file's objects are not the preset's.
LoadedScene load_scene_file(const std::string& json, const std::string& shared) {
  const ShadowfieldSceneFile file = read_shadowfield_scene_json(json);
  LoadedScene loaded;
  loaded.description = make_shadowfield_scene(file.name, shared);
  ShadowfieldSceneDescription& d = loaded.description;
  if (d.objects.size() != file.objects.size())
    throw Error(json + ": " + std::to_string(file.objects.size()) + " objects, the preset " +
                file.name + " has " + std::to_string(d.objects.size()));
  const fs::path folder = fs::path(json).parent_path();
  for (std::size_t o = 0; o < d.objects.size(); ++o) {
    if (d.objects[o].name != file.objects[o].name)
      throw Error(json + ": object " + std::to_string(o) + " is " + file.objects[o].name +
                  ", the preset's is " + d.objects[o].name);
    loaded.blob_paths.push_back((folder / file.objects[o].blob).string());
  }
  d.instances = file.instances;
  d.camera = file.camera;
  d.env = file.env;
  return loaded;
}

io::EnvMap scene_env(const std::string& env_option, const LoadedScene& scene,
                     const std::string& shared, const Context& ctx) {
  if (env_option.empty()) return load_shadowfield_env(scene.description.env, shared, ctx);
  return load_shadowfield_env(env_option, "", ctx);
}

// ---- shadowfield-reference -----------------------------------------------------------------

struct ReferenceCommandOptions {
  std::string json, env, eye, out, shared = "../shared";
  float time = 0.0f;
  int bounces = 0;
  std::uint32_t spp = 1024, seed = 0;
};

void run_shadowfield_reference(const ReferenceCommandOptions& options, const CommandEnv& env) {
  const Context ctx = env.context();
  const LoadedScene scene = load_scene_file(options.json, options.shared);
  const io::EnvMap map = scene_env(options.env, scene, options.shared, ctx);
  const glm::vec3 eye =
      options.eye.empty() ? scene.description.camera.eye : parse_point(options.eye);
  const VertexRadiance result = render_shadowfield_reference(
      scene.description, map, options.time, options.bounces, options.spp, eye, ctx, options.seed);
  write_then_rename(options.out,
                    [&](const std::string& path) { io::write_npy_vec3(path, result.radiance); });
  ctx.info(
      format("wrote %s: %zu vertices at t = %g s, %d bounces, %u spp (estimated relative "
             "RMSE %.2f %%, %.1f s)",
             options.out.c_str(), result.radiance.size(), double(options.time), options.bounces,
             options.spp, 100.0 * result.relative_rmse, result.stats.seconds));
}

void add_reference_subcommand(CLI::App& app, CommandEnv& env) {
  auto options = std::make_shared<ReferenceCommandOptions>();
  auto* cmd = app.add_subcommand(
      "shadowfield-reference",
      "Path-trace a shadowfield scene at a time: per-vertex outgoing radiance, instances in order");
  cmd->add_option("SCENE", options->json, "The scene.json shadowfield-scene wrote")->required();
  cmd->add_option("-o,--out", options->out, "Output .npy (vertices x 3 float32)")->required();
  cmd->add_option("--time", options->time, "Seconds on the scene's paths")->capture_default_str();
  cmd->add_option("--env", options->env, "An environment map file, or 'sky'; default: the scene's");
  cmd->add_option("--bounces", options->bounces, "Indirect bounces")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  cmd->add_option("--spp", options->spp, "Samples per vertex")
      ->check(CLI::Range(2u, 1u << 24))
      ->capture_default_str();
  cmd->add_option("--seed", options->seed, "Sampling seed")->capture_default_str();
  cmd->add_option("--eye", options->eye, "x,y,z world position; default: the scene's camera");
  cmd->add_option("--shared", options->shared, "The shared assets folder")->capture_default_str();
  cmd->callback([options, &env] { run_shadowfield_reference(*options, env); });
}

// ---- shadowfield-measure -------------------------------------------------------------------

struct MeasureOptions {
  std::string json, env, eye, out, shared = "../shared";
  ShadowfieldMeasureSettings settings;
};

void run_shadowfield_measure(const MeasureOptions& options, const CommandEnv& env) {
  const Context ctx = env.context();
  const LoadedScene scene = load_scene_file(options.json, options.shared);
  const io::EnvMap map = scene_env(options.env, scene, options.shared, ctx);
  ShadowfieldMeasureSettings settings = options.settings;
  if (!options.eye.empty()) settings.eye = parse_point(options.eye);
  std::vector<std::vector<std::uint8_t>> blobs;
  for (const std::string& path : scene.blob_paths) blobs.push_back(read_bytes(path));
  const std::vector<ShadowfieldMeasureRow> rows =
      measure_shadowfield_scene(scene.description, blobs, map, settings, ctx);
  const std::string table = shadowfield_measure_markdown(scene.description, rows);
  if (options.out.empty()) {
    std::fputs(table.c_str(), stdout);
    return;
  }
  write_then_rename(options.out, [&](const std::string& path) {
    std::ofstream out(path);
    out << table;
    if (!out) throw Error("cannot write " + path);
  });
  ctx.info("wrote " + options.out);
}

void add_measure_subcommand(CLI::App& app, CommandEnv& env) {
  auto options = std::make_shared<MeasureOptions>();
  ShadowfieldMeasureSettings& s = options->settings;
  auto* cmd = app.add_subcommand(
      "shadowfield-measure",
      "The shadowfield runtime against the path tracer: NRMSE per time and bounce count");
  cmd->add_option("SCENE", options->json, "The scene.json shadowfield-scene wrote")->required();
  cmd->add_option("-o,--out", options->out, "Markdown table; default: printed");
  cmd->add_option("--times", s.times, "Seconds on the scene's paths, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--bounces", s.bounces, "Bounce counts, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--spp", s.spp, "The reference's samples per vertex")->capture_default_str();
  cmd->add_option("--seed", s.seed, "The reference's sampling seed")->capture_default_str();
  cmd->add_option("--env", options->env, "An environment map file, or 'sky'; default: the scene's");
  cmd->add_option("--eye", options->eye, "x,y,z world position; default: the scene's camera");
  cmd->add_option("--shared", options->shared, "The shared assets folder")->capture_default_str();
  cmd->add_flag("--log-product", s.log_product,
                "The runtime combines blockers by the log-space product (default: triple "
                "products)");
  cmd->add_option("--probe-spacings", s.probe_spacings,
                  "Bounce probe spacings in object units, comma-separated, each against the same "
                  "references (0: every vertex gathers its bounce light)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->callback([options, &env] { run_shadowfield_measure(*options, env); });
}

}  // namespace

void add_shadowfield_scene_commands(CLI::App& app, CommandEnv& env) {
  add_scene_subcommand(app, env);
  add_reference_subcommand(app, env);
  add_measure_subcommand(app, env);
}

}  // namespace prt::bake::cli
