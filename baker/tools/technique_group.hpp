// SPDX-License-Identifier: MIT
// A command whose subcommands are the techniques (`bake`, `trade`).
#pragma once

#include "command.hpp"

namespace prt::bake::cli {

// Adds `name` to `app`. Given without a technique, it prints its help (which lists the
// techniques) to stderr and exits with CLI11's "subcommand required" code.
CLI::App* add_technique_group(CLI::App& app, CommandEnv& env, const char* name,
                              const char* description);

}  // namespace prt::bake::cli
