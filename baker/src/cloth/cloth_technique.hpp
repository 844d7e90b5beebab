// SPDX-License-Identifier: MIT
// Technique `cloth`'s parts that prt-bake's steps call (private to baker/src/cloth/).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/cloth/cloth_blob.hpp"
#include "prt/baker/cloth/cloth_tables.hpp"
#include "prt/baker/cloth/fabrics.hpp"
#include "prt/baker/scene.hpp"
#include "prt/baker/technique.hpp"

namespace prt::bake {

// The fabrics a bake names: presets by name, "all" for every preset; throws Error naming the
// presets for an unknown one or a name given twice.
std::vector<ClothFabricSource> cloth_fabric_sources(const std::vector<std::string>& names);

// A vertex's warp: its tangent made orthogonal to the normal, or where there is none (no UVs),
// the world axis least aligned with the normal, made orthogonal to it: any direction in the
// plane is a valid warp, this one is stable and the same for every vertex of a flat face.
glm::vec3 cloth_warp(const glm::vec3& normal, const glm::vec4* tangent);

// The scene's meshes as one cloth mesh: positions, normals and per-vertex warps (the mesh's
// tangents, or, where it has none, the world axis least aligned with the normal made orthogonal
// to it), the triangles. Throws Error for a scene without triangles.
ClothMesh cloth_mesh_of(const Scene& scene);

// The quantisation's effect: the largest |T - T_stored| over every entry of every factorisation.
struct ClothQuantization {
  int bits = 16;
  double max_abs_error = 0.0;
};
ClothQuantization measure_cloth_quantization(const ClothSection& section,
                                             const DecodedClothSection& stored);

// The baker's self-check: the blob loaded through the runtime at full validation, every fabric's
// name, parameters and weave against the bake's, and the scalar shading of a grid of views of a
// flat patch under a light of sharp and wide lobes finite and non-negative on every fabric.
struct ClothBlobCheck {
  bool passed = false;
  std::string message;
  std::size_t samples_shaded = 0;
};
ClothBlobCheck check_cloth_blob(const std::vector<std::uint8_t>& blob, const ClothSection& section);

void write_cloth_bake_report(const std::string& path, const BakeInput& input,
                             const BakeFacts& facts, const ClothTablesBake& bake,
                             const ClothTablesOptions& options, const ClothQuantization& q,
                             const ClothBlobCheck& check);

std::unique_ptr<TechniqueTrade> make_cloth_trade();

// --- Shards (cloth_shards.cpp; docs/farm.md). A shard takes a range of the tables' views (the
// grid's columns): every table's W maps, T and T_c for its views. The merge joins the views and
// factors the tables (bake_cloth_tables in two steps, prt/baker/cloth/cloth_tables.hpp).
struct ClothShardSettings {
  std::vector<std::string> fabric_names;   // --fabric as given ("scene" among them or not)
  std::vector<ClothFabricSource> fabrics;  // what they name in this scene
  ClothTablesOptions options;
  int bits = 16;
};
// A shard's payload: views [first, first + count) of every table. Throws Error for a range
// beyond the grid's views, or as bake_cloth_tables.
std::vector<std::uint8_t> bake_cloth_shard(const Scene& scene, const ClothShardSettings& settings,
                                           std::size_t first, std::size_t count,
                                           const Context& ctx);
// Every shard's payload in view order joined and factored: what bake_cloth_tables returns for
// the same settings. Throws Error naming the part for one of another bake, a damaged payload or
// ranges that do not cover the views once.
ClothTablesBake merge_cloth_shards(const Scene& scene, const ClothShardSettings& settings,
                                   const std::vector<std::vector<std::uint8_t>>& parts,
                                   const Context& ctx);

// --- prt-bake scene (cloth_scene.cpp; docs/cloth/trade.md, "In a scene bake").
// The fabric of a scene's cloth: the preset its first cloth material (KHR_materials_sheen or
// extras.prt.cloth) that is named after one names, else linen_plain. What `--fabric scene`
// bakes and what the scene measurement's reference shades.
const ClothPreset& cloth_scene_fabric(const Scene& scene);
// Suits a node with a cloth material that no skin places; a moving node is fine.
ObjectFit cloth_scene_fit(const Scene& scene, int node);
// The tables' grid, rank (by energy) and bits, cheapest first; the same for any `bounces`
// (cloth has no interreflection).
std::vector<Rung> cloth_scene_ladder(int bounces);
// The runtime's shading of the blob's vertex frames from a few views per vertex under each
// light's static SG fit, against the brute-force reference of the scene's fabric.
std::unique_ptr<ObjectMeasure> make_cloth_measure(const ObjectMeasureInput& input);

}  // namespace prt::bake
