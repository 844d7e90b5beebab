// SPDX-License-Identifier: MIT
// EmbreeScene's Embree handles, private to the baker: ray_batch.cpp casts packets into the same
// RTCScene without widening EmbreeScene's public interface.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <string>
#include <vector>

#include "prt/baker/embree_scene.hpp"

namespace prt::bake {

// Collected by Embree's error callback; read after each call that can fail.
struct DeviceErrors {
  std::string first;
};

struct EmbreeScene::Impl {
  DeviceErrors errors;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<std::uint32_t> geometry_mesh;                // geomID -> mesh index
  std::vector<std::vector<std::uint32_t>> geometry_prims;  // geomID, primID -> triangle index

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
  void check(const char* what) const {
    if (!errors.first.empty()) throw Error(std::string(what) + ": " + errors.first);
  }
};

}  // namespace prt::bake
