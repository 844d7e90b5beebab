// SPDX-License-Identifier: MIT
// Technique `sh` in `prt-bake scene` (prt/baker/scene_bake.hpp): it suits static diffuse
// objects; its ladder climbs the order, each at 8 then 16 bits where that is fewer bytes; its
// blobs are shaded through the runtime for the measurement.
#include <prt/prt_sh.h>
#include <prt/prt_sh_asset.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "prt/baker/scene_bake.hpp"
#include "prt/baker/sh/env_sh.hpp"

#include "../common/trade_common.hpp"
#include "sh_technique.hpp"

namespace prt::bake {

namespace {
// Enough directions that the transfer's own noise stays well under the smallest budgets.
constexpr const char* kSceneRays = "1024";
}  // namespace

std::vector<Rung> sh_scene_ladder(int bounces) {
  struct Candidate {
    std::uint32_t order;
    int bits;
  };
  std::vector<Candidate> candidates;
  for (std::uint32_t order = 2; order <= 8; ++order) {
    for (int bits : {8, 16}) candidates.push_back({order, bits});
  }
  // Bytes per vertex follow order^2 x bits; at a tie the lower order (fewer coefficients to
  // shade) comes first.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) {
                     return a.order * a.order * a.bits < b.order * b.order * b.bits;
                   });
  std::vector<Rung> ladder;
  for (const Candidate& c : candidates) {
    Rung rung;
    rung.args = {"--order", std::to_string(c.order), "--bits", std::to_string(c.bits), "--rays",
                 kSceneRays};
    if (bounces > 0) {
      rung.args.insert(rung.args.end(),
                       {"--transfer", "interreflected", "--bounces", std::to_string(bounces)});
    } else {
      rung.args.insert(rung.args.end(), {"--transfer", "shadowed"});
    }
    ladder.push_back(std::move(rung));
  }
  return ladder;
}

std::vector<glm::vec3> sh_scene_shade(const std::vector<std::uint8_t>& blob,
                                      const io::EnvMap& light, const Context&) {
  const trade::RuntimeAsset loaded = trade::load_runtime_asset(blob);
  prt_sh_info info = prt::sized<prt_sh_info>();
  trade::check_runtime(prt_sh_get_info(loaded.asset.get(), &info), "prt_sh_get_info");
  const std::vector<float> rgb = project_env_sh(light, info.order).to_float();
  std::vector<float> shaded(std::size_t(info.vertex_count) * 3);
  trade::check_runtime(prt_sh_shade(loaded.asset.get(), PRT_BACKEND_CPU, rgb.data(), 0,
                                    info.vertex_count, shaded.data()),
                       "prt_sh_shade");
  return trade::as_vec3(shaded);
}

}  // namespace prt::bake
