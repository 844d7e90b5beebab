// SPDX-License-Identifier: MIT
// The app's side of a shadowfield scene file (docs/shadowfield/scenes.md, "The scene file"):
// scene.json read without the baker, its scripted paths evaluated by prt::io::RigidPath as the
// baker evaluates them, and a scene file written back for one placement of every instance (what the
// reference tool renders).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/io/rigid_path.hpp"

namespace prt::shadowfield_app {

// What the app reports and exits 1 on.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The baker's placements and paths, shared through prt_io.
using Placement = io::RigidPlacement;
using Keyframe = io::RigidKeyframe;
using Path = io::RigidPath;

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
