// SPDX-License-Identifier: MIT
// The scenes of technique `shadowfield` (docs/shadowfield/scenes.md): rigid objects, each baked
// alone in its own frame, and their instances placed at run time on scripted, looping paths.
// The trade, the benchmark and the app take them by name; the app reads the JSON form.
//
// Frames: the world is glTF's (+Y up, metres). An object's frame is its mesh's: the presets
// centre every mesh on its bounds horizontally and put its lowest point at y = 0, so an instance
// rests on the floor (y = 0) when its translation's y is the rest gap, whatever its scale and
// its turn about +Y. An instance places its object by world = scale * rotation * local +
// translation.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "prt/baker/scene.hpp"
#include "prt/baker/shadowfield/shadowfield_brdf.hpp"
#include "prt/io/rigid_path.hpp"

namespace prt::bake {

// How an object reflects: Lambertian, or one of the glossy models of shadowfield_brdf.hpp (the
// bake separates it into K terms). The albedo is the mesh's base colour either way.
enum class ShadowfieldBrdfModel { Diffuse, Phong, Ggx };

struct ShadowfieldMaterialDescription {
  ShadowfieldBrdfModel model = ShadowfieldBrdfModel::Diffuse;
  PhongBrdf phong;  // read when model is Phong
  GgxBrdf ggx;      // read when model is Ggx
};

struct ShadowfieldSceneObject {
  std::string name;
  Scene mesh;  // object frame: one or more meshes, base colours in its materials
  ShadowfieldMaterialDescription material;
};

// A rigid placement (world = scale * rotation * local + translation) and a scripted, looping
// keyframe path of them: prt_io's, which the shadowfield app shares. check() and at() throw
// io::Error.
using ShadowfieldPlacement = io::RigidPlacement;
using ShadowfieldKeyframe = io::RigidKeyframe;
using ShadowfieldPath = io::RigidPath;

struct ShadowfieldInstance {
  std::size_t object = 0;  // index into ShadowfieldSceneDescription::objects
  ShadowfieldPath path;
};

struct ShadowfieldCamera {
  glm::vec3 eye{0.0f, 1.0f, 4.0f};
  glm::vec3 target{0.0f};  // looked at with +Y up
};

// The environment a scene is lit by: the built-in sky (make_demo_sky), or a map of the shared
// assets, by its path relative to the shared folder (e.g. "assets/envmaps/grace_cross.hdr").
inline constexpr const char* kShadowfieldBuiltinSky = "builtin:sky";

struct ShadowfieldSceneDescription {
  std::string name;
  std::vector<ShadowfieldSceneObject> objects;
  std::vector<ShadowfieldInstance> instances;
  ShadowfieldCamera camera;
  std::string env = kShadowfieldBuiltinSky;

  // Vertices over every instance (an object placed twice counts twice): the run time's work.
  std::size_t instanced_vertex_count() const;
};

// The gap between a resting object's lowest point and the floor's top, in metres: small enough
// to look like contact, large enough that the bake's rays never start inside the floor.
inline constexpr float kShadowfieldRestGap = 1e-3f;

// The presets, by name: "teapot", "bunny", "room" (these read meshes under
// shared_dir/assets/meshes) and "procedural" (generated only).
std::vector<std::string> shadowfield_scene_names();
// Throws Error for an unknown name or a missing or unreadable asset.
ShadowfieldSceneDescription make_shadowfield_scene(const std::string& name,
                                                   const std::string& shared_dir);
// Whether a preset reads shared assets (so cannot be made without the shared folder).
bool shadowfield_scene_needs_shared(const std::string& name);

// What the JSON file holds: the description without the meshes, each object named by the blob
// that holds its bake (a path relative to the JSON file).
struct ShadowfieldSceneFileObject {
  std::string name;
  std::string blob;
};

struct ShadowfieldSceneFile {
  std::string name;
  std::vector<ShadowfieldSceneFileObject> objects;
  std::vector<ShadowfieldInstance> instances;
  ShadowfieldCamera camera;
  std::string env = kShadowfieldBuiltinSky;
};

// blob_names: one per object, in order. Throws Error when the counts differ, a path is invalid
// or the file cannot be written.
void write_shadowfield_scene_json(const ShadowfieldSceneDescription& description,
                                  const std::vector<std::string>& blob_names,
                                  const std::string& path);
// Throws Error naming the file and what is wrong (unreadable, not the schema, an instance naming
// no object, a path check() rejects).
ShadowfieldSceneFile read_shadowfield_scene_json(const std::string& path);

}  // namespace prt::bake
