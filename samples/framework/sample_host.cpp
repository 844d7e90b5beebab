// SPDX-License-Identifier: MIT
// run_sample: the options every sample has, the frame loop (the same for a window and
// headless), input, the overlay and screenshots.
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <stb_image_write.h>
#include <CLI/CLI.hpp>
#include <prt/prt.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <deque>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "overlay.hpp"
#include "presenter.hpp"
#include "sample_app.hpp"
#include "sample_host.hpp"

namespace prt::sample {

const char* backend_name(Backend backend) {
  switch (backend) {
    case Backend::Cpu:
      return "cpu";
    case Backend::Simd:
      return "simd";
    case Backend::Gl:
      return "gl";
  }
  return "?";
}

prt_backend runtime_backend(Backend backend) {
  switch (backend) {
    case Backend::Cpu:
      return PRT_BACKEND_CPU;
    case Backend::Simd:
      return PRT_BACKEND_SIMD;
    case Backend::Gl:
      return PRT_BACKEND_GL;
  }
  return PRT_BACKEND_CPU;
}

namespace {

void parse_size(const std::string& text, int* width, int* height) {
  char x = 0, rest = 0;
  std::istringstream in(text);
  if (!(in >> *width >> x >> *height) || (x != 'x' && x != 'X') || (in >> rest) || *width < 16 ||
      *height < 16 || *width > 8192 || *height > 8192)
    throw CLI::ValidationError("--size", "expected WxH (e.g. 1280x720), got '" + text + "'");
}

void write_png(const std::string& path, int width, int height,
               const std::vector<std::uint8_t>& rgb) {
  if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3))
    throw std::runtime_error(path + ": cannot write the PNG file");
}

}  // namespace

void add_host_options(CLI::App& app, HostOptions& o) {
  const std::string group = "Window and frames";
  app.add_flag("--headless", o.headless,
               "Render without a window, on a headless EGL context (same drawing code)")
      ->group(group);
  app.add_option("--size", o.size, "Window (or headless frame) size WxH")
      ->capture_default_str()
      ->group(group);
  app.add_option("--frames", o.frames,
                 "Render N frames, write --screenshot and exit (headless default: 1)")
      ->check(CLI::Range(1, 1000000))
      ->group(group);
  app.add_option("--screenshot,--out", o.screenshot,
                 "PNG the last of --frames is written to (P / F12 write <app>-NNN.png)")
      ->group(group);
  app.add_flag("--screenshot-ui", o.screenshot_ui,
               "Screenshots include the overlay (default: the tone-mapped scene only)")
      ->group(group);
  app.add_option("--input-script", o.input_script,
                 "Replay timed input events from FILE (samples/framework/README.md)")
      ->check(CLI::ExistingFile)
      ->group(group);
  app.add_option("--window-api", o.window_api, "glx|egl: how the window's context is made")
      ->check(CLI::IsMember({"glx", "egl"}))
      ->capture_default_str()
      ->group(group);
  app.add_flag("--no-overlay", o.no_overlay, "Start with the overlay hidden (H toggles it)")
      ->group(group);

  const std::string look = "Light and picture";
  // One map per --env, so a blob named after it is not taken for another map.
  app.add_option("--env", o.envs,
                 "Environment map (.hdr; lat-long, vertical cross or probe, or builtin:sky); "
                 "repeat for more (none: the built-in sky)")
      ->allow_extra_args(false)
      ->group(look);
  app.add_option("--env-mapping", o.env_mapping, "auto|latlong|cross|probe")
      ->check(CLI::IsMember({"auto", "latlong", "cross", "probe"}))
      ->capture_default_str()
      ->group(look);
  app.add_option("--rotate", o.rotate_degrees,
                 "Turn the light about world +Y by DEG degrees (as prt-view --rotate)")
      ->check(CLI::Range(-1e6, 1e6))
      ->group(look);
  app.add_option("--spin", o.spin_degrees_per_second, "Auto-spin of the light, degrees per second")
      ->group(look);
  app.add_option("--exposure", o.exposure_ev,
                 "Exposure in EV (default: metered as prt-view and prt-bake reference meter)")
      ->each([&o](const std::string&) { o.exposure_given = true; })
      ->group(look);
  app.add_option("--tonemap", o.tone_map, "filmic (ACES fit, as prt-view) or linear (a clamp)")
      ->check(CLI::IsMember({"filmic", "linear"}))
      ->capture_default_str()
      ->group(look);
  app.add_option("--supersample", o.supersample, "Samples per pixel along each axis")
      ->check(CLI::Range(1, 4))
      ->capture_default_str()
      ->group(look);
  app.add_option("--backend", o.backend, "auto|cpu|simd|gl (auto: the runtime's best CPU backend)")
      ->check(CLI::IsMember({"auto", "cpu", "simd", "gl"}))
      ->capture_default_str()
      ->group(look);
  app.add_option("--yaw", o.yaw_degrees, "Camera yaw about +Y, degrees (0: from +Z)")->group(look);
  app.add_option("--pitch", o.pitch_degrees,
                 "Camera elevation, degrees (default: prt-view's, atan 0.3)")
      ->group(look);
  app.add_option("--zoom", o.zoom, "Camera distance as a multiple of the framing distance")
      ->check(CLI::PositiveNumber)
      ->group(look);
}

void check_host_options(HostOptions& o) {
  parse_size(o.size, &o.width, &o.height);
  // ImGui lays a new window out on its first frame and draws it from the second.
  if (o.headless && o.frames == 0) o.frames = o.screenshot_ui ? 2 : 1;
}

// ---------------------------------------------------------------------------------------------

// Frames a run with --frames draws past N while the app says it is busy, at most.
constexpr long kMostBusyFrames = 100000;

class Host : public Sample, public InputSink {
 public:
  Host(const char* name, SampleApp& app, const HostOptions& options)
      : name_(name), app_(app), options_(options) {}

  int run();

  // Sample
  Environments& environments() override { return environments_; }
  OrbitCamera& camera() override { return camera_; }
  Backend backend() const override { return backend_; }
  prt_gl_loader_fn gl_loader() const override { return presenter_->loader(); }
  void* gl_loader_user() const override { return presenter_->loader_user(); }
  void fall_back_to_cpu(const std::string& why) override {
    report(why);
    backend_ = usable(Backend::Simd) ? Backend::Simd : Backend::Cpu;
  }
  void backend_unusable(Backend backend, const std::string& why) override;
  void set_scene_bounds(const glm::vec3& lo, const glm::vec3& hi, bool frame_now) override {
    lo_ = lo, hi_ = hi;
    if (frame_now) camera_.frame(lo, hi);
  }
  void meter_exposure() override { meter_ = !options_.exposure_given; }
  prt_result time_shading(const std::function<prt_result()>& shade) override {
    const auto start = std::chrono::steady_clock::now();
    const prt_result result = shade();
    if (backend_ == Backend::Gl) glFinish();
    frame_shading_ms_ +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ++frame_shading_calls_;
    return result;
  }
  void report(const std::string& message) override {
    std::fprintf(stderr, "%s: %s\n", name_, message.c_str());
    messages_.push_back(message);
    if (messages_.size() > 4) messages_.pop_front();
    reported_ = true;
  }
  void overlay_line(const std::string& text) override { overlay_lines_.push_back(text); }
  std::vector<std::uint8_t> read_picture(int* width, int* height) const override {
    return renderer_->read_display(width, height);
  }
  int width() const override { return width_; }
  int height() const override { return height_; }
  glm::vec2 to_frame(double x, double y) const override {
    const double ratio = presenter_->pixel_ratio();
    return {float(x * ratio / std::max(width_, 1)), float(y * ratio / std::max(height_, 1))};
  }

  // InputSink
  void cursor(double x, double y) override;
  void button(MouseButton button, bool pressed) override;
  void scroll(double steps) override { camera_.scroll(float(steps)); }
  void key(const std::string& name) override;
  void drop(const std::vector<std::string>& paths) override { app_.drop(*this, paths); }
  void resize(int width, int height) override { presenter_->resize(width, height); }

 private:
  const char* name_;
  SampleApp& app_;
  HostOptions options_;
  std::unique_ptr<Presenter> presenter_;
  std::unique_ptr<SceneRenderer> renderer_;
  Environments environments_;
  OrbitCamera camera_;
  Backend backend_ = Backend::Cpu;
  bool backend_usable_[3] = {true, false, false};
  std::string backend_notes_[3];  // why a backend is not usable
  glm::vec3 lo_{-1.0f}, hi_{1.0f};
  RenderSettings settings_;
  bool meter_ = true, overlay_ = true, reported_ = false;
  int width_ = 0, height_ = 0;
  double cursor_x_ = 0.0, cursor_y_ = 0.0;
  bool left_down_ = false, right_down_ = false;
  int screenshots_ = 0;
  bool screenshot_requested_ = false;
  double frame_shading_ms_ = 0.0, last_shading_ms_ = 0.0, fps_ = 0.0;
  int frame_shading_calls_ = 0;
  std::vector<double> shading_history_;
  std::deque<std::string> messages_;
  std::vector<std::string> overlay_lines_;
  std::string renderer_name_;

  bool usable(Backend backend) const { return backend_usable_[int(backend)]; }
  void query_backends();
  void draw_frame(bool last_frame);
  void write_screenshot(const std::string& path, bool with_ui);
  std::string key_screenshot_path();
  OverlayState overlay_state();
};

void Host::query_backends() {
  prt::ContextPtr context;
  prt_context_desc desc = prt::sized<prt_context_desc>();
  desc.flags = PRT_CONTEXT_READ_ENVIRONMENT;
  prt_context* raw = nullptr;
  if (prt_context_create(&desc, &raw) != PRT_OK) throw std::runtime_error("no prtkit context");
  context.reset(raw);
  for (Backend b : {Backend::Cpu, Backend::Simd, Backend::Gl}) {
    prt_backend_info info = prt::sized<prt_backend_info>();
    backend_usable_[int(b)] =
        prt_backend_get_info(raw, runtime_backend(b), &info) == PRT_OK && info.usable;
  }
  const std::string& wanted = options_.backend;
  if (wanted == "auto")
    backend_ = usable(Backend::Simd) ? Backend::Simd : Backend::Cpu;
  else
    backend_ = wanted == "cpu" ? Backend::Cpu : wanted == "simd" ? Backend::Simd : Backend::Gl;
  if (!usable(backend_))
    throw std::runtime_error(std::string("backend ") + backend_name(backend_) +
                             " is not usable in this build or on this machine");
}

void Host::backend_unusable(Backend backend, const std::string& why) {
  if (!usable(backend)) return;
  backend_usable_[int(backend)] = false;
  backend_notes_[int(backend)] = why;
  const bool asked = options_.backend == backend_name(backend);
  if (backend_ == backend) backend_ = usable(Backend::Simd) ? Backend::Simd : Backend::Cpu;
  if (asked)
    report(why);
  else
    std::printf("%s: note: %s\n", name_, why.c_str());
}

void Host::cursor(double x, double y) {
  const double dx = x - cursor_x_, dy = y - cursor_y_;
  cursor_x_ = x, cursor_y_ = y;
  if (app_.mouse_move(*this, x, y)) return;
  if (left_down_) camera_.drag(float(dx), float(dy));
  if (right_down_)
    environments_.set_rotation_degrees(environments_.rotation_degrees() +
                                       OrbitCamera::kDegreesPerPixel * dx);
}

void Host::button(MouseButton button, bool pressed) {
  if (app_.mouse_button(*this, button, pressed, cursor_x_, cursor_y_) && pressed) return;
  (button == MouseButton::Left ? left_down_ : right_down_) = pressed;
}

void Host::key(const std::string& name) {
  if (name == "F") camera_.frame(lo_, hi_);
  if (name == "P" || name == "F12") screenshot_requested_ = true;
  if (name == "H") overlay_ = !overlay_;
  if (name == "ESCAPE") presenter_->request_close();
}

std::string Host::key_screenshot_path() {
  char path[64];
  std::snprintf(path, sizeof path, "%s-%03d.png", name_, screenshots_);
  return path;
}

void Host::write_screenshot(const std::string& path, bool with_ui) {
  int w = 0, h = 0;
  std::vector<std::uint8_t> rgb;
  if (!with_ui) {
    rgb = renderer_->read_display(&w, &h);
  } else {
    w = width_, h = height_;
    std::vector<std::uint8_t> rgba(std::size_t(w) * h * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, presenter_->output_framebuffer());
    if (presenter_->output_framebuffer() == 0) glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    rgb.resize(std::size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c)
          rgb[(std::size_t(y) * w + x) * 3 + c] = rgba[(std::size_t(h - 1 - y) * w + x) * 4 + c];
  }
  write_png(path, w, h, rgb);
  ++screenshots_;
  std::printf("wrote %s (%dx%d%s)\n", path.c_str(), w, h, with_ui ? ", with the overlay" : "");
}

OverlayState Host::overlay_state() {
  OverlayState s;
  s.environments = &environments_;
  s.camera = &camera_;
  s.settings = &settings_;
  s.backend = &backend_;
  for (int i = 0; i < 3; ++i) {
    s.backend_usable[i] = backend_usable_[i];
    s.backend_notes[i] = backend_notes_[i];
  }
  s.auto_exposure = &meter_;
  s.exposure_given = options_.exposure_given;
  s.shading_ms = last_shading_ms_;
  s.fps = fps_;
  s.renderer = renderer_name_ + " (" + presenter_->kind() + ")";
  s.messages.assign(messages_.begin(), messages_.end());
  s.lines = overlay_lines_;
  s.reframe = [this] { camera_.frame(lo_, hi_); };
  return s;
}

void Host::draw_frame(bool last_frame) {
  presenter_->framebuffer_size(&width_, &height_);
  width_ = std::max(width_, 1), height_ = std::max(height_, 1);

  ImGui_ImplOpenGL3_NewFrame();
  presenter_->imgui_new_frame(1.0 / std::max(fps_, 1.0));
  ImGui::NewFrame();
  const bool metering_wanted = meter_;
  if (overlay_) draw_overlay(overlay_state(), [this] { app_.panel(*this); });
  overlay_lines_.clear();

  // Shading calls are made in the app's frame() and, for per-pixel views, while drawing.
  frame_shading_ms_ = 0.0;
  frame_shading_calls_ = 0;
  const std::vector<View> views = app_.frame(*this);

  Background background;
  background.latlong_texture = environments_.texture();
  background.rotation = prt::io::rotation_about_y(environments_.rotation_degrees());
  renderer_->render(width_, height_, options_.supersample, views, camera_, background);
  if (frame_shading_calls_ > 0) {
    last_shading_ms_ = frame_shading_ms_;
    shading_history_.push_back(frame_shading_ms_);
  }
  if (metering_wanted && meter_) {
    settings_.exposure_ev = prt::io::auto_exposure_ev(renderer_->read_hdr());
    meter_ = false;
  }
  renderer_->tone_map(settings_);
  app_.drawn(*this);
  ImGui::Render();

  const GLuint output = presenter_->output_framebuffer();
  glBindFramebuffer(GL_READ_FRAMEBUFFER, renderer_->display_framebuffer());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, output);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, output);
  // The key's screenshots are numbered in the working folder; the last of --frames goes to
  // --screenshot.
  std::vector<std::string> shots;
  if (screenshot_requested_) shots.push_back(key_screenshot_path());
  if (last_frame && !options_.screenshot.empty()) shots.push_back(options_.screenshot);
  if (!options_.screenshot_ui)
    for (const std::string& path : shots) write_screenshot(path, false);
  glBindFramebuffer(GL_FRAMEBUFFER, output);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (options_.screenshot_ui)
    for (const std::string& path : shots) write_screenshot(path, true);
  screenshot_requested_ = false;
  presenter_->present();
}

int Host::run() {
  query_backends();
  settings_.tone_map = options_.tone_map == "linear" ? ToneMap::Linear : ToneMap::Filmic;
  settings_.exposure_ev = options_.exposure_ev;
  meter_ = !options_.exposure_given;
  overlay_ = !options_.no_overlay;
  const bool scripted = options_.frames > 0;
  std::vector<InputEvent> script;
  if (!options_.input_script.empty()) script = read_input_script(options_.input_script);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  try {
    if (options_.headless) {
      presenter_ = make_headless_presenter(options_.width, options_.height);
    } else {
      WindowRequest request;
      request.width = options_.width, request.height = options_.height;
      request.title = name_;
      request.egl = options_.window_api == "egl";
      request.vsync = !scripted;
      presenter_ = make_window_presenter(request, *this);
    }
  } catch (...) {
    ImGui::DestroyContext();
    throw;
  }
  ImGui_ImplOpenGL3_Init("#version 430 core");
  renderer_name_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  std::printf("%s: %s, %s, GL %s\n", name_, presenter_->kind().c_str(), renderer_name_.c_str(),
              reinterpret_cast<const char*>(glGetString(GL_VERSION)));
  renderer_ = std::make_unique<SceneRenderer>();

  int status = 0;
  try {
    for (const std::string& env : options_.envs) environments_.add(env, options_.env_mapping);
    if (environments_.empty()) {
      std::printf("%s: no --env MAP.hdr: lit by the built-in sky\n", name_);
      environments_.add(kBuiltinSky);
    }
    environments_.select(0);
    environments_.set_rotation_degrees(options_.rotate_degrees);
    environments_.spin_degrees_per_second = options_.spin_degrees_per_second;
    app_.start(*this);
    camera_.set_yaw_pitch(options_.yaw_degrees, options_.pitch_degrees);
    camera_.set_zoom(options_.zoom);

    auto previous = std::chrono::steady_clock::now();
    for (long frame = 0; !presenter_->should_close(); ++frame) {
      presenter_->poll();
      replay(script, frame, *this);
      if (presenter_->should_close()) break;
      const auto now = std::chrono::steady_clock::now();
      const double seconds = std::chrono::duration<double>(now - previous).count();
      previous = now;
      if (frame > 0) fps_ = fps_ == 0.0 ? 1.0 / seconds : 0.9 * fps_ + 0.1 / seconds;
      // Scripted runs step by 1/60 s a frame, so that they are reproducible.
      environments_.advance(scripted ? 1.0 / 60.0 : seconds);
      // Past --frames while the app is busy, up to a bound that a picture which never settles
      // (a progressive one under a spinning light) cannot pass.
      const bool busy = app_.busy() && frame < options_.frames + kMostBusyFrames;
      const bool last = scripted && frame + 1 >= options_.frames && !busy;
      if (scripted && frame + 1 == options_.frames + kMostBusyFrames && app_.busy())
        report("still busy after " + std::to_string(kMostBusyFrames) + " more frames: giving up");
      draw_frame(last);
      if (last) break;
    }
    if (!shading_history_.empty()) {
      std::vector<double> sorted = shading_history_;
      std::sort(sorted.begin(), sorted.end());
      std::printf("%s: %zu frame(s), shading median %.3f ms per frame, backend %s%s\n", name_,
                  sorted.size(), sorted[sorted.size() / 2], backend_name(backend_),
                  backend_ == Backend::Gl ? " (timed with glFinish)" : "");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name_, e.what());
    status = 1;
  }
  app_.stop(*this);
  environments_.release_textures();
  renderer_.reset();
  ImGui_ImplOpenGL3_Shutdown();
  presenter_->imgui_shutdown();
  ImGui::DestroyContext();
  presenter_.reset();
  if (status == 0 && reported_ && scripted) status = 1;
  return status;
}

int run_sample(const char* name, const std::string& description, SampleApp& app, int argc,
               char** argv) {
  CLI::App cli{description};
  HostOptions options;
  options.supersample = app.default_supersample();
  add_host_options(cli, options);
  app.add_options(cli);
  try {
    cli.parse(argc, argv);
    check_host_options(options);
    app.check_options();
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    Host host(name, app, options);
    return host.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 1;
  }
}

}  // namespace prt::sample
