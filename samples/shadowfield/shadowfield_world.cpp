// SPDX-License-Identifier: MIT
#include "shadowfield_world.hpp"

#include <prt/prt.hpp>

#include <algorithm>
#include <string>

namespace prt::shadowfield_app {
namespace {

prt_shadowfield_transform runtime_transform(const Placement& p) {
  prt_shadowfield_transform t = prt::sized<prt_shadowfield_transform>();
  p.to_rows(t.rotation);
  t.translation[0] = p.translation.x, t.translation[1] = p.translation.y;
  t.translation[2] = p.translation.z;
  t.scale = p.scale;
  return t;
}

Sphere bounds_of(const float* positions, std::uint32_t count) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (std::uint32_t v = 0; v < count; ++v) {
    const glm::vec3 p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  Sphere s;
  s.centre = 0.5f * (lo + hi);
  for (std::uint32_t v = 0; v < count; ++v)
    s.radius = std::max(s.radius, glm::length(glm::vec3(positions[3 * v], positions[3 * v + 1],
                                                        positions[3 * v + 2]) -
                                              s.centre));
  return s;
}

}  // namespace

ShadowfieldWorld::ShadowfieldWorld(const SceneFile& scene) {
  prt_context_desc desc = prt::sized<prt_context_desc>();
  desc.flags = PRT_CONTEXT_READ_ENVIRONMENT;
  if (prt_context_create(&desc, &context_) != PRT_OK)
    throw SceneError("cannot create a prtkit context");
  try {
    if (prt_shadowfield_scene_create(context_, std::uint32_t(scene.instances.size()), &scene_) !=
        PRT_OK)
      throw SceneError(std::string("prt_shadowfield_scene_create: ") +
                       prt_context_last_message(context_));
    for (const SceneObject& object : scene.objects) load_object(object);
    for (const SceneInstance& instance : scene.instances) {
      const Object& o = objects_[instance.object];
      const prt_shadowfield_transform t = runtime_transform(instance.path.at(0.0f));
      std::uint32_t index = 0;
      if (prt_shadowfield_scene_add_instance(scene_, std::uint32_t(instance.object), &t, &index) !=
          PRT_OK)
        throw SceneError(scene.path + ": instance " + std::to_string(instance_object_.size()) +
                         ": " + prt_context_last_message(context_));
      first_vertex_.push_back(vertex_count_);
      for (std::uint32_t i = 0; i < 3 * o.triangle_count; ++i)
        indices_.push_back(vertex_count_ + o.indices[i]);
      vertex_count_ += o.vertex_count;
      instance_object_.push_back(instance.object);
      if (instance.path.moves()) period_ = std::max(period_, instance.path.duration);
    }
    order_ = prt_shadowfield_scene_order(scene_);
    positions_.assign(3u * vertex_count_, 0.0f);
    radiance_.assign(3u * vertex_count_, 0.0f);
    std::vector<Placement> first;
    for (const SceneInstance& instance : scene.instances) first.push_back(instance.path.at(0.0f));
    place(first);
    lo_ = glm::vec3(INFINITY), hi_ = glm::vec3(-INFINITY);
    for (std::uint32_t v = 0; v < vertex_count_; ++v) {
      const glm::vec3 p(positions_[3 * v], positions_[3 * v + 1], positions_[3 * v + 2]);
      lo_ = glm::min(lo_, p), hi_ = glm::max(hi_, p);
    }
  } catch (...) {
    release();
    throw;
  }
}

ShadowfieldWorld::~ShadowfieldWorld() {
  release();
}

void ShadowfieldWorld::release() {
  prt_shadowfield_scene_destroy(scene_);
  scene_ = nullptr;
  for (Object& o : objects_) prt_asset_destroy(o.asset);
  objects_.clear();
  if (context_) prt_context_destroy(context_);
  context_ = nullptr;
}

void ShadowfieldWorld::load_object(const SceneObject& object) {
  Object o;
  if (prt_asset_load_file(context_, object.blob.c_str(), PRT_VALIDATE_FULL, &o.asset) != PRT_OK)
    throw SceneError(object.blob + ": " + prt_context_last_message(context_));
  objects_.push_back(o);  // owned from here, destroyed with the world
  Object& added = objects_.back();
  const void* positions = nullptr;
  const void* indices = nullptr;
  std::size_t position_bytes = 0, index_bytes = 0;
  if (prt_asset_section_data(added.asset, PRT_SECTION_VPOS, &positions, &position_bytes) !=
          PRT_OK ||
      prt_asset_section_data(added.asset, PRT_SECTION_TRIS, &indices, &index_bytes) != PRT_OK)
    throw SceneError(object.blob + ": no mesh (VPOS and TRIS sections) to draw");
  added.positions = static_cast<const float*>(positions);
  added.vertex_count = std::uint32_t(position_bytes / (3 * sizeof(float)));
  added.indices = static_cast<const std::uint32_t*>(indices);
  added.triangle_count = std::uint32_t(index_bytes / (3 * sizeof(std::uint32_t)));
  added.bounds = bounds_of(added.positions, added.vertex_count);
  std::uint32_t index = 0;
  const prt_result result = prt_shadowfield_scene_add_object(scene_, added.asset, &index);
  if (result != PRT_OK)
    throw SceneError(object.blob + ": not a shadowfield object the scene takes: " +
                     prt_context_last_message(context_));
  prt_shadowfield_info info = prt::sized<prt_shadowfield_info>();
  if (prt_shadowfield_get_info(added.asset, &info) != PRT_OK ||
      info.vertex_count != added.vertex_count)
    throw SceneError(object.blob + ": VPOS has " + std::to_string(added.vertex_count) +
                     " vertices but SFLD " + std::to_string(info.vertex_count));
}

void ShadowfieldWorld::place(const std::vector<Placement>& placements) {
  placements_ = placements;
  for (std::size_t i = 0; i < placements.size(); ++i) {
    const prt_shadowfield_transform t = runtime_transform(placements[i]);
    if (prt_shadowfield_scene_set_transform(scene_, std::uint32_t(i), &t) != PRT_OK)
      throw SceneError("instance " + std::to_string(i) + ": " + prt_context_last_message(context_));
    const Object& o = objects_[instance_object_[i]];
    float* out = &positions_[3u * first_vertex_[i]];
    for (std::uint32_t v = 0; v < o.vertex_count; ++v) {
      const glm::vec3 p = placements[i].apply(
          glm::vec3(o.positions[3 * v], o.positions[3 * v + 1], o.positions[3 * v + 2]));
      out[3 * v] = p.x, out[3 * v + 1] = p.y, out[3 * v + 2] = p.z;
    }
  }
}

Sphere ShadowfieldWorld::bounding_sphere(std::size_t instance) const {
  const Sphere& local = objects_[instance_object_[instance]].bounds;
  const Placement& p = placements_[instance];
  return {p.apply(local.centre), local.radius * p.scale};
}

prt_result ShadowfieldWorld::shade(prt::sample::Sample& sample, prt_workers* workers,
                                   const float* light_sh_rgb, const glm::vec3& eye,
                                   const prt_shadowfield_settings& settings) {
  std::vector<float*> out(instance_object_.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = &radiance_[3u * first_vertex_[i]];
  const float at[3] = {eye.x, eye.y, eye.z};
  return sample.time_shading([&] {
    return workers ? prt_shadowfield_shade_workers(workers, scene_, light_sh_rgb, at, &settings,
                                                   out.data())
                   : prt_shadowfield_shade(scene_, light_sh_rgb, at, &settings, out.data());
  });
}

std::unique_ptr<prt::sample::GpuMesh> ShadowfieldWorld::make_mesh() const {
  return std::make_unique<prt::sample::GpuMesh>(positions_.data(), vertex_count_, indices_.data(),
                                                std::uint32_t(indices_.size() / 3));
}

void ShadowfieldWorld::upload(prt::sample::GpuMesh& mesh) const {
  mesh.upload_positions(positions_.data());
}

}  // namespace prt::shadowfield_app
