// SPDX-License-Identifier: MIT
// prt-bake: the command-line front end of libprt_bake. It only parses options and reports;
// the work lives in the library.
#include <cstdio>
#include <exception>

#include <prt/prt.h>

#include "command.hpp"

int main(int argc, char** argv) {
  using namespace prt::bake::cli;
  CLI::App app{"prt-bake: precomputed radiance transfer baker (prtkit " PRT_VERSION_STRING ")"};
  app.require_subcommand(1);
  app.fallthrough();  // global flags may follow the subcommand
  app.set_version_flag("--version", "prt-bake " PRT_VERSION_STRING);

  CommandEnv env;
  app.add_option("--threads", env.threads,
                 "Worker threads (0 = all cores); results do not depend on it")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("-q,--quiet", env.quiet, "Print errors only, no progress");

  add_reference_command(app, env);
  add_inspect_command(app, env);
  add_demo_scene_command(app, env);
  add_info_command(app, env);
  add_env_sh_command(app, env);
  add_scene_command(app, env);
  add_merge_command(app, env);
  add_shadowfield_scene_commands(app, env);
  add_bake_command(app, env);
  add_trade_command(app, env);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt-bake: error: %s\n", e.what());
    return 1;
  }
  return env.exit_code;
}
