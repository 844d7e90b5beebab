// SPDX-License-Identifier: MIT
// Internal to the importers: the per-format readers and the mesh attribute helpers they share.
#pragma once

#include <string>

#include "prt/baker/scene.hpp"

namespace prt::bake::detail {

Scene import_gltf(const std::string& path, const Context& ctx, const ImportOptions& options);
Scene import_obj(const std::string& path, const Context& ctx);

// Area-weighted vertex normals from positions and indices (degenerate triangles add nothing;
// vertices no triangle gives a direction get +Y).
std::vector<glm::vec3> area_weighted_normals(const std::vector<glm::vec3>& positions,
                                             const std::vector<std::uint32_t>& indices);

// Per-vertex tangents from UVs: per-triangle tangent/bitangent accumulated (area-weighted, as in
// MikkTSpace's basic form), Gram-Schmidt against the normal, w = +1 when cross(n, t) points to
// decreasing v (glTF). Vertices without a usable UV gradient get any unit vector orthogonal to
// the normal, w = +1.
std::vector<glm::vec4> uv_tangents(const std::vector<glm::vec3>& positions,
                                   const std::vector<glm::vec3>& normals,
                                   const std::vector<glm::vec2>& texcoords,
                                   const std::vector<std::uint32_t>& indices);

// Checks indices (count multiple of 3, each in range, at least one triangle) and that every
// attribute array has one entry per vertex; throws Error("<file>: <what>").
void validate_mesh(const Mesh& mesh, const std::string& file, const std::string& what);

// Fills normals (generating and flagging where absent) and tangents (generating from UVs where
// absent) of a mesh whose world positions and indices are set.
void complete_mesh_attributes(Mesh& mesh);

}  // namespace prt::bake::detail
