// SPDX-License-Identifier: MIT
// The bake tests' objects and their run time: generated meshes baked with small settings
// (bake_shadowfield_object), written to blobs, loaded by the runtime at full validation and
// shaded as a scene of instances under a constant sky.
#pragma once

#include <gtest/gtest.h>

#include <prt/prt_shadowfield.h>
#include <prt/prt.hpp>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/mesh_generators.hpp"
#include "prt/baker/shadowfield/shadowfield_bake.hpp"

namespace prt::bake::test {

// A scene of one mesh with one material of base colour `albedo`.
inline Scene one_mesh_scene(Mesh mesh, const glm::vec3& albedo) {
  Scene scene;
  scene.source = "generated";
  Material material;
  material.base_color = glm::vec4(albedo, 1.0f);
  scene.materials.push_back(material);
  mesh.material = 0;
  scene.meshes.push_back(std::move(mesh));
  return scene;
}

// Small grids and few rays, so a bake takes a fraction of a second.
inline ShadowfieldBakeSettings small_bake_settings(std::uint32_t order) {
  ShadowfieldBakeSettings s;
  s.fields.order = order;
  s.fields.oof_shells = 16;
  s.fields.oof_face_size = 8;
  s.fields.field_directions = 1024;
  s.fields.transfer_rays = 256;
  s.basis.size = 8;
  s.basis.lights = 64;
  s.srf.shells = 4;
  s.srf.face_size = 6;
  s.srf.directions = 1024;
  return s;
}

// The blob of a diffuse bake of `scene`.
inline std::vector<std::uint8_t> diffuse_blob(const Scene& scene,
                                              const ShadowfieldBakeSettings& settings) {
  const ShadowfieldBakeResult baked =
      bake_shadowfield_object(scene, ShadowfieldMaterial{}, settings, Context{});
  return shadowfield_blob_of(baked.object, settings.bits, "");
}

// A constant radiance `value` in SH of `order`, RGB coefficient-major: L_00 = sqrt(4 pi) value.
inline std::vector<float> constant_sky(std::uint32_t order, float value) {
  std::vector<float> light(3u * order * order, 0.0f);
  for (int c = 0; c < 3; ++c) light[c] = static_cast<float>(std::sqrt(4.0 * M_PI) * value);
  return light;
}

struct Placed {
  std::size_t blob = 0;  // index into the blobs
  glm::vec3 translation{0.0f};
};

// Every instance's outgoing radiance (vertex-major RGB) towards `eye` after `bounces`, through
// the runtime on `backend`: blobs loaded at full validation, one object each, instances
// unrotated at scale 1.
inline std::vector<std::vector<float>> shade_instances(
    const std::vector<std::vector<std::uint8_t>>& blobs, const std::vector<Placed>& instances,
    const std::vector<float>& light, const glm::vec3& eye, std::uint32_t bounces,
    prt_backend backend = PRT_BACKEND_CPU) {
  auto [context, made] = prt::create_context();
  EXPECT_EQ(made, PRT_OK);
  std::vector<prt::AssetPtr> assets;
  for (const auto& blob : blobs) {
    auto [asset, loaded] =
        prt::load_asset_memory(context.get(), blob.data(), blob.size(), PRT_VALIDATE_FULL);
    EXPECT_EQ(loaded, PRT_OK) << prt_context_last_message(context.get());
    assets.push_back(std::move(asset));
  }
  prt_shadowfield_scene* raw = nullptr;
  EXPECT_EQ(prt_shadowfield_scene_create(context.get(), std::uint32_t(instances.size()), &raw),
            PRT_OK);
  const std::unique_ptr<prt_shadowfield_scene, void (*)(prt_shadowfield_scene*)> scene(
      raw, prt_shadowfield_scene_destroy);
  std::vector<std::uint32_t> objects(assets.size());
  for (std::size_t i = 0; i < assets.size(); ++i)
    EXPECT_EQ(prt_shadowfield_scene_add_object(raw, assets[i].get(), &objects[i]), PRT_OK);
  std::vector<std::vector<float>> rgb;
  for (const Placed& placed : instances) {
    prt_shadowfield_transform t{};
    t.struct_size = sizeof t;
    t.rotation[0] = t.rotation[4] = t.rotation[8] = 1.0f;
    for (int a = 0; a < 3; ++a) t.translation[a] = placed.translation[a];
    t.scale = 1.0f;
    std::uint32_t instance = 0;
    EXPECT_EQ(prt_shadowfield_scene_add_instance(raw, objects[placed.blob], &t, &instance), PRT_OK);
    rgb.emplace_back(3u * prt_shadowfield_instance_vertex_count(raw, instance));
  }
  std::vector<float*> out;
  for (auto& values : rgb) out.push_back(values.data());
  prt_shadowfield_settings settings{};
  settings.struct_size = sizeof settings;
  settings.bounces = bounces;
  settings.backend = backend;
  const float eye_xyz[3] = {eye.x, eye.y, eye.z};
  EXPECT_EQ(prt_shadowfield_shade(raw, light.data(), eye_xyz, &settings, out.data()), PRT_OK)
      << prt_context_last_message(context.get());
  return rgb;
}

// The vertex of `mesh` nearest `point`.
inline std::size_t nearest_vertex(const Mesh& mesh, const glm::vec3& point) {
  std::size_t best = 0;
  for (std::size_t v = 1; v < mesh.positions.size(); ++v) {
    if (glm::distance(mesh.positions[v], point) < glm::distance(mesh.positions[best], point))
      best = v;
  }
  return best;
}

}  // namespace prt::bake::test
