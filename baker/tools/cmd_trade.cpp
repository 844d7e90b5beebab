// SPDX-License-Identifier: MIT
// prt-bake trade <technique> SCENE --env MAP ... --out-dir DIR: one subcommand per technique of
// the baker's table (prt/baker/technique.hpp), each with the technique's own sweep options and
// the shared ones (docs/<technique>/trade.md).
#include <memory>

#include "command.hpp"
#include "technique_group.hpp"

namespace prt::bake::cli {
namespace {

struct TradeCommand {
  std::unique_ptr<TechniqueTrade> trade;
  TradeInput input;
};

// The flags every trade takes, declared once for every technique: the maps and folders before
// the technique's own options, the reference, timing, albedo and seed after them.
void add_trade_places(CLI::App* cmd, TradeInput& input) {
  cmd->add_option("SCENE", input.scene, "Scene file (.gltf, .glb, .obj)")->required();
  cmd->add_option("--env", input.envs, "Environment map (.hdr); repeat for several")
      ->required()
      ->allow_extra_args(false);
  cmd->add_option("--out-dir", input.out_dir, "Where trade.csv and trade.md go")->required();
  cmd->add_option("--cache-dir", input.cache_dir,
                  "Where reference radiance is cached (default: OUT_DIR/cache)");
}

void add_trade_measures(CLI::App* cmd, TradeInput& input) {
  cmd->add_option("--ref-spp", input.ref_spp, "Reference samples per vertex")
      ->check(CLI::Range(2u, 1u << 30))
      ->capture_default_str();
  cmd->add_option("--frames", input.frames, "Timed frames per measurement (median)")
      ->capture_default_str();
  cmd->add_option("--albedo", input.albedo,
                  "Diffuse albedo r,g,b for every surface (default: from the materials)");
  cmd->add_option("--seed", input.seed, "Seed of the bakes and references")->capture_default_str();
}

}  // namespace

void add_trade_command(CLI::App& app, CommandEnv& env) {
  CLI::App* group = add_technique_group(
      app, env, "trade", "Measure a technique's speed/accuracy trade against the reference");
  for (const Technique* technique : techniques()) {
    auto command = std::make_shared<TradeCommand>();
    command->trade = technique->make_trade();
    command->input = command->trade->defaults();
    CLI::App* cmd = group->add_subcommand(technique->name(), technique->trade_summary());
    cmd->fallthrough();  // the global flags may follow
    add_trade_places(cmd, command->input);
    const auto record_given = add_options(cmd, command->trade->options());
    add_trade_measures(cmd, command->input);
    cmd->callback([&env, command, record_given] {
      record_given();
      run_trade(*command->trade, command->input, env.context());
    });
  }
}

}  // namespace prt::bake::cli
