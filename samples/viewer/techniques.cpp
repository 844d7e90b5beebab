// SPDX-License-Identifier: MIT
// The techniques prt-view shades: one row per technique folder. A blob that holds several is
// drawn with the first of them in this order unless --technique names another.
#include "cloth/cloth_view.hpp"
#include "pose/pose_view.hpp"
#include "sh/sh_view.hpp"
#include "shadowfield/shadowfield_view.hpp"
#include "view_techniques.hpp"
#include "wavelet/wavelet_view.hpp"

namespace prt::view {

const std::vector<MakeViewTechnique>& view_technique_table() {
  static const std::vector<MakeViewTechnique> kTable = {
      make_sh_view,
      make_wavelet_view,
      make_pose_view,
      make_cloth_view,
      make_shadowfield_view,
  };
  return kTable;
}

}  // namespace prt::view
