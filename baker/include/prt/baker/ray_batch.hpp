// SPDX-License-Identifier: MIT
// The bakes' shared visibility core: one vertex's directions cast from one origin as occlusion
// or nearest-hit rays, in Embree packets by default.
//
// A direction on or below the horizon of the normal (!(dot(n, d) > 0)) is never cast and counts
// as not visible: the bakes give it no weight. The others are cast with the EmbreeScene's
// occlusion test (same origin, tnear, tfar, mask), so every mode gives each direction the bit
// EmbreeScene::occluded would.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/embree_scene.hpp"

namespace prt::bake {

enum class RayBatchMode {
  Packet16,  // rtcOccluded16 over the directions above the horizon, 16 at a time (default)
  Single,    // rtcOccluded1 per direction: the reference the others agree with
  Stream,    // rtcOccluded1M over all of them at once
};

const char* ray_batch_mode_name(RayBatchMode mode);

// Not thread-safe: it owns scratch buffers; use one per task or thread. The EmbreeScene must
// outlive it.
class RayBatch {
 public:
  explicit RayBatch(const EmbreeScene& scene, RayBatchMode mode = RayBatchMode::Packet16);
  ~RayBatch();
  RayBatch(const RayBatch&) = delete;
  RayBatch& operator=(const RayBatch&) = delete;

  // visible[i] = 1 when directions[i] is above the horizon of `normal` and the ray from
  // `origin` along it is not blocked within [tnear, tfar], else 0, in the input order.
  // Directions need not be unit length (t is in units of |d|). Returns the rays cast.
  std::size_t cast(const glm::vec3& origin, const glm::vec3& normal, const glm::vec3* directions,
                   std::size_t count, unsigned char* visible, float tnear = 0.0f,
                   float tfar = INFINITY);

  // found[i] = 1 and hits[i] = the nearest hit, as EmbreeScene::intersect reports it, when
  // directions[i] is above the horizon of `normal` and the ray hits within [tnear, tfar]; else
  // found[i] = 0 and hits[i] is left alone. Packet16 casts rtcIntersect16 packets, the other
  // modes one ray at a time. Returns the rays cast.
  std::size_t intersect(const glm::vec3& origin, const glm::vec3& normal,
                        const glm::vec3* directions, std::size_t count, RayHit* hits,
                        unsigned char* found, float tnear = 0.0f, float tfar = INFINITY);

  RayBatchMode mode() const { return mode_; }

 private:
  struct Scratch;  // Embree ray buffers, kept out of this header
  // The input indices of the directions above the horizon of `normal`; the others get `below`.
  const std::vector<std::uint32_t>& above_horizon(const glm::vec3& normal,
                                                  const glm::vec3* directions, std::size_t count,
                                                  unsigned char* flags, unsigned char below);
  const EmbreeScene& scene_;
  RayBatchMode mode_;
  std::unique_ptr<Scratch> scratch_;
};

}  // namespace prt::bake
