// SPDX-License-Identifier: MIT
#include "cloth_blob.hpp"

#include <prt/prt.hpp>

#include <cmath>
#include <cstring>

#include "blob_scene.hpp"
#include "env_image.hpp"

namespace prt::cloth_app {
namespace {

// The names of the techniques a blob holds, for saying what a blob without CLTH is.
std::string technique_names(const prt_asset* asset) {
  const std::uint32_t set = prt_asset_techniques(asset);
  std::string names;
  for (std::uint32_t t = 1; t < 32; ++t) {
    prt_technique_info info = prt::sized<prt_technique_info>();
    if (!(set & (1u << t)) || prt_technique_get_info(prt_technique(t), &info) != PRT_OK) continue;
    names += (names.empty() ? "" : ", ") + std::string(info.name);
  }
  return names.empty() ? "no technique's section" : "technique " + names;
}

// Area-weighted vertex normals (the cross products of the triangles' edges summed).
std::vector<float> normals_from_triangles(const std::vector<float>& p,
                                          const std::vector<std::uint32_t>& indices) {
  std::vector<double> sum(p.size(), 0.0);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const float* a = &p[3 * indices[t]];
    const float* b = &p[3 * indices[t + 1]];
    const float* c = &p[3 * indices[t + 2]];
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) sum[3 * indices[t + k] + i] += n[i];
  }
  std::vector<float> normals(p.size());
  for (std::size_t v = 0; v < p.size(); v += 3) {
    const double length =
        std::sqrt(sum[v] * sum[v] + sum[v + 1] * sum[v + 1] + sum[v + 2] * sum[v + 2]);
    for (int i = 0; i < 3; ++i) normals[v + i] = length > 0.0 ? float(sum[v + i] / length) : 0.0f;
  }
  return normals;
}

}  // namespace

ClothBlob::ClothBlob(const std::string& path) : path_(path) {
  prt_context_desc desc = prt::sized<prt_context_desc>();
  desc.flags = PRT_CONTEXT_READ_ENVIRONMENT;
  if (prt_context_create(&desc, &context_) != PRT_OK)
    throw prt::view::ViewerError("cannot create a prtkit context");
  if (prt_asset_load_file(context_, path.c_str(), PRT_VALIDATE_FULL, &asset_) != PRT_OK) {
    const std::string message = prt_context_last_message(context_);
    prt_context_destroy(context_);
    throw prt::view::ViewerError(path + ": " + message);
  }
  try {
    info_ = prt::sized<prt_cloth_info>();
    if (prt_cloth_get_info(asset_, &info_) != PRT_OK)
      fail("no CLTH section: not a cloth blob (it holds " + technique_names(asset_) +
           "); make one with prt-bake bake cloth");
    read_fabrics();
    const void* data = nullptr;
    std::size_t bytes = 0;
    has_mesh_ = prt_asset_section_data(asset_, PRT_SECTION_VPOS, &data, &bytes) == PRT_OK &&
                prt_asset_section_data(asset_, PRT_SECTION_TRIS, &data, &bytes) == PRT_OK;
  } catch (...) {
    prt_asset_destroy(asset_);
    prt_context_destroy(context_);
    throw;
  }
}

ClothBlob::~ClothBlob() {
  prt_asset_destroy(asset_);
  prt_context_destroy(context_);
}

void ClothBlob::fail(const std::string& what) const {
  throw prt::view::ViewerError(path_ + ": " + what);
}

void ClothBlob::read_fabrics() {
  for (std::uint32_t f = 0; f < info_.fabric_count; ++f) {
    Fabric fabric;
    const char* name = nullptr;
    fabric.defaults = prt::sized<prt_cloth_params>();
    fabric.weave = prt::sized<prt_cloth_weave>();
    prt::view::check_runtime(prt_cloth_get_fabric(asset_, f, &name, &fabric.defaults, &fabric.weave,
                                                  &fabric.table_bytes),
                             "prt_cloth_get_fabric");
    fabric.name = name;
    fabrics_.push_back(fabric);
  }
}

int ClothBlob::find(const std::string& name) const {
  for (std::size_t f = 0; f < fabrics_.size(); ++f)
    if (fabrics_[f].name == name) return int(f);
  return -1;
}

std::string ClothBlob::fabric_names() const {
  std::string names;
  for (const Fabric& f : fabrics_) names += (names.empty() ? "" : ", ") + f.name;
  return names;
}

std::string ClothBlob::mesh_problem() const {
  if (!has_mesh_) return "the blob has no mesh (VPOS, TRIS)";
  const void* data = nullptr;
  std::size_t bytes = 0;
  if (prt_asset_section_data(asset_, PRT_SECTION_VTAN, &data, &bytes) != PRT_OK)
    return "the blob's mesh has no warp per vertex (VTAN), which cloth is shaded with";
  return "";
}

FramedMesh ClothBlob::mesh() const {
  const std::string problem = mesh_problem();
  if (!problem.empty()) fail(problem);
  auto section = [this](std::uint32_t tag, std::size_t unit, auto* out) {
    const void* data = nullptr;
    std::size_t bytes = 0;
    if (prt_asset_section_data(asset_, tag, &data, &bytes) != PRT_OK) return false;
    out->resize(bytes / unit);
    std::memcpy(out->data(), data, out->size() * unit);
    return true;
  };
  FramedMesh mesh;
  section(PRT_SECTION_VPOS, sizeof(float), &mesh.positions);
  section(PRT_SECTION_TRIS, sizeof(std::uint32_t), &mesh.indices);
  section(PRT_SECTION_VTAN, sizeof(float), &mesh.warps);
  if (!section(PRT_SECTION_VNRM, sizeof(float), &mesh.normals))
    mesh.normals = normals_from_triangles(mesh.positions, mesh.indices);
  // The reader checks the sections' sizes against VPOS and the indices against it at full
  // validation; say so here rather than draw out of bounds.
  const std::size_t values = mesh.positions.size();
  if (values % 3 != 0 || mesh.normals.size() != values || mesh.warps.size() != values ||
      mesh.indices.size() % 3 != 0)
    fail("VPOS, VNRM, VTAN or TRIS sizes disagree");
  for (std::uint32_t i : mesh.indices)
    if (i >= mesh.vertex_count()) fail("TRIS index out of range");
  return mesh;
}

}  // namespace prt::cloth_app
