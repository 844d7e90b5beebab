// SPDX-License-Identifier: MIT
// The ray-throughput roofline the benchmarks compare with: a raw Embree scene with no prtkit code
// in the way.
#pragma once

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "prt/baker/embree_scene.hpp"
#include "prt/baker/scene.hpp"

namespace prt_bench {

// A raw Embree device and scene over a Scene's non-degenerate triangles.
struct RawEmbree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  explicit RawEmbree(const prt::bake::Scene& s) {
    device = rtcNewDevice(nullptr);
    scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    for (const prt::bake::Mesh& mesh : s.meshes) {
      std::vector<std::uint32_t> kept;
      for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        if (prt::bake::is_degenerate_triangle(mesh, t)) continue;
        kept.insert(kept.end(), mesh.indices.begin() + 3 * t, mesh.indices.begin() + 3 * t + 3);
      }
      if (kept.empty()) continue;
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, mesh.positions.size()));
      std::memcpy(v, mesh.positions.data(), mesh.positions.size() * 12);
      auto* i = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, kept.size() / 3));
      std::memcpy(i, kept.data(), kept.size() * 4);
      rtcCommitGeometry(g);
      rtcAttachGeometry(scene, g);
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(scene);
  }
  ~RawEmbree() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  int widest_packet() const {
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) return 16;
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) return 8;
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED)) return 4;
    return 1;
  }
  RawEmbree(const RawEmbree&) = delete;
  RawEmbree& operator=(const RawEmbree&) = delete;
};

inline void set_ftz_daz() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

}  // namespace prt_bench
