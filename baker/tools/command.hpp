// SPDX-License-Identifier: MIT
// What every prt-bake subcommand shares: global flags, the terminal context, the exit code.
#pragma once

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/options.hpp"
#include "prt/baker/technique.hpp"

namespace prt::bake::cli {

struct CommandEnv {
  unsigned threads = 0;  // --threads N (0 = all cores), shared by every command
  bool quiet = false;    // --quiet: errors only, no progress
  int exit_code = 0;     // set by the command that ran
  // A context that logs to stderr and draws progress when stderr is a terminal.
  Context context() const;
};

// Adds every option of `options` to `cmd` as a CLI11 option (cli_options.cpp). The returned
// callback records which options were given; the command calls it before it runs.
std::function<void()> add_options(CLI::App* cmd, const OptionList& options);
// The options of `options` given on `cmd`'s command line, as apply_option_args takes them
// ("--order=4"), in the list's order: what a shard records of its bake's settings.
std::vector<std::string> given_option_args(CLI::App* cmd, const OptionList& options);

// Each command file registers one subcommand; its callback runs the command, throws Error on
// failure, and sets env.exit_code when it has something other than 0 to say.
void add_reference_command(CLI::App& app, CommandEnv& env);
void add_inspect_command(CLI::App& app, CommandEnv& env);
void add_demo_scene_command(CLI::App& app, CommandEnv& env);
void add_info_command(CLI::App& app, CommandEnv& env);
void add_env_sh_command(CLI::App& app, CommandEnv& env);
// `scene`: the content pipeline (cmd_scene.cpp).
void add_scene_command(CLI::App& app, CommandEnv& env);
// `merge`: a distributed bake's shards into its blob (cmd_merge.cpp).
void add_merge_command(CLI::App& app, CommandEnv& env);
// shadowfield-scene, shadowfield-reference and shadowfield-measure (cmd_shadowfield_scene.cpp).
void add_shadowfield_scene_commands(CLI::App& app, CommandEnv& env);
// `bake` and `trade`, with one subcommand per technique of prt::bake::techniques().
void add_bake_command(CLI::App& app, CommandEnv& env);
void add_trade_command(CLI::App& app, CommandEnv& env);

}  // namespace prt::bake::cli
