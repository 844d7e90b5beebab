// SPDX-License-Identifier: MIT
#include "technique_blob.hpp"

#include <cmath>
#include <vector>

#include "prt/format/blob_layout.h"

namespace prt::bake {

prt::format::SectionOptions required_section() {
  prt::format::SectionOptions options;
  options.compression = prt::format::Compression::kZstd;
  options.required = true;
  return options;
}

prt::format::BlobWriter start_technique_blob(const Scene& scene, const std::string& info) {
  std::vector<float> positions, normals;
  std::vector<std::uint32_t> triangles;
  bool all_normals = true;
  for (const Mesh& mesh : scene.meshes) {
    const auto base = static_cast<std::uint32_t>(positions.size() / 3);
    for (const glm::vec3& p : mesh.positions) positions.insert(positions.end(), {p.x, p.y, p.z});
    all_normals = all_normals && mesh.normals.size() == mesh.positions.size();
    for (const glm::vec3& n : mesh.normals) {
      const bool finite = std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z);
      normals.insert(normals.end(),
                     {finite ? n.x : 0.0f, finite ? n.y : 0.0f, finite ? n.z : 0.0f});
    }
    for (std::uint32_t i : mesh.indices) triangles.push_back(base + i);
  }
  prt::format::SectionOptions optional;
  optional.compression = prt::format::Compression::kZstd;
  const prt::format::SectionOptions required = required_section();
  const std::size_t vertices = scene.vertex_count();
  prt::format::BlobWriter writer;
  writer.set_producer("prtkit " PRT_VERSION_STRING);
  if (!info.empty()) writer.add_section(PRT_BLOB_TAG_INFO, info.data(), info.size(), info.size());
  // The floats and indices are stored as in memory: the baker builds on little-endian hosts only.
  writer.add_section(PRT_BLOB_TAG_VPOS, positions.data(), positions.size() * sizeof(float),
                     vertices, required);
  if (all_normals) {
    writer.add_section(PRT_BLOB_TAG_VNRM, normals.data(), normals.size() * sizeof(float), vertices,
                       optional);
  }
  writer.add_section(PRT_BLOB_TAG_TRIS, triangles.data(), triangles.size() * sizeof(std::uint32_t),
                     triangles.size() / 3, required);
  return writer;
}

SelfCheckAsset load_for_self_check(const std::vector<std::uint8_t>& blob) {
  SelfCheckAsset loaded;
  prt_context* context = nullptr;
  if (prt_context_create(nullptr, &context) != PRT_OK) {
    loaded.failure = "cannot create a runtime context";
    return loaded;
  }
  loaded.context.reset(context);
  prt_asset* asset = nullptr;
  const prt_result result =
      prt_asset_load_memory(context, blob.data(), blob.size(), PRT_VALIDATE_FULL, &asset);
  if (result != PRT_OK) {
    loaded.failure = runtime_failure("prt_asset_load_memory (full validation)", result, context);
    return loaded;
  }
  loaded.asset.reset(asset);
  return loaded;
}

std::string runtime_failure(const char* what, prt_result result, const prt_context* context) {
  return std::string(what) + " failed (" + std::to_string(static_cast<int>(result)) +
         "): " + prt_context_last_message(context);
}

}  // namespace prt::bake
