// SPDX-License-Identifier: MIT
// The app's side of a shadowfield scene file (docs/shadowfield/scenes.md, "The scene file"):
// scene.json read without the baker, its scripted paths evaluated as the baker's ShadowfieldPath
// evaluates them, and a scene file written back for one placement of every instance (what the
// reference tool renders).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace prt::shadowfield_app {

// What the app reports and exits 1 on.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// world = scale * rotation * local + translation.
struct Placement {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z; unit
  float scale = 1.0f;

  glm::vec3 apply(const glm::vec3& local) const { return scale * (rotation * local) + translation; }
  // The runtime's transform: row-major rotation, translation, scale.
  void to_rows(float rotation_rows[9]) const;
};

struct Keyframe {
  float time = 0.0f;
  Placement placement;
};

// Keyframes at ascending times in [0, duration): translation and scale linear, rotation by
// slerp, looping back to the first keyframe a period later. One keyframe stands still.
struct Path {
  std::vector<Keyframe> keyframes;
  float duration = 0.0f;

  Placement at(double time) const;
  bool moves() const { return keyframes.size() > 1; }
};

struct SceneObject {
  std::string name, blob;  // blob: resolved against the scene file's folder
};

struct SceneInstance {
  std::size_t object = 0;
  Path path;
};

struct SceneFile {
  std::string path, name, env;
  glm::vec3 eye{0.0f, 1.0f, 4.0f}, target{0.0f};
  std::vector<SceneObject> objects;
  std::vector<SceneInstance> instances;
};

// Reads DIR/scene.json (or the JSON file itself when `where` names one). Throws SceneError
// naming the file and what is wrong: missing, not JSON, not the schema, an instance naming no
// object, a path whose keyframes are not ascending in [0, duration) or not finite, a missing blob.
SceneFile read_scene_file(const std::string& where);

// Writes `scene` with each instance standing still at placements[i] (one keyframe at time 0),
// the blobs by their path from the new file's folder, and `env` as its environment. Throws
// SceneError on failure.
void write_placed_scene_file(const SceneFile& scene, const std::vector<Placement>& placements,
                             const std::string& env, const std::string& path);

}  // namespace prt::shadowfield_app
