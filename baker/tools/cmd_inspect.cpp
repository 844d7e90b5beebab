// SPDX-License-Identifier: MIT
// prt-bake inspect [SCENE] [--env MAP]: imports a scene and/or an environment map and prints
// what the baker sees. Broken input fails with the importer's message and a non-zero exit.
#include <algorithm>
#include <cstdio>
#include <limits>
#include <memory>

#include "command.hpp"
#include "prt/baker/scene.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake::cli {
namespace {

struct InspectOptions {
  std::string scene;
  std::string env;
  std::string env_mapping = "auto";
  bool per_mesh = false;
};

void print_scene(const Scene& scene, bool per_mesh) {
  glm::vec3 lo, hi;
  scene.bounds(lo, hi);
  std::size_t skinned = 0;
  for (const Mesh& mesh : scene.meshes) skinned += mesh.skin >= 0 ? 1 : 0;
  std::printf("scene: %s\n", scene.source.c_str());
  std::printf("  meshes:     %zu (%zu skinned)\n", scene.meshes.size(), skinned);
  std::printf("  vertices:   %zu\n", scene.vertex_count());
  std::printf("  triangles:  %zu\n", scene.triangle_count());
  std::printf("  materials:  %zu\n", scene.materials.size());
  std::printf("  images:     %zu\n", scene.images.size());
  std::printf("  nodes:      %zu\n", scene.nodes.size());
  std::printf("  skins:      %zu\n", scene.skins.size());
  for (const Skin& skin : scene.skins) {
    std::printf("    '%s': %zu joints\n", skin.name.c_str(), skin.joints.size());
  }
  std::printf("  animations: %zu\n", scene.animations.size());
  for (const Animation& animation : scene.animations) {
    std::printf("    '%s': %zu channels, %.3f s\n", animation.name.c_str(),
                animation.channels.size(), animation.duration);
  }
  std::printf("  bounds:     (%g, %g, %g) .. (%g, %g, %g)\n", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
  if (!per_mesh) return;
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& mesh = scene.meshes[i];
    std::printf("  mesh %zu '%s': %zu vertices, %zu triangles, material %d, skin %d%s%s%s%s\n", i,
                mesh.name.c_str(), mesh.vertex_count(), mesh.triangle_count(), mesh.material,
                mesh.skin, mesh.normals_generated ? ", normals generated" : "",
                mesh.tangents.empty()
                    ? ""
                    : (mesh.tangents_generated ? ", tangents generated" : ", tangents"),
                mesh.texcoords0.empty() ? "" : ", uv", mesh.colors0.empty() ? "" : ", colours");
  }
}

void print_envmap(const io::EnvMap& map) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
  glm::dvec3 integral(0.0);
  double solid_angle = 0.0;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      float w = 0.0f;
      if (!map.texel(x, y, nullptr, &w)) continue;
      const glm::dvec3 v(map.texel_value(x, y));
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
      integral += v * double(w);
      solid_angle += w;
    }
  }
  const glm::dvec3 mean = integral / std::max(solid_angle, 1e-30);
  std::printf("environment: %s\n", map.source().c_str());
  std::printf("  size:       %d x %d\n", map.width(), map.height());
  std::printf("  mapping:    %s\n", io::env_mapping_name(map.mapping()));
  std::printf("  radiance:   min (%g, %g, %g)  max (%g, %g, %g)\n", lo.x, lo.y, lo.z, hi.x, hi.y,
              hi.z);
  std::printf("  mean:       (%g, %g, %g) over %.5f sr\n", mean.x, mean.y, mean.z, solid_angle);
  std::printf("  sanitised:  %zu texels (NaN, Inf or negative replaced by 0)\n",
              map.sanitized_texels());
}

}  // namespace

void add_inspect_command(CLI::App& app, CommandEnv& env) {
  auto options = std::make_shared<InspectOptions>();
  auto* cmd = app.add_subcommand(
      "inspect",
      "Import a scene (.gltf, .glb, .obj) and/or an environment map (.hdr) and print "
      "a summary");
  cmd->add_option("SCENE", options->scene, "Scene file");
  cmd->add_option("--env", options->env, "Environment map (.hdr)");
  cmd->add_option("--env-mapping", options->env_mapping, "auto|latlong|cross|probe")
      ->check(CLI::IsMember({"auto", "latlong", "cross", "probe"}));
  cmd->add_flag("--meshes", options->per_mesh, "Also list every mesh");
  cmd->callback([&env, options] {
    if (options->scene.empty() && options->env.empty()) {
      throw Error("inspect: give a SCENE, an --env MAP, or both");
    }
    const Context ctx = env.context();
    // Load both before printing, so broken input prints nothing but the error.
    std::unique_ptr<Scene> scene;
    std::unique_ptr<io::EnvMap> map;
    if (!options->scene.empty()) {
      scene = std::make_unique<Scene>(import_scene(options->scene, ctx));
    }
    if (!options->env.empty()) {
      map = std::make_unique<io::EnvMap>(io::load_envmap(
          options->env, io::parse_env_mapping(options->env_mapping), ctx.io_messages()));
    }
    if (scene) print_scene(*scene, options->per_mesh);
    if (map) print_envmap(*map);
  });
}

}  // namespace prt::bake::cli
