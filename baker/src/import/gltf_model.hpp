// SPDX-License-Identifier: MIT
// Internal to the glTF importer: loading a tinygltf::Model with every check the importer relies
// on done up front, and reading accessors safely.
#pragma once

#include <tiny_gltf.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "prt/baker/context.hpp"

namespace prt::bake::detail {

// What a keep-going load set aside instead of throwing; each reason is worded as the Error would
// have been, without the leading "<path>: ".
struct BrokenParts {
  // (mesh, primitive) -> why the primitive is unusable: a bad Draco extension or bitstream, an
  // accessor of its that is unusable. tinygltf may have been given the primitive emptied (no
  // attributes, no indices) so that it could load the rest: never read a primitive listed here.
  std::map<std::pair<int, int>, std::string> primitives;
  std::map<int, std::string> images;  // image -> why its bytes do not decode (left empty)
};

// Reads .gltf or .glb at path. Before tinygltf sees the bytes it checks the GLB container (so a
// truncated file is named as such), the JSON, the glTF version, required extensions, external
// buffer files and every index a Draco primitive uses; afterwards every accessor and buffer view
// is validated against the bytes present. Throws Error("<path>: <what>").
// With keep_going, what concerns one primitive or one image is put in *keep_going instead (an
// accessor only primitives use: those primitives; one nothing uses: a warning), and the rest of
// the file still loads; what concerns the file as a whole still throws.
tinygltf::Model load_gltf_model(const std::string& path, const Context& ctx,
                                BrokenParts* keep_going = nullptr);

// The text of an Error about path without its leading "<path>: ".
std::string without_path(const std::string& message, const std::string& path);

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
