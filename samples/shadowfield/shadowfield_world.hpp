// SPDX-License-Identifier: MIT
// The runtime's side of the app: one context, the scene's blobs loaded into it, the runtime's
// scene of their instances, the instances' meshes joined into one world-space mesh to draw, and
// each frame's placements and per-vertex radiance.
#pragma once

#include <prt/prt.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "sample_app.hpp"
#include "scene_file.hpp"

namespace prt::shadowfield_app {

struct Sphere {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};

class ShadowfieldWorld {
 public:
  // Loads every blob (full validation) and adds its object and the instances at their first
  // placement. Throws SceneError naming the blob and quoting the runtime.
  explicit ShadowfieldWorld(const SceneFile& scene);
  ~ShadowfieldWorld();
  ShadowfieldWorld(const ShadowfieldWorld&) = delete;
  ShadowfieldWorld& operator=(const ShadowfieldWorld&) = delete;

  prt_context* context() const { return context_; }
  prt_shadowfield_scene* scene() const { return scene_; }
  std::uint32_t order() const { return order_; }
  std::uint32_t vertex_count() const { return vertex_count_; }
  // The longest loop of the scene's paths (the time slider's range).
  float period() const { return period_; }
  // Bounds of the scene at its first placement (what the camera frames).
  const glm::vec3& lo() const { return lo_; }
  const glm::vec3& hi() const { return hi_; }

  // The instances at `placements` (one per instance): the runtime's transforms and the
  // world-space positions.
  void place(const std::vector<Placement>& placements);
  // An instance's bounding sphere at its current placement.
  Sphere bounding_sphere(std::size_t instance) const;

  // One frame's shading of every instance (on `workers` when not null), timed by the sample.
  prt_result shade(prt::sample::Sample& sample, prt_workers* workers, const float* light_sh_rgb,
                   const glm::vec3& eye, const prt_shadowfield_settings& settings);
  // Radiance of every vertex, instances in order, 3 floats each (the reference's order too).
  const std::vector<float>& radiance() const { return radiance_; }

  // A mesh of every instance's triangles; upload() puts the current positions into it.
  std::unique_ptr<prt::sample::GpuMesh> make_mesh() const;
  void upload(prt::sample::GpuMesh& mesh) const;

 private:
  struct Object {
    prt_asset* asset = nullptr;
    const float* positions = nullptr;
    const std::uint32_t* indices = nullptr;
    std::uint32_t vertex_count = 0, triangle_count = 0;
    Sphere bounds;  // object frame
  };
  prt_context* context_ = nullptr;
  prt_shadowfield_scene* scene_ = nullptr;
  std::vector<Object> objects_;
  std::vector<std::size_t> instance_object_;
  std::vector<std::uint32_t> first_vertex_;  // per instance, in the joined mesh
  std::vector<Placement> placements_;
  std::vector<float> positions_, radiance_;
  std::vector<std::uint32_t> indices_;
  std::uint32_t order_ = 0, vertex_count_ = 0;
  float period_ = 0.0f;
  glm::vec3 lo_{0.0f}, hi_{0.0f};

  void load_object(const SceneObject& object);
  void release();
};

}  // namespace prt::shadowfield_app
