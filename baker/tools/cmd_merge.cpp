// SPDX-License-Identifier: MIT
// prt-bake merge -o OUT.prtk SHARD...: the blob of a bake made in parts (`prt-bake bake <t>
// --shard i/N`), byte for byte the blob of the whole bake (prt/baker/shards.hpp, docs/farm.md).
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "prt/baker/shards.hpp"

namespace prt::bake::cli {
namespace {

struct MergeOptions {
  std::vector<std::string> shards;
  std::string output, report;
};

}  // namespace

void add_merge_command(CLI::App& app, CommandEnv& env) {
  auto options = std::make_shared<MergeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "Merge the shards of a distributed bake into its blob (the whole bake's bytes)");
  cmd->add_option("shards", options->shards, "Every shard file of the bake, in any order")
      ->required();
  cmd->add_option("-o,--output", options->output, "Output blob (.prtk)")->required();
  cmd->add_option("--report", options->report, "Write the bake's JSON report");
  cmd->callback([options, &env] {
    run_merge(options->shards, options->output, options->report, env.context());
  });
}

}  // namespace prt::bake::cli
