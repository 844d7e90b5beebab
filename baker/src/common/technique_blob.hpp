// SPDX-License-Identifier: MIT
// What every technique's blob and self-check share (private to the baker): the mesh sections a
// blob starts with, and the runtime handles the self-checks load it through.
#pragma once

#include <prt/prt.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/scene.hpp"
#include "prt/format/blob_writer.hpp"

namespace prt::bake {

// A writer holding the sections every technique's blob starts with (formats/SPEC.md §7): INFO
// (skipped when empty), VPOS (required), VNRM (when every vertex has a normal; a non-finite
// normal, which the bakes give zero transfer, is stored as (0, 0, 0) so full validation accepts
// it) and TRIS (required), zstd-compressed, producer "prtkit <version>". The technique adds its
// own section and calls finish().
prt::format::BlobWriter start_technique_blob(const Scene& scene, const std::string& info);

// The section options of a technique section: zstd, required.
prt::format::SectionOptions required_section();

using RuntimeContextPtr = prt::ContextPtr;
using RuntimeAssetPtr = prt::AssetPtr;

// A blob loaded through the runtime at full validation, in a context of its own, for a bake's
// self-check: on failure `asset` is null and `failure` says what failed.
struct SelfCheckAsset {
  RuntimeContextPtr context;
  RuntimeAssetPtr asset;
  std::string failure;
};
SelfCheckAsset load_for_self_check(const std::vector<std::uint8_t>& blob);

// "<what> failed (<result>): <the context's last message>", for self-check reports.
std::string runtime_failure(const char* what, prt_result result, const prt_context* context);

}  // namespace prt::bake
