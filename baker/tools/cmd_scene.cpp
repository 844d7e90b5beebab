// SPDX-License-Identifier: MIT
// prt-bake scene SCENE -o OUT/ --error-budget E: bakes every object of a scene with the technique
// and settings that meet E in the fewest bytes (prt/baker/scene_bake.hpp, docs/pipeline.md).
#include <memory>
#include <string>

#include "command.hpp"
#include "prt/baker/scene_bake.hpp"
#include "prt/baker/shards.hpp"
#include "prt/baker/text.hpp"

namespace prt::bake::cli {

void add_scene_command(CLI::App& app, CommandEnv& env) {
  auto s = std::make_shared<SceneBakeSettings>();
  auto budget_percent = std::make_shared<double>(2.0);
  CLI::App* cmd = app.add_subcommand(
      "scene",
      "Bake a whole scene: each object with the cheapest technique and settings that "
      "meet an error budget against the reference renderer");
  cmd->add_option("scene", s->scene, "The scene (.gltf, .glb, .obj)")->required();
  cmd->add_option("-o,--out-dir", s->out_dir,
                  "Output folder: blobs, scene.prts, scene.json, report.json")
      ->required();
  cmd->add_option("--error-budget", *budget_percent,
                  "E, in percent: the largest relative RMSE against the reference, per object")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--env", s->envs,
                  "Environment maps the scene will see (default: the built-in "
                  "sky); every object meets E under each");
  cmd->add_option("--bounces", s->bounces, "Indirect bounces of the reference")
      ->capture_default_str()
      ->check(CLI::Range(0, 8));
  cmd->add_option("--ref-spp", s->ref_spp, "Reference samples per measured vertex")
      ->capture_default_str()
      ->check(CLI::Range(2u, 1u << 20));
  cmd->add_option("--probe-vertices", s->probe_vertices, "Vertices measured per object")
      ->capture_default_str()
      ->check(CLI::Range(1u, 1u << 30));
  cmd->add_option("--seed", s->seed, "Seed of every bake and reference")->capture_default_str();
  cmd->add_option("--cache-dir", s->cache_dir, "Cache of baked candidates (default OUT/.cache)");
  cmd->add_option("--object", s->overrides,
                  "NAME=TECHNIQUE[:--opt,value,...]: force a technique (and settings) on an "
                  "object, over its node's extras");
  cmd->add_flag("--compare-single", s->compare_single,
                "Also report the bytes of baking every object with one technique at the "
                "settings the hardest object needs");
  auto shard = std::make_shared<std::string>();
  cmd->add_option("--shard", *shard,
                  "i/N: bake objects i, i+N, ... into the cache only; a run without --shard "
                  "over the same --cache-dir writes the outputs");
  cmd->add_flag("--strict", s->strict,
                "Exit non-zero when an object is broken or does not meet the budget");
  cmd->callback([s, budget_percent, shard, &env] {
    const Context ctx = env.context();
    SceneBakeSettings settings = *s;
    settings.error_budget = *budget_percent / 100.0;
    if (!shard->empty()) {
      const ShardSpec spec = parse_shard_spec(*shard);
      settings.shard_index = spec.index;
      settings.shard_count = spec.count;
    }
    const SceneBakeSummary summary = run_scene_bake(settings, ctx);
    if (settings.shard_count > 1) {
      ctx.info(
          format("shard %s: %zu objects, %zu baked (%zu from the cache), %zu broken, %zu "
                 "over budget; run without --shard over the same cache to write the outputs",
                 shard->c_str(), summary.objects, summary.baked, summary.from_cache, summary.broken,
                 summary.over_budget));
      if (summary.failed() && settings.strict) env.exit_code = 1;
      return;
    }
    ctx.info(
        format("%zu objects: %zu baked (%zu from the cache), %zu broken, %zu over budget; "
               "%zu bytes; wrote %s/scene.prts, scene.json and report.json",
               summary.objects, summary.baked, summary.from_cache, summary.broken,
               summary.over_budget, summary.bytes, settings.out_dir.c_str()));
    if (summary.single_bytes > 0) {
      ctx.info(
          format("one technique for every object: %zu bytes; the choice per object: %zu "
                 "(%.0f %%)",
                 summary.single_bytes, summary.bytes,
                 100.0 * double(summary.bytes) / double(summary.single_bytes)));
    }
    if (summary.failed() && settings.strict) env.exit_code = 1;
  });
}

}  // namespace prt::bake::cli
