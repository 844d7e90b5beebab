// SPDX-License-Identifier: MIT
#include "prt/baker/ray_batch.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <vector>

#include "embree_scene_impl.hpp"

namespace prt::bake {
namespace {

constexpr std::size_t kPacket = 16;

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

std::size_t RayBatch::cast(const glm::vec3& origin, const glm::vec3& normal,
                           const glm::vec3* directions, std::size_t count, unsigned char* visible,
                           float tnear, float tfar) {
  std::vector<std::uint32_t>& above = scratch_->above;
  above.clear();
  for (std::size_t i = 0; i < count; ++i) {
    // The bakes' horizon rule, written as they wrote it so a NaN also counts as below.
    if (glm::dot(normal, directions[i]) > 0.0f) {
      above.push_back(static_cast<std::uint32_t>(i));
    } else {
      visible[i] = 0;
    }
  }
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

}  // namespace prt::bake
