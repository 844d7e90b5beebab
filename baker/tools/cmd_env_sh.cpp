// SPDX-License-Identifier: MIT
// prt-bake env-sh MAP --order N [--env-mapping M]: projects an environment map onto SH and
// prints the coefficients as JSON (convention: formats/SPEC.md, prt/prt_sh.h).
#include <prt/prt_sh.h>

#include <cstdio>
#include <memory>

#include "command.hpp"
#include "prt/baker/sh/env_sh.hpp"

namespace prt::bake::cli {
namespace {

struct EnvShOptions {
  std::string map;
  unsigned order = 3;
  std::string env_mapping = "auto";
};

}  // namespace

void add_env_sh_command(CLI::App& app, CommandEnv& env) {
  auto options = std::make_shared<EnvShOptions>();
  CLI::App* cmd = app.add_subcommand(
      "env-sh", "Project an environment map onto spherical harmonics; print JSON to stdout");
  cmd->add_option("map", options->map, "Radiance .hdr environment map")->required();
  cmd->add_option("--order,-n", options->order, "SH order N (N*N coefficients)")
      ->check(CLI::Range(1u, unsigned(PRT_SH_MAX_ORDER)));
  cmd->add_option("--env-mapping", options->env_mapping, "auto | latlong | cross | probe")
      ->check(CLI::IsMember({"auto", "latlong", "cross", "probe"}));
  cmd->callback([options, &env] {
    const Context ctx = env.context();
    const io::EnvMap map = io::load_envmap(
        options->map, io::parse_env_mapping(options->env_mapping), ctx.io_messages());
    const EnvSh sh = project_env_sh(map, options->order);
    std::printf("%s\n", env_sh_json(map, sh).c_str());
  });
}

}  // namespace prt::bake::cli
