// SPDX-License-Identifier: MIT
// The fabric presets of technique `cloth`: Sadeghi et al. 2013's Table II (docs/cloth/model.md,
// "The six fabrics"), as ../shared/assets/tables/cloth_microcylinder_sadeghi2013.json carries
// them, built in: each fabric's live parameters and weave as the runtime takes them.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <prt/prt_cloth.h>

namespace prt::bake {

// Thread 2's albedo scale of satin charmeuse, front and back: the two open sources of the table
// disagree (0.2 or 0.02); docs/cloth/model.md#satin-decision says why it is 0.02.
inline constexpr float kSatinWeftAlbedoScale = 0.02f;

struct ClothPreset {
  std::string name;           // the table's key, e.g. "linen_plain"
  prt_cloth_params params{};  // albedo = A_color x A_scale, angles in radians
  prt_cloth_weave weave{};    // offsets in radians; repeated values merged, in order of first
                              // appearance, with their multiplicities
};

// The six presets, in the table's order.
const std::vector<ClothPreset>& cloth_fabrics();
std::vector<std::string> cloth_fabric_names();
// The preset called `name`, or nullptr.
const ClothPreset* find_cloth_fabric(std::string_view name);
// The preset called `name`; Error naming the presets when there is none.
const ClothPreset& cloth_fabric(std::string_view name);

}  // namespace prt::bake
