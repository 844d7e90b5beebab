// SPDX-License-Identifier: MIT
// EmbreeScene's Embree handles, private to the baker: ray_batch.cpp casts packets into the same
// RTCScene without widening EmbreeScene's public interface.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/embree_scene.hpp"

namespace prt::bake {

// Collected by Embree's error callback; read after each call that can fail.
struct DeviceErrors {
  std::string first;
};

// Every mask bit set: Debian's Embree has RAY_MASK on, and a zero mask hits nothing.
constexpr std::uint32_t kEmbreeAllMask = 0xFFFFFFFFu;

// An occlusion or intersection ray as EmbreeScene casts it.
inline RTCRay make_embree_ray(const glm::vec3& origin, const glm::vec3& dir, float tnear,
                              float tfar) {
  RTCRay ray;
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.dir_x = dir.x;
  ray.dir_y = dir.y;
  ray.dir_z = dir.z;
  ray.tnear = tnear;
  ray.tfar = tfar;
  ray.time = 0.0f;
  ray.mask = kEmbreeAllMask;
  ray.id = 0;
  ray.flags = 0;
  return ray;
}

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
