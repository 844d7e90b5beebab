// SPDX-License-Identifier: MIT
// Midpoint subdivision of a skinned character, to bake `pose` at a finer vertex count than the
// file's (the paper's 11.5k-vertex character from CesiumMan's 3.3k): every triangle becomes four
// at its edge midpoints, each edge split once, and every vertex attribute of the new vertex is
// interpolated from the edge's two ends (see pose_subdivide.cpp for the rules per attribute).
#pragma once

#include <cstddef>

#include "prt/baker/scene.hpp"

namespace prt::bake {

// One level: V + E vertices (E the mesh's distinct edges, by vertex index) and 4 T triangles,
// the original vertices first and unchanged, then one vertex per edge in order of first use.
Mesh subdivide_mesh(const Mesh& mesh);

// `scene` with every mesh subdivided one level at a time while a whole level stays within
// `target_vertices`, then a last level that splits only the longest edges (bind-pose length,
// over all meshes), as many as make exactly `target_vertices`. A copy of `scene` when it already
// has that many vertices or has no triangles.
Scene subdivide_scene(const Scene& scene, std::size_t target_vertices);

}  // namespace prt::bake
