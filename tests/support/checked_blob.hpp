// SPDX-License-Identifier: MIT
// A technique's blob baked in process as `prt-bake <t>` bakes it: options as the command line
// spells them, bake, quantize, write, then the blob's self-check through the runtime, for the
// tests that compare blobs of one object at different settings.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/technique.hpp"

namespace prt_test {

// Throws prt::bake::Error for an unknown technique or a blob that fails its self-check.
inline std::vector<std::uint8_t> checked_blob(const std::string& technique,
                                              const std::vector<std::string>& args,
                                              const prt::bake::Scene& scene,
                                              const std::string& scene_name,
                                              const prt::bake::Context& ctx) {
  const prt::bake::Technique* entry = prt::bake::find_technique(technique);
  if (!entry) throw prt::bake::Error("no technique " + technique);
  const std::unique_ptr<prt::bake::TechniqueBake> bake = entry->make_bake();
  prt::bake::apply_option_args(bake->options(), args);
  prt::bake::BakeInput input;
  input.scene = scene_name;
  bake->bake(scene, input, ctx);
  bake->quantize();
  std::vector<std::uint8_t> blob = bake->write(scene, input);
  const prt::bake::SelfCheck check = bake->self_check(blob);
  if (!check.passed) throw prt::bake::Error(technique + " self-check: " + check.message);
  return blob;
}

}  // namespace prt_test
