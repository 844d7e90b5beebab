// SPDX-License-Identifier: MIT
// prt-bake bake <technique> SCENE -o OUT.prtk: one subcommand per technique of the baker's table
// (prt/baker/technique.hpp), each with the technique's own options and the shared ones.
#include <memory>

#include "command.hpp"
#include "prt/baker/shards.hpp"
#include "technique_group.hpp"

namespace prt::bake::cli {
namespace {

// The flags every bake takes, declared once for every technique.
void add_bake_input(CLI::App* cmd, BakeInput& input) {
  cmd->add_option("--albedo", input.albedo,
                  "Diffuse albedo r,g,b for every surface (default: from the materials)");
  cmd->add_option("--seed", input.seed, "Random seed (same seed, same blob, any thread count)")
      ->capture_default_str();
  cmd->add_option("-o,--output", input.output, "Output blob (.prtk)")->required();
  cmd->add_option("--report", input.report,
                  "Write a JSON report (settings, rays, seconds, blob bytes, quantisation error, "
                  "self-check)");
}

struct BakeCommand {
  std::unique_ptr<TechniqueBake> bake;
  BakeInput input;
  std::string shard;  // --shard i/N; empty: the whole bake
};

}  // namespace

void add_bake_command(CLI::App& app, CommandEnv& env) {
  CLI::App* group =
      add_technique_group(app, env, "bake", "Bake a technique's transfer into a runtime blob");
  for (const Technique* technique : techniques()) {
    auto command = std::make_shared<BakeCommand>();
    command->bake = technique->make_bake();
    CLI::App* cmd = group->add_subcommand(technique->name(), technique->summary());
    cmd->fallthrough();  // the global flags may follow
    cmd->add_option("SCENE", command->input.scene, "Scene file (.gltf, .glb, .obj)")->required();
    const OptionList options = command->bake->options();
    const auto record_given = add_options(cmd, options);
    add_bake_input(cmd, command->input);
    cmd->add_option("--shard", command->shard,
                    "i/N: bake the i-th of N parts (from 0) into a shard file at -o; "
                    "`prt-bake merge` makes the blob from all N (docs/farm.md)");
    cmd->callback([&env, technique, command, record_given, cmd, options] {
      record_given();
      if (command->shard.empty()) {
        run_bake(*command->bake, command->input, env.context());
        return;
      }
      if (!command->input.report.empty())
        throw Error("--report: a shard has no report; give it to `prt-bake merge`");
      run_shard_bake(*technique, *command->bake, command->input, given_option_args(cmd, options),
                     parse_shard_spec(command->shard), env.context());
    });
  }
}

}  // namespace prt::bake::cli
