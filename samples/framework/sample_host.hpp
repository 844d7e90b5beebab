// SPDX-License-Identifier: MIT
// The framework's own command-line options (run_sample adds them before the app's).
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace prt::sample {

struct HostOptions {
  bool headless = false, screenshot_ui = false, no_overlay = false, exposure_given = false;
  std::string size = "1280x720", screenshot, input_script, window_api = "glx";
  int width = 0, height = 0;  // from size
  long frames = 0;            // 0: until the window closes
  std::vector<std::string> envs;
  std::string env_mapping = "auto", tone_map = "filmic", backend = "auto";
  double rotate_degrees = 0.0, spin_degrees_per_second = 0.0;
  float exposure_ev = 0.0f, yaw_degrees = 0.0f, pitch_degrees = 16.699244f, zoom = 1.0f;
  int supersample = 2;
};

void add_host_options(CLI::App& app, HostOptions& options);
// Rules across options; throws CLI::ValidationError.
void check_host_options(HostOptions& options);

}  // namespace prt::sample
