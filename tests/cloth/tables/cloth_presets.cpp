// SPDX-License-Identifier: MIT
#include "cloth_presets.hpp"

#include <stdexcept>

#include "prt/baker/cloth/fabrics.hpp"

namespace cloth_test {

std::vector<Preset> presets() {
  std::vector<Preset> out;
  for (const prt::bake::ClothFabric& f : prt::bake::cloth_fabrics())
    out.push_back({f.name, f.params, f.weave});
  return out;
}

Preset preset(const std::string& name) {
  const prt::bake::ClothFabric& f = prt::bake::cloth_fabric(name);
  return {f.name, f.params, f.weave};
}

}  // namespace cloth_test
