// SPDX-License-Identifier: MIT
// The fabric presets (prt/baker/cloth/fabrics.hpp) as plain values, from a file of their own:
// fabrics.hpp and cloth_blob.hpp both define a prt::bake::ClothFabric, so no file includes both.
#pragma once

#include <prt/prt_cloth.h>

#include <string>
#include <vector>

namespace cloth_test {

struct Preset {
  std::string name;
  prt_cloth_params params{};
  prt_cloth_weave weave{};
};

// The six presets, in the table's order.
std::vector<Preset> presets();
// The preset called `name` (a test failure if there is none).
Preset preset(const std::string& name);

}  // namespace cloth_test
