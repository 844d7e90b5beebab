// SPDX-License-Identifier: MIT
// prt-bake demo-scene DIR: writes the built-in default scene and sky, so the demo and the
// tutorials need no downloaded asset.
#include <filesystem>

#include "command.hpp"
#include "prt/baker/demo_scene.hpp"

namespace prt::bake::cli {

void add_demo_scene_command(CLI::App& app, CommandEnv& env) {
  auto* cmd = app.add_subcommand(
      "demo-scene",
      "Write the built-in default scene (DIR/demo_scene.glb) and sky (DIR/demo_sky.hdr)");
  auto dir = std::make_shared<std::string>();
  auto sky_width = std::make_shared<int>(512);
  cmd->add_option("DIR", *dir, "Output folder (created if missing)")->required();
  cmd->add_option("--sky-width", *sky_width, "Width of the lat-long sky in pixels")
      ->check(CLI::Range(16, 8192));
  cmd->callback([&env, dir, sky_width] {
    Context ctx = env.context();
    std::filesystem::create_directories(*dir);
    const std::string scene_path = *dir + "/demo_scene.glb";
    const std::string sky_path = *dir + "/demo_sky.hdr";
    Scene scene = make_demo_scene();
    write_glb(scene, scene_path);
    write_envmap_hdr(make_demo_sky(*sky_width), sky_path);
    ctx.info("wrote " + scene_path + " (" + std::to_string(scene.vertex_count()) + " vertices, " +
             std::to_string(scene.triangle_count()) + " triangles) and " + sky_path);
  });
}

}  // namespace prt::bake::cli
