// SPDX-License-Identifier: MIT
// Cloth blobs for prt-cloth's tests, made with the baker (prt/baker/cloth): the six presets of
// prt/baker/cloth/fabrics.hpp with their tables baked on small grids (quick, and coarse), or
// over synthetic tables, with or without a mesh. A synthetic table's
// T and T_c are the constant 1 / (the size of its thread's multiset), the mean of the weights W,
// which sum to at most 1 over a thread (docs/cloth/model.md): each thread then shades as the plain
// average of its tangents' scattering, without the shadowing and masking a bake would tabulate.
// Smooth and cheap to write; enough for an app that shows whatever the runtime shades.
#pragma once

#include <prt/baker/cloth/cloth_blob.hpp>
#include <prt/baker/cloth/cloth_tables.hpp>
#include <prt/baker/cloth/fabrics.hpp>
#include <prt/baker/context.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace prt_cloth_app_test {

// The smallest grids SPEC §7.4 allows: a constant table needs no more.
inline prt::bake::ClothGrid constant_grid() {
  prt::bake::ClothGrid grid;
  grid.xi_size = 2, grid.lambda_levels = 1, grid.lambda_min = grid.lambda_max = 1.0f;
  grid.view_theta = 2, grid.view_phi = 2;
  return grid;
}

inline prt::bake::ClothTable constant_table(const prt::bake::ClothGrid& grid, float value) {
  prt::bake::ClothTable table;
  for (prt::bake::ClothFactor* f : {&table.full, &table.cone}) {
    f->rank = 1;
    f->u.assign(grid.rows(), value);
    f->v.assign(grid.columns(), 1.0f);
  }
  return table;
}

// satin back's 0.67 + 0.33 is 1 + 3e-8 in float, which the CLTH checker refuses (the runtime's
// parameter check allows that slack): the weft's coverage a float step or two lower.
inline prt_cloth_params fitted_coverages(prt_cloth_params params) {
  float& weft = params.threads[1].coverage;
  while (double(params.threads[0].coverage) + double(weft) > 1.0) weft = std::nextafter(weft, 0.0f);
  return params;
}

// The presets called `names` (all six when empty), in that order.
inline std::vector<const prt::bake::ClothPreset*> presets(const std::vector<std::string>& names) {
  std::vector<const prt::bake::ClothPreset*> out;
  if (names.empty())
    for (const prt::bake::ClothPreset& p : prt::bake::cloth_fabrics()) out.push_back(&p);
  for (const std::string& name : names) out.push_back(&prt::bake::cloth_fabric(name));
  return out;
}

// The presets' section with their tables baked by bake_cloth_tables on small grids: 8 x 8 lobe
// directions, 4 sharpness levels over the light's range, 6 x 6 views; seconds to bake.
inline prt::bake::ClothSection baked_section(const std::vector<std::string>& names = {}) {
  std::vector<prt::bake::ClothFabricSource> sources;
  for (const prt::bake::ClothPreset* p : presets(names))
    sources.push_back({p->name, fitted_coverages(p->params), p->weave});
  prt::bake::ClothTablesOptions options;
  options.grid.xi_size = 8;
  options.grid.lambda_levels = 4;
  options.grid.view_theta = 6;
  options.grid.view_phi = 6;
  options.sampling.map_size = 64;
  return prt::bake::bake_cloth_tables(sources, options, prt::bake::Context{}).section;
}

// The presets' section over the constant tables above.
inline prt::bake::ClothSection preset_section(const std::vector<std::string>& names = {}) {
  prt::bake::ClothSection section;
  section.grid = constant_grid();
  for (const prt::bake::ClothPreset* preset : presets(names)) {
    prt::bake::ClothFabric fabric;
    fabric.name = preset->name;
    fabric.params = fitted_coverages(preset->params);
    for (int j = 0; j < 2; ++j) {
      std::uint32_t copies = 0;
      for (std::uint32_t k = 0; k < preset->weave.tangent_count[j]; ++k)
        copies += preset->weave.multiplicity[j][k];
      for (std::uint32_t k = 0; k < preset->weave.tangent_count[j]; ++k) {
        fabric.threads[j].push_back({preset->weave.offsets[j][k], preset->weave.multiplicity[j][k],
                                     std::uint32_t(section.tables.size()), false});
        section.tables.push_back(constant_table(section.grid, 1.0f / float(copies)));
      }
    }
    section.fabrics.push_back(fabric);
  }
  return section;
}

// A sheet bent over a cylinder of radius 1 about +Z: x = sin a, y = cos a - 1 for a in
// [-1.2, 1.2] radians, z in [-1, 1]; normals radial, warp along the bend (d/da) so that its
// threads run across the fold. n x n vertices.
inline prt::bake::ClothMesh bent_sheet(int n = 24) {
  prt::bake::ClothMesh mesh;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double a = -1.2 + 2.4 * i / (n - 1), z = -1.0 + 2.0 * j / (n - 1);
      mesh.positions.insert(mesh.positions.end(),
                            {float(std::sin(a)), float(std::cos(a) - 1.0), float(z)});
      mesh.normals.insert(mesh.normals.end(), {float(std::sin(a)), float(std::cos(a)), 0.0f});
      mesh.tangents.insert(mesh.tangents.end(), {float(std::cos(a)), float(-std::sin(a)), 0.0f});
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const std::uint32_t a = std::uint32_t(j * n + i), b = a + 1, c = a + std::uint32_t(n),
                          d = c + 1;
      mesh.triangles.insert(mesh.triangles.end(), {a, c, b, b, c, d});
    }
  return mesh;
}

}  // namespace prt_cloth_app_test
