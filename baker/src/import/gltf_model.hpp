// SPDX-License-Identifier: MIT
// Internal to the glTF importer: loading a tinygltf::Model with every check the importer relies
// on done up front, and reading accessors safely.
#pragma once

#include <tiny_gltf.h>

#include <string>
#include <vector>

#include "prt/baker/context.hpp"

namespace prt::bake::detail {

// Reads .gltf or .glb at path. Before tinygltf sees the bytes it checks the GLB container (so a
// truncated file is named as such), the JSON, the glTF version, required extensions, external
// buffer files and every index a Draco primitive uses; afterwards every accessor and buffer view
// is validated against the bytes present. Throws Error("<path>: <what>").
tinygltf::Model load_gltf_model(const std::string& path, const Context& ctx);

// One accessor's elements as doubles, count x components, row by row (sparse substitution
// applied). With normalise, integer accessors marked normalized map to [0,1] / [-1,1].
struct AccessorData {
  std::size_t count = 0;
  int components = 0;
  std::vector<double> values;
  const double* element(std::size_t i) const { return values.data() + i * components; }
};

// Throws Error naming the file and what (e.g. "mesh 0 primitive 1 POSITION") when the accessor
// index is invalid or its component count is not one of allowed_components (empty = any).
AccessorData read_accessor(const tinygltf::Model& model, int index, bool normalise,
                           const std::string& file, const std::string& what,
                           const std::vector<int>& allowed_components = {});

}  // namespace prt::bake::detail
