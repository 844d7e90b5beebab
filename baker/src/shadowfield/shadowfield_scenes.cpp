// SPDX-License-Identifier: MIT
// The preset scenes of technique `shadowfield` (docs/shadowfield/scenes.md).
#include "prt/baker/shadowfield/shadowfield_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <utility>

#include <glm/gtc/constants.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/mesh_generators.hpp"

namespace prt::bake {
namespace {

constexpr float kTwoPi = 2.0f * glm::pi<float>();

// The floor every preset stands its objects on: a square in y = 0 (its top), centred.
constexpr int kFloorVerticesPerSide = 64;

Material base_colour(std::string name, glm::vec3 colour) {
  Material m;
  m.name = std::move(name);
  m.base_color = glm::vec4(colour, 1.0f);
  return m;
}

// The bake reads mesh-local attributes for rigid objects; here the object frame is the mesh's.
void keep_as_local(Scene& scene) {
  for (Mesh& mesh : scene.meshes) {
    mesh.local_positions = mesh.positions;
    mesh.local_normals = mesh.normals;
  }
}

// Centres the object on its bounds horizontally and puts its lowest point at y = 0, so that a
// turn about +Y and a uniform scale keep it standing on its origin.
void stand_on_origin(Scene& scene) {
  glm::vec3 lo, hi;
  scene.bounds(lo, hi);
  const glm::vec3 offset(-0.5f * (lo.x + hi.x), -lo.y, -0.5f * (lo.z + hi.z));
  for (Mesh& mesh : scene.meshes) {
    for (glm::vec3& p : mesh.positions) p += offset;
  }
  keep_as_local(scene);
}

// The largest side of the object's bounding box, to size it in the world.
float largest_extent(const Scene& scene) {
  glm::vec3 lo, hi;
  scene.bounds(lo, hi);
  const glm::vec3 size = hi - lo;
  return std::max({size.x, size.y, size.z});
}

ShadowfieldSceneObject object_from_mesh(std::string name, Mesh mesh, glm::vec3 colour,
                                        ShadowfieldMaterialDescription material = {}) {
  ShadowfieldSceneObject object;
  object.name = name;
  object.mesh.source = "generated: " + name;
  object.mesh.materials.push_back(base_colour(name, colour));
  mesh.material = 0;
  object.mesh.meshes.push_back(std::move(mesh));
  object.material = material;
  stand_on_origin(object.mesh);
  return object;
}

ShadowfieldSceneObject object_from_asset(const std::string& name, const std::string& shared_dir,
                                         const std::string& file, glm::vec3 colour,
                                         ShadowfieldMaterialDescription material = {}) {
  const std::filesystem::path path = std::filesystem::path(shared_dir) / "assets" / "meshes" / file;
  if (!std::filesystem::exists(path))
    throw Error(path.string() + ": missing (shadowfield scenes read the shared assets)");
  ShadowfieldSceneObject object;
  object.name = name;
  object.mesh = import_scene(path.string(), Context{});
  object.mesh.materials = {base_colour(name, colour)};
  for (Mesh& mesh : object.mesh.meshes) mesh.material = 0;
  object.material = material;
  stand_on_origin(object.mesh);
  return object;
}

ShadowfieldMaterialDescription phong(double exponent, double specular, double diffuse) {
  ShadowfieldMaterialDescription m;
  m.model = ShadowfieldBrdfModel::Phong;
  m.phong = PhongBrdf{exponent, specular, diffuse};
  return m;
}

ShadowfieldMaterialDescription ggx(double alpha, double f0) {
  ShadowfieldMaterialDescription m;
  m.model = ShadowfieldBrdfModel::Ggx;
  m.ggx = GgxBrdf{alpha, f0};
  return m;
}

ShadowfieldSceneObject make_floor(float half) {
  const int cells = kFloorVerticesPerSide - 1;
  return object_from_mesh("floor", make_plane_mesh("floor", 0, half, half, cells, cells),
                          {0.70f, 0.70f, 0.68f});
}

glm::quat yaw(float radians) {
  return glm::angleAxis(radians, glm::vec3(0.0f, 1.0f, 0.0f));
}

ShadowfieldPath still(glm::vec3 translation, glm::quat rotation = yaw(0.0f)) {
  ShadowfieldPath path;
  path.keyframes.push_back({0.0f, {translation, rotation, 1.0f}});
  return path;
}

// `count` keyframes evenly spread over `duration`, keyframe j placed by place(j / count).
ShadowfieldPath sampled_path(int count, float duration,
                             const std::function<ShadowfieldPlacement(float)>& place) {
  ShadowfieldPath path;
  path.duration = duration;
  for (int j = 0; j < count; ++j) {
    const float phase = float(j) / float(count);
    path.keyframes.push_back({phase * duration, place(phase)});
  }
  return path;
}

// A slow loop around a rectangle, turning a quarter at each corner, resting on the floor.
ShadowfieldPath slide_and_turn(float half_x, float half_z, float scale) {
  const glm::vec2 corners[4] = {
      {-half_x, half_z}, {half_x, half_z}, {half_x, -half_z}, {-half_x, -half_z}};
  return sampled_path(4, 16.0f, [&](float phase) {
    const glm::vec2 c = corners[int(std::lround(phase * 4.0f)) % 4];
    return ShadowfieldPlacement{{c.x, kShadowfieldRestGap, c.y}, yaw(phase * kTwoPi), scale};
  });
}

// One object on the floor, sized so its largest side is `size` metres, on a slow path.
ShadowfieldSceneDescription object_on_floor(std::string name, ShadowfieldSceneObject object,
                                            float size) {
  ShadowfieldSceneDescription scene;
  scene.name = std::move(name);
  const float scale = size / largest_extent(object.mesh);
  scene.objects.push_back(make_floor(2.0f * size));
  scene.objects.push_back(std::move(object));
  scene.instances.push_back({0, still(glm::vec3(0.0f))});
  scene.instances.push_back({1, slide_and_turn(0.4f * size, 0.3f * size, scale)});
  scene.camera = {{0.0f, 1.6f * size, 3.2f * size}, {0.0f, 0.3f * size, 0.0f}};
  scene.env = "assets/envmaps/grace_cross.hdr";
  return scene;
}

ShadowfieldSceneDescription make_teapot(const std::string& shared_dir) {
  return object_on_floor("teapot",
                         object_from_asset("teapot", shared_dir, "teapot.obj",
                                           {0.80f, 0.28f, 0.20f}, phong(10.0, 0.7, 0.3)),
                         1.0f);
}

ShadowfieldSceneDescription make_bunny(const std::string& shared_dir) {
  return object_on_floor(
      "bunny", object_from_asset("bunny", shared_dir, "stanford-bunny.obj", {0.85f, 0.80f, 0.70f}),
      1.0f);
}

// A carousel: `scales.size()` objects evenly spaced on a circle around the origin, turning
// together one revolution per loop; the odd ones also move in and out twice a loop (so
// neighbours pass close), and each spins about its own axis 0, 1 or 2 extra turns (few enough
// that consecutive keyframes stay well under half a turn apart, where slerp is unambiguous).
struct Carousel {
  float radius = 1.0f;
  float swing = 0.0f;  // the odd objects' radial amplitude
  float duration = 24.0f;
  int keyframes = 12;
};

ShadowfieldPath carousel_path(const Carousel& c, int index, int count, float scale, int spin) {
  return sampled_path(c.keyframes, c.duration, [&](float phase) {
    const float angle = kTwoPi * (float(index) / float(count) + phase);
    const float r = c.radius + (index % 2 ? c.swing * std::sin(2.0f * kTwoPi * phase) : 0.0f);
    return ShadowfieldPlacement{{r * std::sin(angle), kShadowfieldRestGap, r * std::cos(angle)},
                                yaw(angle + float(spin) * kTwoPi * phase),
                                scale};
  });
}

void add_carousel(ShadowfieldSceneDescription& scene, const Carousel& carousel,
                  std::vector<std::pair<ShadowfieldSceneObject, float>> objects_and_sizes) {
  const int count = int(objects_and_sizes.size());
  for (int i = 0; i < count; ++i) {
    auto& [object, size] = objects_and_sizes[std::size_t(i)];
    const float scale = size / largest_extent(object.mesh);
    scene.instances.push_back(
        {scene.objects.size(), carousel_path(carousel, i, count, scale, i % 3)});
    scene.objects.push_back(std::move(object));
  }
}

// A wall of the room: x in [-half, half], y in [0, height], facing +Z, gridded.
ShadowfieldSceneObject make_wall(float half, float height) {
  Mesh wall = make_grid_mesh("wall", 0, 30, 64, [&](float u, float v) {
    return SurfacePoint{{half - 2.0f * half * u, height * v, 0.0f}, {0.0f, 0.0f, 1.0f}};
  });
  return object_from_mesh("wall", std::move(wall), {0.80f, 0.78f, 0.72f});
}

ShadowfieldSceneDescription make_room(const std::string& shared_dir) {
  const float half = 3.0f;
  ShadowfieldSceneDescription scene;
  scene.name = "room";
  scene.objects = {make_floor(half), make_wall(half, 2.0f)};
  scene.instances.push_back({0, still(glm::vec3(0.0f))});
  // Back, left and right walls, one object placed three times; the front stays open to the view.
  const float quarter = 0.25f * kTwoPi;
  scene.instances.push_back({1, still({0.0f, kShadowfieldRestGap, -half})});
  scene.instances.push_back({1, still({-half, kShadowfieldRestGap, 0.0f}, yaw(quarter))});
  scene.instances.push_back({1, still({half, kShadowfieldRestGap, 0.0f}, yaw(-quarter))});
  add_carousel(
      scene, Carousel{1.6f, 0.45f, 24.0f, 12},
      {{object_from_asset("teapot", shared_dir, "teapot.obj", {0.80f, 0.28f, 0.20f},
                          phong(10.0, 0.7, 0.3)),
        0.9f},
       {object_from_asset("spot", shared_dir, "spot.obj", {0.90f, 0.85f, 0.80f}), 0.8f},
       {object_from_mesh("sphere", make_sphere_mesh(0, glm::vec3(0.0f), 1.0f, 32, 64),
                         {0.95f, 0.75f, 0.35f}, ggx(0.3, 0.9)),
        0.8f},
       {object_from_mesh("torus", make_torus_mesh(0, glm::vec3(0.0f), 0.7f, 0.3f, 32, 64),
                         {0.25f, 0.45f, 0.85f}),
        0.9f},
       {object_from_mesh("box", make_box_mesh(0, glm::vec3(0.0f), 1.0f, 0.0f, 16),
                         {0.30f, 0.70f, 0.35f}),
        0.6f},
       {object_from_mesh("cylinder", make_cylinder_mesh(0, glm::vec3(0.0f), 0.5f, 1.2f, 16, 64, 8),
                         {0.85f, 0.85f, 0.80f}, phong(10.0, 0.5, 0.5)),
        0.8f}});
  scene.camera = {{0.0f, 4.2f, 6.8f}, {0.0f, 0.3f, 0.0f}};
  scene.env = kShadowfieldBuiltinSky;
  return scene;
}

ShadowfieldSceneDescription make_procedural() {
  ShadowfieldSceneDescription scene;
  scene.name = "procedural";
  scene.objects.push_back(make_floor(2.0f));
  scene.instances.push_back({0, still(glm::vec3(0.0f))});
  add_carousel(scene, Carousel{1.0f, 0.3f, 16.0f, 12},
               {{object_from_mesh("sphere", make_sphere_mesh(0, glm::vec3(0.0f), 1.0f),
                                  {0.80f, 0.32f, 0.18f}, phong(10.0, 0.7, 0.3)),
                 0.8f},
                {object_from_mesh("torus", make_torus_mesh(0, glm::vec3(0.0f), 0.7f, 0.3f),
                                  {0.20f, 0.35f, 0.75f}),
                 0.8f},
                {object_from_mesh("box", make_box_mesh(0, glm::vec3(0.0f), 1.0f, 0.0f),
                                  {0.85f, 0.85f, 0.80f}),
                 0.6f}});
  scene.camera = {{0.0f, 2.2f, 4.2f}, {0.0f, 0.3f, 0.0f}};
  scene.env = kShadowfieldBuiltinSky;
  return scene;
}

}  // namespace

std::size_t ShadowfieldSceneDescription::instanced_vertex_count() const {
  std::size_t n = 0;
  for (const ShadowfieldInstance& instance : instances) {
    n += objects.at(instance.object).mesh.vertex_count();
  }
  return n;
}

std::vector<std::string> shadowfield_scene_names() {
  return {"teapot", "bunny", "room", "procedural"};
}

bool shadowfield_scene_needs_shared(const std::string& name) {
  return name != "procedural";
}

ShadowfieldSceneDescription make_shadowfield_scene(const std::string& name,
                                                   const std::string& shared_dir) {
  if (name == "teapot") return make_teapot(shared_dir);
  if (name == "bunny") return make_bunny(shared_dir);
  if (name == "room") return make_room(shared_dir);
  if (name == "procedural") return make_procedural();
  throw Error("unknown shadowfield scene '" + name +
              "' (expected teapot, bunny, room or procedural)");
}

}  // namespace prt::bake
