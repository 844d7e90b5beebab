// SPDX-License-Identifier: MIT
#include "prt/baker/embree_scene.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <limits>
#include <string>

#include "../common/numbers.hpp"
#include "embree_scene_impl.hpp"

namespace prt::bake {
namespace {

void on_embree_error(void* user, RTCError code, const char* message) {
  auto* errors = static_cast<DeviceErrors*>(user);
  if (errors->first.empty()) {
    errors->first = "Embree error " + std::to_string(static_cast<int>(code)) + ": " +
                    (message ? message : "(no message)");
  }
}

}  // namespace

bool is_degenerate_triangle(const Mesh& mesh, std::size_t triangle) {
  const std::size_t n = mesh.positions.size();
  const std::uint32_t a = mesh.indices[3 * triangle], b = mesh.indices[3 * triangle + 1],
                      c = mesh.indices[3 * triangle + 2];
  if (a >= n || b >= n || c >= n || a == b || b == c || a == c) return true;
  const glm::vec3 &p0 = mesh.positions[a], &p1 = mesh.positions[b], &p2 = mesh.positions[c];
  if (!finite(p0) || !finite(p1) || !finite(p2)) return true;
  const glm::dvec3 e1 = glm::dvec3(p1) - glm::dvec3(p0), e2 = glm::dvec3(p2) - glm::dvec3(p0);
  const double twice_area = glm::length(glm::cross(e1, e2));
  const double longest = std::max({glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e2 - e1, e2 - e1)});
  // Zero area up to float rounding: the vertices are collinear or coincide.
  return !(twice_area > 1e-7 * longest);
}

EmbreeScene::EmbreeScene(const Scene& scene, const Context& ctx) : impl_(std::make_unique<Impl>()) {
  Impl& im = *impl_;
  im.device = rtcNewDevice(nullptr);
  if (!im.device) throw Error("cannot create an Embree device");
  rtcSetDeviceErrorFunction(im.device, on_embree_error, &im.errors);
  im.scene = rtcNewScene(im.device);
  rtcSetSceneBuildQuality(im.scene, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(im.scene, RTC_SCENE_FLAG_ROBUST);
  im.check("creating the Embree scene");

  lo_ = glm::vec3(std::numeric_limits<float>::max());
  hi_ = glm::vec3(-std::numeric_limits<float>::max());
  // The occluders follow the meshes, numbered on from them (RayHit::mesh).
  const std::size_t meshes = scene.meshes.size();
  for (std::size_t m = 0; m < meshes + scene.occluders.size(); ++m) {
    const Mesh& mesh = m < meshes ? scene.meshes[m] : scene.occluders[m - meshes];
    std::vector<std::uint32_t> kept;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      if (is_degenerate_triangle(mesh, t)) {
        ++dropped_triangles_;
      } else {
        kept.push_back(static_cast<std::uint32_t>(t));
      }
    }
    if (kept.empty()) continue;

    RTCGeometry geometry = rtcNewGeometry(im.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(std::uint32_t), kept.size()));
    if (!vertices || !indices) {
      rtcReleaseGeometry(geometry);
      im.check("allocating Embree buffers");
      throw Error("cannot allocate Embree buffers");
    }
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      // Non-finite vertices are only used by dropped triangles; keep Embree's buffer finite.
      const glm::vec3 p = finite(mesh.positions[v]) ? mesh.positions[v] : glm::vec3(0.0f);
      vertices[3 * v] = p.x;
      vertices[3 * v + 1] = p.y;
      vertices[3 * v + 2] = p.z;
    }
    for (std::size_t k = 0; k < kept.size(); ++k) {
      for (int corner = 0; corner < 3; ++corner) {
        const std::uint32_t index = mesh.indices[3 * kept[k] + corner];
        indices[3 * k + corner] = index;
        lo_ = glm::min(lo_, mesh.positions[index]);
        hi_ = glm::max(hi_, mesh.positions[index]);
      }
    }
    rtcCommitGeometry(geometry);
    const unsigned id = rtcAttachGeometry(im.scene, geometry);
    rtcReleaseGeometry(geometry);  // the scene holds its own reference
    im.check("building the Embree scene");
    if (im.geometry_mesh.size() <= id) {
      im.geometry_mesh.resize(id + 1);
      im.geometry_prims.resize(id + 1);
    }
    im.geometry_mesh[id] = static_cast<std::uint32_t>(m);
    triangle_count_ += kept.size();
    im.geometry_prims[id] = std::move(kept);
  }
  rtcCommitScene(im.scene);
  im.check("building the Embree BVH");

  if (triangle_count_ == 0) lo_ = hi_ = glm::vec3(0.0f);
  const float extent = std::max({std::abs(lo_.x), std::abs(lo_.y), std::abs(lo_.z), std::abs(hi_.x),
                                 std::abs(hi_.y), std::abs(hi_.z)});
  const float radius = 0.5f * glm::length(hi_ - lo_);
  epsilon_ = 1e-5f * std::max(extent + radius, 1e-6f);
  if (dropped_triangles_ > 0) {
    ctx.warn("ray-tracing scene: dropped " + std::to_string(dropped_triangles_) +
             " degenerate triangles (out-of-range or repeated index, non-finite position, or "
             "zero area)");
  }
}

EmbreeScene::~EmbreeScene() = default;

bool EmbreeScene::occluded(const glm::vec3& origin, const glm::vec3& dir, float tnear,
                           float tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = make_embree_ray(origin, dir, tnear, tfar);
  rtcOccluded1(impl_->scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar = -inf on occlusion
}

bool EmbreeScene::intersect(const glm::vec3& origin, const glm::vec3& dir, RayHit* hit, float tnear,
                            float tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayhit;
  rayhit.ray = make_embree_ray(origin, dir, tnear, tfar);
  rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rayhit);
  if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit->t = rayhit.ray.tfar;
  hit->mesh = impl_->geometry_mesh[rayhit.hit.geomID];
  hit->triangle = impl_->geometry_prims[rayhit.hit.geomID][rayhit.hit.primID];
  hit->u = rayhit.hit.u;
  hit->v = rayhit.hit.v;
  return true;
}

}  // namespace prt::bake
