// SPDX-License-Identifier: MIT
// The PSTR section of technique `pose` (formats/SPEC.md §7.3) from a skeleton and a fitted model.
#pragma once

#include <cstdint>
#include <vector>

#include "prt/baker/pose/pose_model.hpp"
#include "prt/baker/pose/pose_training.hpp"

namespace prt::bake {

// The raw bytes of the section (little-endian, zero-padded); Error when the layout cannot hold
// the model (order, joints, dimensions, bits) or the skeleton and model disagree.
std::vector<std::uint8_t> encode_pstr_section(const PoseSkeleton& skeleton, const PoseModel& model,
                                              ShTransferKind kind, int bounces);

}  // namespace prt::bake
