// SPDX-License-Identifier: MIT
// The content pipeline: `prt-bake scene SCENE -o OUT/ --error-budget E` (docs/pipeline.md).
//
// Every node with a mesh is an object. Each technique of the table (techniques()) says whether
// it suits the object (Technique::fit: its skin, animation, materials, hints); for each that
// does, the pipeline climbs the technique's ladder of settings, cheapest first, baking the object
// and measuring the blob through the runtime against the reference renderer on a subset of the
// object's vertices, under every light the scene will see, until a setting meets E. It keeps the
// candidate with the fewest bytes that meets E (or, when none does, the most accurate, and says
// so). Results are cached by a content hash of everything they depend on, so a re-run bakes only
// what changed; every file is written to a temporary name and renamed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/baker/context.hpp"
#include "prt/baker/scene.hpp"
#include "prt/baker/technique.hpp"

namespace prt::bake {

// What a node is to the pipeline: the facts every Technique::fit reads.
struct NodeKind {
  bool has_mesh = false;
  bool skinned = false;  // a skin places its mesh
  bool moves = false;    // animated, or extras.prt.dynamic
  bool cloth = false;    // a material of its meshes has KHR_materials_sheen or extras.prt.cloth
};
NodeKind node_kind(const Scene& scene, int node);
// The fit of the techniques for static diffuse objects (sh, wavelet): a mesh that no skin
// places, that does not move and has no cloth material.
ObjectFit static_diffuse_fit(const Scene& scene, int node);

// One object: a node's meshes, alone, with the materials and images they use.
struct SceneObject {
  std::string name;  // unique in the scene: the node's name, or "node<index>", made unique
  int node = -1;
  Scene scene;  // its meshes in world space (Mesh::node kept, indices remapped)
  std::vector<std::string> problems;  // why it cannot be baked; empty: it can
  bool skipped = false;               // extras.prt.skip
};
// The objects of an imported scene, in node order. A node whose meshes are unusable (no
// triangle that is not degenerate, non-finite positions from a broken transform) is still
// listed, with its problems.
std::vector<SceneObject> scene_objects(const Scene& scene);

struct SceneBakeSettings {
  std::string scene;                   // SCENE (.gltf, .glb, .obj)
  std::string out_dir;                 // -o
  std::string cache_dir;               // empty: OUT_DIR/.cache
  double error_budget = 0.02;          // E: relative RMSE against the reference, per object
  std::vector<std::string> envs;       // the lights; empty: the built-in sky
  int bounces = 1;                     // the reference's indirect bounces
  std::uint32_t ref_spp = 1024;        // reference samples per vertex
  std::uint32_t probe_vertices = 512;  // vertices per object measured (all when fewer)
  std::uint32_t seed = 0;
  // "NAME=TECHNIQUE" or "NAME=TECHNIQUE:--opt,value,--opt,value": forces a technique (and
  // settings) on object NAME, over the node's extras.
  std::vector<std::string> overrides;
  bool strict = false;  // a broken object or an unmet budget fails the run
  // Also bake every object with each technique that suits them all, at the settings the hardest
  // object needs, for the report's comparison (more bakes; the cache keeps them).
  bool compare_single = false;
  // --shard i/N: bake only objects i, i + N, i + 2N, ... (in node order) into the cache and
  // write nothing else; a run without it over the same cache then bakes nothing anew and
  // writes every output (docs/farm.md). N = 1: the whole scene.
  std::size_t shard_index = 0, shard_count = 1;
};

struct SceneBakeSummary {
  std::size_t objects = 0, baked = 0, from_cache = 0, broken = 0, over_budget = 0;
  std::size_t bytes = 0;
  // With compare_single: the fewest bytes of one technique for every object that meets E on
  // all of them; 0 when none does (or not compared).
  std::size_t single_bytes = 0;
  bool failed() const { return broken > 0 || over_budget > 0; }
};

// Runs the pipeline; writes OUT_DIR/<object>.prtk for every baked object, OUT_DIR/scene.json
// (the manifest) and OUT_DIR/report.json. Throws Error when the scene cannot be read at all or
// an output cannot be written; a broken object is reported, not thrown.
SceneBakeSummary run_scene_bake(const SceneBakeSettings& settings, const Context& ctx);
// The same on a scene already in memory (settings.scene is then only its name in the outputs),
// e.g. one assembled with append_scene.
SceneBakeSummary run_scene_bake(const SceneBakeSettings& settings, const Scene& scene,
                                const Context& ctx);

}  // namespace prt::bake
