// SPDX-License-Identifier: MIT
// The framework's ImGui window: figures (fps, the runtime's shading time), the backend switch,
// the environment picker and rotation, exposure and tone mapping, the camera, the keys, then
// the app's panel.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "environments.hpp"
#include "orbit_camera.hpp"
#include "sample_app.hpp"
#include "scene_renderer.hpp"

namespace prt::sample {

struct OverlayState {
  Environments* environments = nullptr;
  OrbitCamera* camera = nullptr;
  RenderSettings* settings = nullptr;
  Backend* backend = nullptr;
  bool backend_usable[3] = {true, false, false};
  std::string backend_notes[3];   // why one is not usable, when the app said
  bool* auto_exposure = nullptr;  // set to meter again on the next frame
  bool exposure_given = false;
  double shading_ms = 0.0, fps = 0.0;
  std::string renderer;
  std::vector<std::string> messages, lines;
  std::function<void()> reframe;
};

void draw_overlay(const OverlayState& state, const std::function<void()>& app_panel);

}  // namespace prt::sample
