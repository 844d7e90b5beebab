// SPDX-License-Identifier: MIT
// A baker technique: what `prt-bake bake <name>` and `prt-bake trade <name>` run. Each technique
// implements it in its own folder (baker/src/<name>/) and is listed once in techniques(); the
// command builds one subcommand per technique from that list, with the technique's own options
// and the shared ones (SCENE, --albedo, --seed, -o, --report; for trade SCENE, --env, --out-dir,
// --cache-dir, --ref-spp, --frames, --albedo, --seed).
//
// A bake runs the steps of TechniqueBake in order (run_bake): import the scene, bake (the
// transfer), quantise, write the blob, check it through the runtime, report. A trade runs
// TechniqueTrade (run_trade): check the options, load the scene (by default SCENE imported),
// prepare (lights and cached references), build one Embree scene, sweep (bake, load, shade and
// measure each setting; trade.csv and trade.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/embree_scene.hpp"
#include "prt/baker/options.hpp"
#include "prt/baker/scene.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake {

// The flags every bake takes.
struct BakeInput {
  std::string scene;   // SCENE (.gltf, .glb, .obj)
  std::string albedo;  // --albedo "r,g,b" for every surface; empty: from the materials
  std::uint32_t seed = 0;
  std::string output;  // -o: the blob
  std::string report;  // --report: the JSON report; empty: none
};

// What every bake report states besides the technique's own settings and results.
struct BakeFacts {
  std::size_t vertices = 0, triangles = 0;
  unsigned threads = 1;
  std::size_t blob_bytes = 0;
};

struct SelfCheck {
  bool passed = false;
  std::string message;  // what failed, or a summary of what was checked
};

// One bake: the settings its options fill, then the steps run_bake calls once each, in order.
class TechniqueBake {
 public:
  virtual ~TechniqueBake() = default;
  // The technique's own options, bound to this bake's settings (they point into it: keep the
  // bake alive while they are used).
  virtual OptionList options() = 0;
  // Computes the transfer of every vertex of `scene`.
  virtual void bake(const Scene& scene, const BakeInput& input, const Context& ctx) = 0;
  // Quantises the transfer as the blob stores it.
  virtual void quantize() = 0;
  // The blob; the same scene and settings give the same bytes.
  virtual std::vector<std::uint8_t> write(const Scene& scene, const BakeInput& input) const = 0;
  // The line the command prints once the blob is written.
  virtual std::string summary(const Scene& scene, const BakeInput& input,
                              std::size_t blob_bytes) const = 0;
  // Loads the blob through the runtime at full validation and checks it against the bake.
  virtual SelfCheck self_check(const std::vector<std::uint8_t>& blob) = 0;
  // Writes the JSON report (settings, bake, blob, quantisation, self-check); Error on failure.
  virtual void write_report(const std::string& path, const BakeInput& input,
                            const BakeFacts& facts) const = 0;

  // --- Shards: `prt-bake bake <t> --shard i/N` bakes a part, `prt-bake merge` the whole
  // (docs/farm.md). A bake that keeps these defaults does not split.
  // What a shard takes a range of ("vertices"), and how many there are in `scene`; 0: the bake
  // does not split.
  virtual const char* shard_unit() const { return "vertices"; }
  virtual std::size_t shard_units(const Scene& scene) const;
  // Bakes units [first, first + count) of `scene` only, with the settings its options hold, and
  // returns what a shard file carries for them.
  virtual std::vector<std::uint8_t> bake_shard(const Scene& scene, const BakeInput& input,
                                               std::size_t first, std::size_t count,
                                               const Context& ctx);
  // Takes every shard's bytes in unit order (the ranges cover the units once, in order) and
  // finishes the bake as bake() would have: quantize() and write() then give the bytes of the
  // whole bake. Throws Error when a part does not fit.
  virtual void merge_shards(const Scene& scene, const BakeInput& input,
                            const std::vector<std::vector<std::uint8_t>>& parts,
                            const Context& ctx);
};

// The flags every trade takes; a technique gives their defaults (TechniqueTrade::defaults).
struct TradeInput {
  std::string scene, out_dir, cache_dir;  // cache_dir empty: OUT_DIR/cache
  std::string albedo;                     // "r,g,b" or empty (from the materials)
  std::vector<std::string> envs;          // environment maps, at least one
  std::uint32_t ref_spp = 2048, seed = 0;
  int frames = 10;  // timed frames per measurement (median)
};

// One speed/accuracy sweep of a technique against the reference renderer.
class TechniqueTrade {
 public:
  virtual ~TechniqueTrade() = default;
  // The shared flags with this sweep's defaults.
  virtual TradeInput defaults() const = 0;
  // The technique's own options, bound to this trade's settings (they point into it).
  virtual OptionList options() = 0;
  // Throws Error naming the flag when an option value cannot be swept; before any work.
  virtual void check(const TradeInput& input) const = 0;
  // The scene SCENE names. Default: the file imported (.gltf, .glb, .obj); a technique whose
  // trade also takes scenes by another name (shadowfield's presets) overrides it.
  virtual Scene load_scene(const TradeInput& input, const Context& ctx);
  // Loads the maps as the technique's runtime takes them, and their cached references.
  virtual void prepare(const Scene& scene, const TradeInput& input, const Context& ctx) = 0;
  // Bakes, loads, shades and measures every setting; writes OUT_DIR/trade.csv and trade.md.
  virtual void sweep(const Scene& scene, const EmbreeScene& rays, const TradeInput& input,
                     const Context& ctx) = 0;
};

// One candidate setting of a technique for `prt-bake scene`: the arguments of its bake options,
// e.g. {"--order", "4", "--bits", "8"}.
struct Rung {
  std::vector<std::string> args;
};

// Whether a technique suits an object of a scene, and why (said in the scene report).
struct ObjectFit {
  bool suits = false;
  std::string reason;
};

class Technique;

// What a scene bake measures one object's candidates in (prt/baker/scene_bake.hpp).
struct ObjectMeasureInput {
  const Scene* scene = nullptr;           // the whole scene: what surrounds the object
  const Scene* object = nullptr;          // the object alone, as its candidates bake it
  int node = -1;                          // the object's node, in both
  std::vector<const io::EnvMap*> lights;  // every light the scene will see, at least one
  int bounces = 1;                        // the reference's indirect bounces
  std::uint32_t ref_spp = 1024;           // reference samples per vertex
  std::uint32_t probe_vertices = 512;     // vertices measured (all when the object has fewer)
  std::uint32_t seed = 0;
};

struct Measurement {
  double error = 0.0;      // the worst light's relative RMSE, the reference's noise taken out
  double ref_noise = 0.0;  // the reference's own relative RMSE estimate under that light
};

// Measures the candidates of one object against the reference renderer. Built once per object
// (and per factory, see Technique::measure); it renders its references on first need, so that an
// object whose candidates all come from the cache renders none.
class ObjectMeasure {
 public:
  virtual ~ObjectMeasure() = default;
  // The error of a blob `technique` baked for the object. Throws Error when it cannot be
  // measured (the blob does not load, shades the wrong vertex count, ...).
  virtual Measurement measure(const Technique& technique, const std::vector<std::uint8_t>& blob,
                              const Context& ctx) = 0;
};
using ObjectMeasureFactory = std::unique_ptr<ObjectMeasure> (*)(const ObjectMeasureInput& input);

// The measurement of static objects (sh, wavelet): each light's diffuse reference on
// `probe_vertices` vertices of the object alone, against Technique::shade of every vertex.
std::unique_ptr<ObjectMeasure> make_diffuse_measure(const ObjectMeasureInput& input);
// `count` of `vertices` vertex indices spread evenly over the vertex order (all when fewer).
std::vector<std::size_t> spread_vertices(std::size_t vertices, std::size_t count);

class Technique {
 public:
  virtual ~Technique() = default;
  // The technique's name, the folder name in every layer: "sh", "wavelet".
  virtual const char* name() const = 0;
  // One line each: what its bake makes, what its trade measures.
  virtual const char* summary() const = 0;
  virtual const char* trade_summary() const = 0;
  virtual std::unique_ptr<TechniqueBake> make_bake() const = 0;
  virtual std::unique_ptr<TechniqueTrade> make_trade() const = 0;

  // --- prt-bake scene (prt/baker/scene_bake.hpp). A technique that keeps these defaults is
  // never chosen for an object, but can still be forced on one it can bake.
  // Whether the technique suits node `node` of `scene` (its skin, animation, materials, hints).
  virtual ObjectFit fit(const Scene& scene, int node) const;
  // Candidate settings, cheapest first (the fewest bytes, then the shortest bake), for a scene
  // whose reference has `bounces` indirect bounces. The scene command climbs it until one meets
  // the error budget.
  virtual std::vector<Rung> ladder(int bounces) const;
  // Outgoing radiance of every vertex of a blob this technique baked, shaded through the runtime
  // under `light` as a diffuse surface is seen (the reference's estimate for no eye). Throws
  // Error when the technique cannot be measured this way.
  virtual std::vector<glm::vec3> shade(const std::vector<std::uint8_t>& blob,
                                       const io::EnvMap& light, const Context& ctx) const;
  // How the scene command measures this technique's candidates. Techniques that return the same
  // factory share one measurement per object, and so its reference renders. Default:
  // make_diffuse_measure, which calls shade(). A technique whose output is not a diffuse
  // vertex radiance (a pose, a view, other objects) returns its own.
  virtual ObjectMeasureFactory measure() const;
};

// Every technique of the baker, in the order the command lists them (baker/src/techniques.cpp).
const std::vector<const Technique*>& techniques();
// The technique of that name, or null.
const Technique* find_technique(const std::string& name);

// Imports input.scene, runs every step of `bake` and writes the blob (and the report); throws
// Error when a step or the self-check fails, after writing what it could.
void run_bake(TechniqueBake& bake, const BakeInput& input, const Context& ctx);
// run_bake's steps: the import (with its checks of --albedo and degenerate meshes), and what
// follows the transfer (quantise, write, self-check, report), which a merge of shards runs too.
Scene import_bake_scene(const BakeInput& input, const Context& ctx);
void finish_bake(TechniqueBake& bake, const Scene& scene, const BakeInput& input,
                 const Context& ctx);

// Checks the shared flags and the technique's, then runs the sweep (see the top of this file).
void run_trade(TechniqueTrade& trade, TradeInput input, const Context& ctx);

// Parses "r,g,b" (the --albedo flag); throws Error on anything else.
glm::vec3 parse_albedo(const std::string& text);

}  // namespace prt::bake
