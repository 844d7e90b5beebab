// SPDX-License-Identifier: MIT
// Procedural meshes (grids, plane, sphere, torus, box, cylinder) for the built-in scenes, so the
// demo and the tests need no downloaded asset. Every mesh is in the glTF frame (+Y up), with unit
// normals, world-space positions only (callers that need local_positions copy them).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "prt/baker/scene.hpp"

namespace prt::bake {

// A point of a parametric surface and its (not necessarily unit) normal.
using SurfacePoint = std::pair<glm::vec3, glm::vec3>;
using ParametricSurface = std::function<SurfacePoint(float u, float v)>;

// A (rows + 1) x (cols + 1) vertex grid over u, v in [0, 1], two triangles a cell, row-major
// (v along rows). Zero-area triangles (where a row collapses to a point, such as a sphere's
// poles) are skipped; their vertices stay.
Mesh make_grid_mesh(std::string name, int material, int rows, int cols,
                    const ParametricSurface& surface);

// The plane y = 0, x in [-half_x, half_x], z in [-half_z, half_z], normal +Y, with
// (cells_x + 1) x (cells_z + 1) vertices.
Mesh make_plane_mesh(std::string name, int material, float half_x, float half_z, int cells_x,
                     int cells_z);

// Seam vertices are duplicated, so the sphere is closed geometrically but not topologically.
Mesh make_sphere_mesh(int material, glm::vec3 centre, float radius, int rows = 48, int cols = 96);

// A ring around +Y: `major` the ring's radius, `minor` the tube's.
Mesh make_torus_mesh(int material, glm::vec3 centre, float major, float minor, int rows = 48,
                     int cols = 96);

// A cube of half-size `half`, turned by `yaw` radians about +Y: six faces of cells x cells
// squares with their own vertices (sharp edges keep flat normals).
Mesh make_box_mesh(int material, glm::vec3 centre, float half, float yaw, int cells = 16);

// An upright closed cylinder, its axis along +Y through `base_centre` (the centre of its bottom
// cap): the side as a (rows + 1) x (cols + 1) grid and each cap as rings of its own vertices
// (flat normals), `cap_rings` rings from the rim to the centre.
Mesh make_cylinder_mesh(int material, glm::vec3 base_centre, float radius, float height,
                        int rows = 16, int cols = 64, int cap_rings = 8);

// Appends `part` to `mesh` (indices renumbered); the name and material of `mesh` stay.
void append_mesh(Mesh& mesh, const Mesh& part);

}  // namespace prt::bake
