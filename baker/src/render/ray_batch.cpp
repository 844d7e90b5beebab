// SPDX-License-Identifier: MIT
#include "prt/baker/ray_batch.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <vector>

#include "embree_scene_impl.hpp"

namespace prt::bake {
namespace {

constexpr std::size_t kPacket = 16;

// Lanes [0, lanes) of a packet carry directions[above[first + k]] from `origin`; the rest are
// switched off (valid = 0) with a harmless direction.
void fill_packet(const glm::vec3& origin, const glm::vec3* directions,
                 const std::vector<std::uint32_t>& above, std::size_t first, std::size_t lanes,
                 float tnear, float tfar, int* valid, RTCRay16& packet) {
  for (std::size_t k = 0; k < kPacket; ++k) {
    const bool on = k < lanes;
    valid[k] = on ? -1 : 0;
    const glm::vec3 d = on ? directions[above[first + k]] : glm::vec3(0.0f, 0.0f, 1.0f);
    packet.org_x[k] = origin.x;
    packet.org_y[k] = origin.y;
    packet.org_z[k] = origin.z;
    packet.dir_x[k] = d.x;
    packet.dir_y[k] = d.y;
    packet.dir_z[k] = d.z;
    packet.tnear[k] = tnear;
    packet.tfar[k] = tfar;
    packet.time[k] = 0.0f;
    packet.mask[k] = kEmbreeAllMask;
    packet.id[k] = 0;
    packet.flags[k] = 0;
  }
}

}  // namespace

struct RayBatch::Scratch {
  std::vector<std::uint32_t> above;  // input indices of the directions above the horizon
  std::vector<RTCRay> stream;
};

const char* ray_batch_mode_name(RayBatchMode mode) {
  switch (mode) {
    case RayBatchMode::Packet16:
      return "packet16";
    case RayBatchMode::Single:
      return "single";
    case RayBatchMode::Stream:
      return "stream";
  }
  return "unknown";
}

RayBatch::RayBatch(const EmbreeScene& scene, RayBatchMode mode)
    : scene_(scene), mode_(mode), scratch_(std::make_unique<Scratch>()) {}

RayBatch::~RayBatch() = default;

const std::vector<std::uint32_t>& RayBatch::above_horizon(const glm::vec3& normal,
                                                          const glm::vec3* directions,
                                                          std::size_t count, unsigned char* flags,
                                                          unsigned char below) {
  std::vector<std::uint32_t>& above = scratch_->above;
  above.clear();
  for (std::size_t i = 0; i < count; ++i) {
    // The bakes' horizon rule, written as they wrote it so a NaN also counts as below.
    if (glm::dot(normal, directions[i]) > 0.0f) {
      above.push_back(static_cast<std::uint32_t>(i));
    } else {
      flags[i] = below;
    }
  }
  return above;
}

std::size_t RayBatch::cast(const glm::vec3& origin, const glm::vec3& normal,
                           const glm::vec3* directions, std::size_t count, unsigned char* visible,
                           float tnear, float tfar) {
  const std::vector<std::uint32_t>& above = above_horizon(normal, directions, count, visible, 0);
  if (above.empty()) return 0;
  RTCScene scene = scene_.impl_->scene;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  switch (mode_) {
    case RayBatchMode::Single:
      for (std::uint32_t i : above) {
        RTCRay ray = make_embree_ray(origin, directions[i], tnear, tfar);
        rtcOccluded1(scene, &context, &ray);
        visible[i] = ray.tfar < 0.0f ? 0 : 1;  // Embree sets tfar = -inf on occlusion
      }
      break;
    case RayBatchMode::Packet16:
      for (std::size_t first = 0; first < above.size(); first += kPacket) {
        const std::size_t lanes = std::min(kPacket, above.size() - first);
        alignas(64) int valid[kPacket];
        alignas(64) RTCRay16 packet;
        fill_packet(origin, directions, above, first, lanes, tnear, tfar, valid, packet);
        rtcOccluded16(valid, scene, &context, &packet);
        for (std::size_t k = 0; k < lanes; ++k) {
          visible[above[first + k]] = packet.tfar[k] < 0.0f ? 0 : 1;
        }
      }
      break;
    case RayBatchMode::Stream: {
      std::vector<RTCRay>& rays = scratch_->stream;
      rays.resize(above.size());
      for (std::size_t k = 0; k < above.size(); ++k) {
        rays[k] = make_embree_ray(origin, directions[above[k]], tnear, tfar);
      }
      rtcOccluded1M(scene, &context, rays.data(), static_cast<unsigned>(rays.size()),
                    sizeof(RTCRay));
      for (std::size_t k = 0; k < above.size(); ++k) {
        visible[above[k]] = rays[k].tfar < 0.0f ? 0 : 1;
      }
      break;
    }
  }
  return above.size();
}

std::size_t RayBatch::intersect(const glm::vec3& origin, const glm::vec3& normal,
                                const glm::vec3* directions, std::size_t count, RayHit* hits,
                                unsigned char* found, float tnear, float tfar) {
  const std::vector<std::uint32_t>& above = above_horizon(normal, directions, count, found, 0);
  if (above.empty()) return 0;
  const EmbreeScene::Impl& im = *scene_.impl_;
  if (mode_ != RayBatchMode::Packet16) {  // the reference: one ray at a time
    for (std::uint32_t i : above)
      found[i] = scene_.intersect(origin, directions[i], &hits[i], tnear, tfar) ? 1 : 0;
    return above.size();
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (std::size_t first = 0; first < above.size(); first += kPacket) {
    const std::size_t lanes = std::min(kPacket, above.size() - first);
    alignas(64) int valid[kPacket];
    alignas(64) RTCRayHit16 packet;
    fill_packet(origin, directions, above, first, lanes, tnear, tfar, valid, packet.ray);
    for (std::size_t k = 0; k < kPacket; ++k) {
      packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.primID[k] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, im.scene, &context, &packet);
    for (std::size_t k = 0; k < lanes; ++k) {
      const std::uint32_t i = above[first + k], geometry = packet.hit.geomID[k];
      found[i] = geometry == RTC_INVALID_GEOMETRY_ID ? 0 : 1;
      if (!found[i]) continue;
      hits[i].t = packet.ray.tfar[k];
      hits[i].mesh = im.geometry_mesh[geometry];
      hits[i].triangle = im.geometry_prims[geometry][packet.hit.primID[k]];
      hits[i].u = packet.hit.u[k];
      hits[i].v = packet.hit.v[k];
    }
  }
  return above.size();
}

}  // namespace prt::bake
