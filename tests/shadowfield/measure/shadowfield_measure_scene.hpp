// SPDX-License-Identifier: MIT
// A small `shadowfield` scene for the measurement tests, baked once with small settings: a
// white diffuse box resting on a white diffuse floor under the built-in sky, so the box shadows
// the floor and the two light each other by interreflection.
#pragma once

#include <cstdint>
#include <vector>

#include "prt/baker/mesh_generators.hpp"
#include "prt/baker/shadowfield/shadowfield_bake.hpp"
#include "prt/baker/shadowfield/shadowfield_scenes.hpp"

namespace prt::bake::measure_test {

inline ShadowfieldSceneObject white_object(const char* name, Mesh mesh) {
  ShadowfieldSceneObject object;
  object.name = name;
  Material white;
  white.name = name;
  white.base_color = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  object.mesh.materials.push_back(white);
  mesh.material = 0;
  // The bake reads mesh-local attributes; the object's frame is the mesh's.
  mesh.local_positions = mesh.positions;
  mesh.local_normals = mesh.normals;
  object.mesh.meshes.push_back(std::move(mesh));
  return object;
}

inline ShadowfieldPath still_at(glm::vec3 translation) {
  ShadowfieldPath path;
  path.keyframes.push_back({0.0f, {translation, glm::quat(1.0f, 0.0f, 0.0f, 0.0f), 1.0f}});
  return path;
}

// From (0.2, -0.1) to (-0.3, 0.2) turning 60 degrees about +Y in 2 s, and back in 2 s.
inline ShadowfieldPath sliding_and_turning() {
  ShadowfieldPath path;
  path.duration = 4.0f;
  const glm::quat turned = glm::angleAxis(glm::radians(60.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  path.keyframes.push_back(
      {0.0f,
       {glm::vec3(0.2f, kShadowfieldRestGap, -0.1f), glm::quat(1.0f, 0.0f, 0.0f, 0.0f), 1.0f}});
  path.keyframes.push_back({2.0f, {glm::vec3(-0.3f, kShadowfieldRestGap, 0.2f), turned, 1.0f}});
  return path;
}

// Floor 2 m square at y = 0; a 0.6 m box resting on it off centre (its bottom at y = 0 in its
// frame, lifted by the rest gap), moving on a short path.
inline ShadowfieldSceneDescription box_on_floor() {
  ShadowfieldSceneDescription scene;
  scene.name = "box on floor";
  scene.objects.push_back(white_object("floor", make_plane_mesh("floor", 0, 1.0f, 1.0f, 20, 20)));
  scene.objects.push_back(
      white_object("box", make_box_mesh(0, glm::vec3(0.0f, 0.3f, 0.0f), 0.3f, 0.0f, 4)));
  scene.instances.push_back({0, still_at(glm::vec3(0.0f))});
  scene.instances.push_back({1, sliding_and_turning()});
  scene.camera = {{0.0f, 2.0f, 3.0f}, {0.0f, 0.3f, 0.0f}};
  scene.env = kShadowfieldBuiltinSky;
  return scene;
}

inline ShadowfieldBakeSettings small_bake_settings() {
  ShadowfieldBakeSettings s;
  s.fields.order = 4;
  s.fields.oof_shells = 8;
  s.fields.oof_face_size = 8;
  s.fields.field_directions = 256;
  s.fields.transfer_rays = 256;
  s.basis.size = 8;
  s.basis.lights = 64;
  s.srf.shells = 4;
  s.srf.face_size = 4;
  s.srf.directions = 256;
  return s;
}

inline std::vector<std::vector<std::uint8_t>> bake_blobs(const ShadowfieldSceneDescription& scene,
                                                         const ShadowfieldBakeSettings& settings) {
  std::vector<std::vector<std::uint8_t>> blobs;
  for (const ShadowfieldSceneObject& object : scene.objects) {
    const ShadowfieldBakeResult baked = bake_shadowfield_object(
        object.mesh, make_shadowfield_material(object.material, settings.brdf), settings,
        Context{});
    blobs.push_back(shadowfield_blob_of(baked.object, settings.bits, object.name));
  }
  return blobs;
}

}  // namespace prt::bake::measure_test
