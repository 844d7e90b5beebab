// SPDX-License-Identifier: MIT
// The six fabric presets: Sadeghi et al. 2013, Table II, as the shared table carries it, written
// as that table writes it (degrees, A_color and A_scale, the tangent curves' control points) and
// turned into the runtime's structs once.
#include "prt/baker/cloth/fabrics.hpp"

#include <cmath>
#include <vector>

#include "../common/numbers.hpp"
#include "prt/baker/context.hpp"

namespace prt::bake {
namespace {

// One thread as the table gives it.
struct ThreadRow {
  double eta;
  double a_color[3];
  double a_scale;
  double kd;
  double gamma_s_deg, gamma_v_deg;
  double coverage;
  // Owned, since rows are copied out of the helpers that build them.
  std::vector<double> offsets_deg;
};

struct FabricRow {
  const char* name;
  ThreadRow threads[2];
};

float radians(double degrees) {
  return static_cast<float>(degrees * kPi / 180.0);
}

prt_cloth_thread thread_params(const ThreadRow& row) {
  prt_cloth_thread t{};
  t.eta = static_cast<float>(row.eta);
  for (int c = 0; c < 3; ++c) t.albedo[c] = static_cast<float>(row.a_color[c] * row.a_scale);
  t.kd = static_cast<float>(row.kd);
  t.gamma_s = radians(row.gamma_s_deg);
  t.gamma_v = radians(row.gamma_v_deg);
  t.coverage = static_cast<float>(row.coverage);
  return t;
}

// The thread's multiset as distinct offsets with multiplicities, in order of first appearance.
void thread_weave(const ThreadRow& row, int j, prt_cloth_weave& weave) {
  std::uint32_t& count = weave.tangent_count[j];
  for (const double degrees : row.offsets_deg) {
    const float tau = radians(degrees);
    std::uint32_t k = 0;
    while (k < count && weave.offsets[j][k] != tau) ++k;
    if (k == count) {
      weave.offsets[j][count] = tau;
      weave.multiplicity[j][count] = 0;
      ++count;
    }
    ++weave.multiplicity[j][k];
  }
}

ClothPreset fabric_of(const FabricRow& row) {
  ClothPreset fabric;
  fabric.name = row.name;
  fabric.params.struct_size = sizeof(prt_cloth_params);
  fabric.weave.struct_size = sizeof(prt_cloth_weave);
  for (int j = 0; j < 2; ++j) {
    fabric.params.threads[j] = thread_params(row.threads[j]);
    thread_weave(row.threads[j], j, fabric.weave);
  }
  return fabric;
}

// Satin charmeuse's thread 2, front and back alike but for its coverage.
ThreadRow satin_weft(double coverage) {
  return {1.539, {1.0, 0.37, 0.3}, kSatinWeftAlbedoScale, 0.7, 30, 60, coverage, {0}};
}

std::vector<ClothPreset> build_fabrics() {
  const ThreadRow satin_warp_front = {
      1.539, {1.0, 0.37, 0.3}, 0.035, 0.1, 2.5, 5, 0.9, {-32, -32, -18, 0, 0, 18, 32, 32}};
  const ThreadRow satin_warp_back = {
      1.539, {1.0, 0.37, 0.3}, 0.035, 0.1, 2.5, 5, 0.67, {-30, -30, 30, 30, -5, -5, 5, 5}};
  const FabricRow rows[] = {
      {"linen_plain",
       {{1.46, {0.2, 0.8, 1.0}, 0.3, 0.3, 12, 24, 0.33, {-25, 25}},
        {1.46, {0.2, 0.8, 1.0}, 0.3, 0.3, 12, 24, 0.33, {-25, 25}}}},
      {"silk_crepe_de_chine",
       {{1.345, {1.0, 0.95, 0.05}, 0.12, 0.2, 5, 10, 0.75, {-35, -35, 35, 35}},
        {1.345, {1.0, 0.95, 0.05}, 0.16, 0.3, 18, 32, 0.25, {0}}}},
      {"polyester_satin_charmeuse", {satin_warp_front, satin_weft(0.1)}},
      {"polyester_satin_charmeuse_back", {satin_warp_back, satin_weft(0.33)}},
      {"silk_shot",
       {{1.345, {0.1, 1.0, 0.4}, 0.2, 0.1, 4, 8, 0.86, {-25, -25, 25, 25}},
        {1.345, {1.0, 0.0, 0.1}, 0.6, 0.1, 5, 10, 0.14, {0}}}},
      {"velvet",
       {{1.46, {0.05, 0.02, 0.0}, 0.3, 0.1, 6, 12, 0.5, {-90, -50}},
        {1.46, {0.05, 0.02, 0.0}, 0.3, 0.1, 6, 12, 0.5, {-90, -55, 55, 90}}}},
  };
  std::vector<ClothPreset> fabrics;
  for (const FabricRow& row : rows) fabrics.push_back(fabric_of(row));
  return fabrics;
}

}  // namespace

const std::vector<ClothPreset>& cloth_fabrics() {
  static const std::vector<ClothPreset> fabrics = build_fabrics();
  return fabrics;
}

std::vector<std::string> cloth_fabric_names() {
  std::vector<std::string> names;
  for (const ClothPreset& fabric : cloth_fabrics()) names.push_back(fabric.name);
  return names;
}

const ClothPreset* find_cloth_fabric(std::string_view name) {
  for (const ClothPreset& fabric : cloth_fabrics())
    if (fabric.name == name) return &fabric;
  return nullptr;
}

const ClothPreset& cloth_fabric(std::string_view name) {
  if (const ClothPreset* fabric = find_cloth_fabric(name)) return *fabric;
  std::string known;
  for (const std::string& n : cloth_fabric_names()) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown fabric '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace prt::bake
