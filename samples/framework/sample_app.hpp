// SPDX-License-Identifier: MIT
// A windowed prtkit sample: the app (SampleApp) adds its options, loads its content, makes its
// per-frame runtime calls and says what to draw; the framework (Sample, run_sample) owns the
// window or the headless context, the camera, the environments, the backend switch, drawing,
// tone mapping, the overlay, input and screenshots. See samples/framework/README.md.
#pragma once

#include <prt/prt.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "environments.hpp"
#include "input.hpp"
#include "orbit_camera.hpp"
#include "scene_renderer.hpp"

namespace CLI {
class App;
}

namespace prt::sample {

enum class Backend { Cpu, Simd, Gl };
const char* backend_name(Backend backend);
prt_backend runtime_backend(Backend backend);

// The framework's side, handed to every SampleApp call.
class Sample {
 public:
  virtual ~Sample() = default;

  virtual Environments& environments() = 0;
  virtual OrbitCamera& camera() = 0;

  // The backend the user picked, and the runtime's GL loader for the context that is current.
  virtual Backend backend() const = 0;
  virtual prt_gl_loader_fn gl_loader() const = 0;
  virtual void* gl_loader_user() const = 0;
  // Goes back to a CPU backend (after the GL backend failed, say), reporting `why`.
  virtual void fall_back_to_cpu(const std::string& why) = 0;
  // The app's technique cannot use `backend` (`why`): the overlay greys it out, and when it is
  // the current one the best remaining CPU backend takes over. Reported (a run with --frames then
  // exits 1) when --backend asked for it; otherwise printed as a note.
  virtual void backend_unusable(Backend backend, const std::string& why) = 0;

  // The scene's bounds, which `F` frames; reframes now when `frame_now`.
  virtual void set_scene_bounds(const glm::vec3& lo, const glm::vec3& hi, bool frame_now) = 0;
  // Meters the exposure again on the next frame (unless it was given on the command line).
  virtual void meter_exposure() = 0;

  // Runs `shade` (one runtime shading call) and adds its time to this frame's shading time;
  // with the GL backend, the time includes a glFinish, so that it covers the GPU's work.
  virtual prt_result time_shading(const std::function<prt_result()>& shade) = 0;

  // A message for the user: printed on stderr, shown in the overlay; a run with --frames then
  // exits with status 1.
  virtual void report(const std::string& message) = 0;
  // A line shown in this frame's overlay.
  virtual void overlay_line(const std::string& text) = 0;

  // The frame just drawn, tone mapped, without the overlay: RGB, top row first. For
  // SampleApp::drawn.
  virtual std::vector<std::uint8_t> read_picture(int* width, int* height) const = 0;

  // The frame in pixels (the window's framebuffer, or --size headless).
  virtual int width() const = 0;
  virtual int height() const = 0;
  // A window position (cursor coordinates) as a fraction of the frame from the top left.
  virtual glm::vec2 to_frame(double x, double y) const = 0;
};

class SampleApp {
 public:
  virtual ~SampleApp() = default;

  // The app's own options and positional arguments.
  virtual void add_options(CLI::App& app) = 0;
  // Rules across options, after parsing: throws CLI::ValidationError.
  virtual void check_options() {}

  // The GL context is current and the environments given on the command line are loaded: loads
  // what the options name. Throws std::exception to fail the run.
  virtual void start(Sample& sample) = 0;
  // One frame: the runtime calls (each shading call through Sample::time_shading), then the
  // views to draw.
  virtual std::vector<View> frame(Sample& sample) = 0;
  // The frame is drawn and tone mapped (Sample::read_picture returns it).
  virtual void drawn(Sample&) {}
  // True while more frames are needed to finish what the app shows (a picture computed over
  // several frames, a gallery of pictures): a run with --frames draws past N until it is false.
  virtual bool busy() const { return false; }
  // The default of --supersample: per-pixel shading costs grow with its square.
  virtual int default_supersample() const { return 2; }
  // The app's controls, inside the framework's ImGui window.
  virtual void panel(Sample&) {}
  // A mouse button or cursor move the app takes (a divider, say): return true to keep it from
  // the camera. (x, y) are window pixels from the top left.
  virtual bool mouse_button(Sample&, MouseButton, bool /*pressed*/, double /*x*/, double /*y*/) {
    return false;
  }
  virtual bool mouse_move(Sample&, double /*x*/, double /*y*/) { return false; }
  // Files dropped on the window.
  virtual void drop(Sample&, const std::vector<std::string>& /*paths*/) {}
  // The GL context is still current: release GL objects.
  virtual void stop(Sample&) {}
};

// Parses the framework's and the app's options, opens a window (or the headless context with
// --headless), runs the frame loop and returns the exit status: 0, 1 on failure (and on any
// report() in a run with --frames), 2 on bad arguments.
int run_sample(const char* name, const std::string& description, SampleApp& app, int argc,
               char** argv);

}  // namespace prt::sample
