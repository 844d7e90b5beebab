// SPDX-License-Identifier: MIT
// Technique `cloth`: the mesh a bake writes, the quantisation's effect on the tables, the
// self-check through the runtime, and the bake report.
#include <prt/prt.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "prt/baker/text.hpp"

#include "../common/technique_blob.hpp"
#include "cloth_technique.hpp"

namespace prt::bake {
namespace {

// The rows x columns values of factor U V^T, in double.
double reconstruct(const ClothFactor& f, std::uint64_t row, std::uint64_t column) {
  double s = 0.0;
  for (std::uint32_t r = 0; r < f.rank; ++r)
    s += double(f.u[row * f.rank + r]) * double(f.v[column * f.rank + r]);
  return s;
}

double max_factor_difference(const ClothFactor& a, const ClothFactor& b, const ClothGrid& g) {
  double worst = 0.0;
  for (std::uint64_t row = 0; row < g.rows(); ++row)
    for (std::uint64_t column = 0; column < g.columns(); ++column)
      worst = std::max(worst, std::fabs(reconstruct(a, row, column) - reconstruct(b, row, column)));
  return worst;
}

bool same_weave(const prt_cloth_weave& w, const ClothFabric& f) {
  for (int j = 0; j < 2; ++j) {
    if (w.tangent_count[j] != f.threads[j].size()) return false;
    for (std::uint32_t k = 0; k < w.tangent_count[j]; ++k)
      if (w.offsets[j][k] != f.threads[j][k].offset ||
          w.multiplicity[j][k] != f.threads[j][k].multiplicity)
        return false;
  }
  return true;
}

bool same_params(const prt_cloth_params& a, const prt_cloth_params& b) {
  for (int j = 0; j < 2; ++j) {
    const prt_cloth_thread &x = a.threads[j], &y = b.threads[j];
    if (x.eta != y.eta || x.kd != y.kd || x.gamma_s != y.gamma_s || x.gamma_v != y.gamma_v ||
        x.coverage != y.coverage || x.albedo[0] != y.albedo[0] || x.albedo[1] != y.albedo[1] ||
        x.albedo[2] != y.albedo[2])
      return false;
  }
  return true;
}

// A flat patch (normal +Y, warp +X) seen from a grid of views, and a light of wide and sharp
// lobes, some below the horizon: what the self-check shades.
struct CheckScene {
  std::vector<float> normals, warps, views;
  std::vector<prt_cloth_lobe> lobes;
};

CheckScene check_scene() {
  CheckScene s;
  for (int e = 0; e < 6; ++e)
    for (int a = 0; a < 12; ++a) {
      const double el = (5.0 + 16.0 * e) * 3.14159265358979 / 180.0;
      const double az = a * 30.0 * 3.14159265358979 / 180.0;
      s.normals.insert(s.normals.end(), {0.0f, 1.0f, 0.0f});
      s.warps.insert(s.warps.end(), {1.0f, 0.0f, 0.0f});
      s.views.insert(s.views.end(), {float(std::cos(el) * std::cos(az)), float(std::sin(el)),
                                     float(std::cos(el) * std::sin(az))});
    }
  const float sharpness[] = {0.25f, 3.0f, 40.0f, 800.0f, 1e4f};
  const float axes[][3] = {
      {0, 1, 0}, {0.6f, 0.8f, 0}, {0, 0.6f, 0.8f}, {-0.8f, 0.6f, 0}, {0.6f, -0.8f, 0}};
  for (int k = 0; k < 5; ++k)
    s.lobes.push_back({{axes[k][0], axes[k][1], axes[k][2]}, sharpness[k], {1.0f, 0.8f, 0.6f}});
  return s;
}

}  // namespace

glm::vec3 cloth_warp(const glm::vec3& normal, const glm::vec4* tangent) {
  if (tangent) {
    const glm::vec3 t = glm::vec3(*tangent), w = t - glm::dot(t, normal) * normal;
    if (glm::dot(w, w) > 1e-12f) return glm::normalize(w);
  }
  const glm::vec3 n = normal;
  const glm::vec3 a =
      std::fabs(n.x) <= std::fabs(n.y) && std::fabs(n.x) <= std::fabs(n.z)
          ? glm::vec3(1, 0, 0)
          : (std::fabs(n.y) <= std::fabs(n.z) ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1));
  return glm::normalize(a - glm::dot(a, n) * n);
}

ClothMesh cloth_mesh_of(const Scene& scene) {
  ClothMesh out;
  std::uint32_t base = 0;
  for (const Mesh& mesh : scene.meshes) {
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const glm::vec3 p = mesh.positions[v], n = mesh.normals[v];
      const glm::vec3 w = cloth_warp(n, mesh.tangents.empty() ? nullptr : &mesh.tangents[v]);
      out.positions.insert(out.positions.end(), {p.x, p.y, p.z});
      out.normals.insert(out.normals.end(), {n.x, n.y, n.z});
      out.tangents.insert(out.tangents.end(), {w.x, w.y, w.z});
    }
    for (std::uint32_t i : mesh.indices) out.triangles.push_back(base + i);
    base += static_cast<std::uint32_t>(mesh.vertex_count());
  }
  if (out.triangles.empty()) throw Error(scene.source + ": no triangles to bake a cloth on");
  return out;
}

ClothQuantization measure_cloth_quantization(const ClothSection& section,
                                             const DecodedClothSection& stored) {
  ClothQuantization q;
  q.bits = stored.bits;
  for (std::size_t t = 0; t < section.tables.size(); ++t) {
    q.max_abs_error = std::max(
        q.max_abs_error,
        max_factor_difference(section.tables[t].full, stored.section.tables[t].full, section.grid));
    q.max_abs_error = std::max(
        q.max_abs_error,
        max_factor_difference(section.tables[t].cone, stored.section.tables[t].cone, section.grid));
  }
  return q;
}

ClothBlobCheck check_cloth_blob(const std::vector<std::uint8_t>& blob,
                                const ClothSection& section) {
  ClothBlobCheck check;
  SelfCheckAsset loaded = load_for_self_check(blob);
  if (!loaded.asset) {
    check.message = loaded.failure;
    return check;
  }
  prt_cloth_info info = prt::sized<prt_cloth_info>();
  if (prt_cloth_get_info(loaded.asset.get(), &info) != PRT_OK ||
      info.fabric_count != section.fabrics.size() || info.table_count != section.tables.size()) {
    check.message = "the runtime reads other fabric or table counts";
    return check;
  }
  const CheckScene scene = check_scene();
  prt_cloth_pixels pixels = prt::sized<prt_cloth_pixels>();
  pixels.normals = scene.normals.data();
  pixels.warps = scene.warps.data();
  pixels.views = scene.views.data();
  prt_cloth_light light = prt::sized<prt_cloth_light>();
  light.lobe_count = static_cast<std::uint32_t>(scene.lobes.size());
  light.lobes = scene.lobes.data();
  const std::uint32_t count = static_cast<std::uint32_t>(scene.views.size() / 3);
  std::vector<float> rgb(3 * std::size_t(count));
  for (std::uint32_t f = 0; f < info.fabric_count; ++f) {
    const char* name = nullptr;
    prt_cloth_params params = prt::sized<prt_cloth_params>();
    prt_cloth_weave weave = prt::sized<prt_cloth_weave>();
    const ClothFabric& baked = section.fabrics[f];
    if (prt_cloth_get_fabric(loaded.asset.get(), f, &name, &params, &weave, nullptr) != PRT_OK ||
        baked.name != name || !same_params(params, baked.params) || !same_weave(weave, baked)) {
      check.message =
          "fabric " + baked.name + ": the runtime reads another name, parameters or weave";
      return check;
    }
    const prt_result r = prt_cloth_shade(loaded.asset.get(), PRT_BACKEND_CPU, f, nullptr, &light,
                                         nullptr, &pixels, 0, count, rgb.data());
    if (r != PRT_OK) {
      check.message = runtime_failure("prt_cloth_shade", r, loaded.context.get());
      return check;
    }
    for (float x : rgb)
      if (!std::isfinite(x) || x < 0.0f) {
        check.message = "fabric " + baked.name + " shades to a negative or non-finite value";
        return check;
      }
    check.samples_shaded += count;
  }
  check.passed = true;
  check.message = format("%u fabrics, %u tables read back; %zu samples shaded", info.fabric_count,
                         info.table_count, check.samples_shaded);
  return check;
}

void write_cloth_bake_report(const std::string& path, const BakeInput& input,
                             const BakeFacts& facts, const ClothTablesBake& bake,
                             const ClothTablesOptions& options, const ClothQuantization& q,
                             const ClothBlobCheck& check) {
  const ClothGrid& g = bake.section.grid;
  nlohmann::json fabrics = nlohmann::json::array(), tables = nlohmann::json::array();
  for (const ClothFabric& f : bake.section.fabrics) {
    std::vector<std::uint32_t> used;
    for (const auto& thread : f.threads)
      for (const ClothTangent& t : thread)
        if (std::find(used.begin(), used.end(), t.table) == used.end()) used.push_back(t.table);
    std::uint64_t bytes = 0;
    for (std::uint32_t t : used)
      bytes += q.bits == 8 ? bake.tables[t].bytes8 : bake.tables[t].bytes16;
    fabrics.push_back({{"name", f.name}, {"tables", used}, {"table_bytes", bytes}});
  }
  for (const ClothTableReport& t : bake.tables)
    tables.push_back({{"offsets", t.key.offsets},
                      {"multiplicities", t.key.multiplicities},
                      {"offset", t.key.offset()},
                      {"rank", t.full.rank},
                      {"cone_rank", t.cone.rank},
                      {"relative_error", t.full.relative_error},
                      {"cone_relative_error", t.cone.relative_error},
                      {"max_abs_error", std::max(t.full.max_abs_error, t.cone.max_abs_error)},
                      {"bytes16", t.bytes16},
                      {"bytes8", t.bytes8}});
  const nlohmann::json json = {
      {"command", "bake"},
      {"technique", "cloth"},
      {"scene",
       {{"file", input.scene}, {"vertices", facts.vertices}, {"triangles", facts.triangles}}},
      {"grid",
       {{"xi_size", g.xi_size},
        {"lambda_levels", g.lambda_levels},
        {"lambda_min", g.lambda_min},
        {"lambda_max", g.lambda_max},
        {"view_theta", g.view_theta},
        {"view_phi", g.view_phi}}},
      {"factor",
       {{"energy", options.factor.energy},
        {"fixed_rank", options.factor.fixed_rank},
        {"bits", q.bits}}},
      {"fabrics", fabrics},
      {"tables", tables},
      {"seconds", {{"sample", bake.sample_seconds}, {"factor", bake.factor_seconds}}},
      {"threads", facts.threads},
      {"quantization_max_abs_error", q.max_abs_error},
      {"blob", {{"file", input.output}, {"bytes", facts.blob_bytes}}},
      {"self_check",
       {{"passed", check.passed}, {"message", check.message}, {"samples", check.samples_shaded}}},
  };
  std::ofstream file(path);
  if (!file || !(file << json.dump(2) << '\n')) throw Error(path + ": cannot write the report");
}

}  // namespace prt::bake
