// SPDX-License-Identifier: MIT
// `bake` and `trade` without a technique list the techniques (technique_group.hpp).
#include "technique_group.hpp"

#include <cstdio>

namespace prt::bake::cli {

CLI::App* add_technique_group(CLI::App& app, CommandEnv& env, const char* name,
                              const char* description) {
  CLI::App* group = app.add_subcommand(name, description);
  group->fallthrough();  // the global flags may follow
  group->callback([group, &env, name] {
    if (!group->get_subcommands().empty()) return;
    std::fprintf(stderr, "prt-bake %s: name a technique\n%s", name,
                 group->help("prt-bake").c_str());
    env.exit_code = static_cast<int>(CLI::ExitCodes::RequiredError);
  });
  return group;
}

}  // namespace prt::bake::cli
