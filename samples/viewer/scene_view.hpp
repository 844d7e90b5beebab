// SPDX-License-Identifier: MIT
// prt-viewer's scene mode: a baked scene (`prt-bake scene`'s manifest, OUT/scene.prts) loaded
// with prt_scene_load_file and shaded with one prt_scene_shade per frame, as a game would. Every
// object's blob is in world space at its rest placement, so its mesh (VPOS/TRIS) is drawn as it
// is, all objects as one mesh, coloured with their radiance. The light is the framework's
// current map turned by its rotation, handed to the scene when either changes. Like the rest of
// the viewer it names no technique: names come from prt_technique_get_info.
#pragma once

#include <prt/prt.h>
#include <prt/prt_scene.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "prt/io/envmap.hpp"
#include "sample_app.hpp"
#include "scene_renderer.hpp"

namespace prt::view {

// True for a scene manifest: a path ending in .prts, or a blob that loads and holds a SCNE
// section. False for anything else, including files that do not load (the blob mode then says
// why).
bool is_scene_manifest(const std::string& path);

class SceneView {
 public:
  // `backend_option` is the framework's --backend as given (auto, cpu, simd or gl): auto lets
  // each technique shade on its best CPU-side backend.
  SceneView(std::string path, std::string backend_option);
  ~SceneView();
  SceneView(const SceneView&) = delete;
  SceneView& operator=(const SceneView&) = delete;

  // Loads the scene given to the constructor and frames it (the GL context is current). Throws
  // ViewerError with the runtime's message.
  void start(prt::sample::Sample& sample);
  // Loads the manifest at `path` in place of the current scene (a drop), and frames it; the
  // current scene stays when it fails (throws ViewerError).
  void open(prt::sample::Sample& sample, const std::string& path);

  // Hands the scene the light when it changed, shades it, and returns the one view of all the
  // objects.
  std::vector<prt::sample::View> frame(prt::sample::Sample& sample);
  // The objects (name, technique, vertices) and the frame time.
  void panel(prt::sample::Sample& sample);
  // Releases the GL objects (while the context is current).
  void release_gl();

 private:
  struct Loaded;  // a context, its scene and the scene's mesh on the GPU
  std::string path_, backend_option_;
  std::unique_ptr<Loaded> loaded_;
  std::uint64_t light_version_ = ~0ull;
  // The current map as an environment image (unturned; into faces_ for cross and probe maps).
  const prt::io::EnvMap* env_map_ = nullptr;
  prt_env_image env_{};
  std::vector<float> faces_, radiance_;
  // Which backend prt_scene_shade gets, re-chosen when the overlay's backend changes.
  bool backend_chosen_ = false, told_gl_ = false;
  prt::sample::Backend sample_backend_ = prt::sample::Backend::Cpu;
  prt_backend backend_ = PRT_BACKEND_AUTO;
  double shade_ms_ = 0.0, frame_ms_ = 0.0;
  std::chrono::steady_clock::time_point previous_{};

  std::unique_ptr<Loaded> load(const std::string& path) const;
  void show(prt::sample::Sample& sample, std::unique_ptr<Loaded> loaded);
  void choose_backend(prt::sample::Sample& sample);
  void set_environment(prt::sample::Sample& sample);
  void shade(prt::sample::Sample& sample);
};

}  // namespace prt::view
