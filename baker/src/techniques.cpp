// SPDX-License-Identifier: MIT
// The baker's techniques, one row each: prt-bake builds `bake <name>` and `trade <name>` from
// this list. A technique implements prt/baker/technique.hpp in baker/src/<name>/.
#include "prt/baker/technique.hpp"

namespace prt::bake {

const Technique& sh_technique();       // baker/src/sh/sh_technique.cpp
const Technique& wavelet_technique();  // baker/src/wavelet/wavelet_technique.cpp
const Technique& pose_technique();     // baker/src/pose/pose_technique.cpp
const Technique& cloth_technique();    // baker/src/cloth/cloth_technique.cpp
const Technique& shadowfield_technique();  // baker/src/shadowfield/shadowfield_technique.cpp

const std::vector<const Technique*>& techniques() {
  static const std::vector<const Technique*> all = {&sh_technique(), &wavelet_technique(),
                                                    &pose_technique(), &cloth_technique(),
                                                    &shadowfield_technique()};
  return all;
}

const Technique* find_technique(const std::string& name) {
  for (const Technique* technique : techniques()) {
    if (name == technique->name()) return technique;
  }
  return nullptr;
}

}  // namespace prt::bake
