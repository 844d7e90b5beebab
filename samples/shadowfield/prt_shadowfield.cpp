// SPDX-License-Identifier: MIT
// prt-shadowfield: technique `shadowfield`'s scene of rigid objects, each baked alone, moving on
// their scripted paths (or dragged with the mouse) and shadowing and lighting each other, shaded
// by the runtime every frame in a window (or headless) on the sample framework. When paused, it
// can render the reference for the current placement in the background with
// `prt-bake shadowfield-reference` and show it beside, split with or as the error of the
// runtime's picture. README.md says how to run it.
//
// Each frame makes the calls a game would: prt_shadowfield_scene_set_transform for every
// instance, then prt_shadowfield_shade (or _workers) with the world light in SH, the eye and the
// bounce count.
#include <imgui.h>
#include <CLI/CLI.hpp>
#include <prt/prt.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "compare.hpp"
#include "env_image.hpp"
#include "prt/io/envmap.hpp"
#include "prt/io/image_io.hpp"
#include "prt/io/radiance_error.hpp"
#include "reference_run.hpp"
#include "sample_app.hpp"
#include "scene_file.hpp"
#include "shadowfield_world.hpp"
#include "sky_map.hpp"

namespace prt::shadowfield_app {
namespace {

namespace fs = std::filesystem;
using prt::sample::FrameRect;
using prt::sample::GpuMesh;
using prt::sample::View;
using prt::view::check_runtime;

enum class Compare { Single, Side, Split, Error };

// Bounces the panel offers: more cost a pass each for little more light.
constexpr int kMostLiveBounces = 3;

// The folder the app's temporary files (the sky, the reference's inputs and outputs) go in.
const fs::path& scratch_dir() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("prt-shadowfield-" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

// Where `--env sky` is written.
std::string sky_path() {
  return (scratch_dir() / "sky.hdr").string();
}

// The reference tool: `prt-bake` beside the app, else in the build tree the app was built in,
// else on PATH.
std::string default_reference_tool() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (!error && fs::exists(self.parent_path() / "prt-bake"))
    return (self.parent_path() / "prt-bake").string();
#ifdef PRT_SHADOWFIELD_BAKE_TOOL
  if (fs::exists(PRT_SHADOWFIELD_BAKE_TOOL)) return PRT_SHADOWFIELD_BAKE_TOOL;
#endif
  return "prt-bake";
}

std::string vec3_text(const glm::vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "%.6g,%.6g,%.6g", v.x, v.y, v.z);
  return text;
}

class ShadowfieldApp : public prt::sample::SampleApp {
 public:
  // --yaw, --pitch or --zoom was given: the scene file's camera is not used.
  bool camera_given = false;

  void add_options(CLI::App& app) override {
    app.add_option("SCENE_DIR", scene_path_,
                   "A folder holding scene.json and the blobs it names (prt-bake "
                   "shadowfield-scene), or the JSON file")
        ->required();
    app.add_option("--bounces", bounces_, "Light bounces between instances (0: direct light only)")
        ->check(CLI::Range(0, kMostLiveBounces))
        ->capture_default_str();
    app.add_flag("--log-product", log_product_,
                 "Combine the blockers' visibilities by the log-space product (for scenes where "
                 "vertices have many blockers) instead of triple products");
    app.add_option("--probe-spacing", probe_spacing_,
                   "Gather each bounce's light on a grid of this spacing (in each object's own "
                   "units) and interpolate it to the vertices: faster on large scenes, the bounce "
                   "light a little smoother (0: every vertex gathers its own)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--threads", threads_,
                   "Threads sharing a frame's shading (prt_shadowfield_shade_workers; 1: the "
                   "calling thread alone, 0: one per core)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--time", time_, "Scene time to start at, seconds")->capture_default_str();
    app.add_flag("--pause", paused_, "Start paused");
    app.add_option("--speed", speed_, "Playback speed (scene seconds per second)")
        ->capture_default_str();
    app.add_option("--time-step", time_step_,
                   "Scene seconds per frame while playing (0: the wall clock), for reproducible "
                   "headless runs")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--move", move_options_,
                   "I:X,Z: move instance I so that it stands at X,Z on the floor now, as a drag "
                   "would (repeatable)");
    app.add_option("--compare", compare_,
                   "single|side|split|error: the runtime alone, beside the reference, in a split "
                   "screen with it, or beside the heat map of its error; the reference is rendered "
                   "while paused")
        ->check(CLI::IsMember({"single", "side", "split", "error"}))
        ->capture_default_str();
    app.add_option("--divider", divider_, "Split screen: where the divider is (0..1 of the width)")
        ->check(CLI::Range(0.0f, 1.0f))
        ->capture_default_str();
    app.add_option("--error-scale", error_scale_, "Heat map: relative error shown as white")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--reference-tool", reference_tool_,
                   "The prt-bake that renders the reference (default: beside this program, in "
                   "its build tree, or on PATH)");
    app.add_option("--reference-spp", reference_spp_, "Reference: paths per vertex")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.footer(
        "--env MAP.hdr or --env sky (the scenes' built-in sky, the default). Keys: left-drag an "
        "object to move it on the floor (elsewhere: orbit, or the split's divider), right-drag "
        "turn the light, wheel zoom, F frame, P or F12 screenshot, H overlay, Esc "
        "quit.");
  }

  void check_options() override {
    const char* names[] = {"single", "side", "split", "error"};
    for (int i = 0; i < 4; ++i)
      if (compare_ == names[i]) mode_ = static_cast<Compare>(i);
    for (const std::string& text : move_options_) {
      Move m;
      char tail = 0;
      if (std::sscanf(text.c_str(), "%u:%f,%f%c", &m.instance, &m.x, &m.z, &tail) != 3)
        throw CLI::ValidationError("--move", "expected I:X,Z, got '" + text + "'");
      moves_.push_back(m);
    }
    if (reference_tool_.empty()) reference_tool_ = default_reference_tool();
  }

  void start(prt::sample::Sample& sample) override {
    scene_ = read_scene_file(scene_path_);
    world_ = std::make_unique<ShadowfieldWorld>(scene_);
    if (log_product_) set_product();
    mesh_ = world_->make_mesh();
    reference_mesh_ = world_->make_mesh();
    heat_mesh_ = world_->make_mesh();
    offsets_.assign(scene_.instances.size(), glm::vec3(0.0f));
    for (const Move& m : moves_) {
      if (m.instance >= scene_.instances.size())
        throw SceneError("--move " + std::to_string(m.instance) + ": the scene has " +
                         std::to_string(scene_.instances.size()) + " instances");
      const glm::vec3 at = scene_.instances[m.instance].path.at(time_).translation;
      offsets_[m.instance] = glm::vec3(m.x - at.x, 0.0f, m.z - at.z);
    }
    if (threads_ != 1) {
      prt_workers_desc desc = prt::sized<prt_workers_desc>();
      desc.thread_count = threads_;
      check_runtime(prt_workers_create(world_->context(), &desc, &workers_), "prt_workers_create");
    }
    sample.backend_unusable(prt::sample::Backend::Gl,
                            "this app shades on the CPU backends (prt-viewer shows "
                            "shadowfield's GL backend): the CPU shades, the GPU draws");
    std::printf(
        "%s: %zu objects, %zu instances, %u vertices, SH order %u, %u thread(s), %s product, "
        "bounce light %s\n",
        scene_.path.c_str(), scene_.objects.size(), scene_.instances.size(), world_->vertex_count(),
        world_->order(), workers_ ? prt_workers_thread_count(workers_) : 1u,
        log_product_ ? "log-space" : "triple", probe_note().c_str());
    if (scene_.env != "builtin:sky" && sample.environments().size() == 1 &&
        sample.environments().current_path() == sky_path())
      std::printf("%s: the scene is lit by %s; without --env MAP the built-in sky lights it\n",
                  scene_.path.c_str(), scene_.env.c_str());
    place();
    sample.set_scene_bounds(world_->lo(), world_->hi(), true);
    sample.meter_exposure();
    previous_ = std::chrono::steady_clock::now();
  }

  std::vector<View> frame(prt::sample::Sample& sample) override {
    const auto now = std::chrono::steady_clock::now();
    frame_ms_ = std::chrono::duration<double, std::milli>(now - previous_).count();
    // The first frame shows --time; each later one a step on.
    if (drew_a_frame_) advance_time(std::chrono::duration<double>(now - previous_).count());
    previous_ = now;
    place();
    prepare_light(sample);
    if (!drew_a_frame_ && !camera_given) aim_camera(sample);
    drew_a_frame_ = true;
    const float aspect = runtime_aspect(sample);
    eye_ = sample.camera().camera(aspect).eye;
    shade(sample);
    if (!printed_positions_) print_positions(sample), printed_positions_ = true;
    overlay(sample);
    update_reference(sample);
    return views();
  }

  bool busy() const override {
    // A scripted run that compares waits for the reference of what it shows, so that its
    // picture has it (the framework asks before each frame).
    if (mode_ == Compare::Single || !paused_) return false;
    if (current_key_.empty()) return true;
    if (reference_.state() == ReferenceRun::State::Running) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      return true;
    }
    return reference_key_ != current_key_ && failed_key_ != current_key_;
  }

  void panel(prt::sample::Sample& sample) override {
    bool playing = !paused_;
    if (ImGui::Checkbox("play", &playing)) paused_ = !playing;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120.0f);
    ImGui::SliderFloat("speed", &speed_, 0.0f, 3.0f);
    float t = float(time_);
    if (ImGui::SliderFloat("time (s)", &t, 0.0f, world_->period(), "%.2f")) time_ = t;
    ImGui::SliderInt("bounces", &bounces_, 0, kMostLiveBounces);
    if (ImGui::Checkbox("log-space product", &log_product_)) set_product();
    ImGui::SliderFloat("probe spacing", &probe_spacing_, 0.0f, 1.0f,
                       probe_spacing_ > 0.0f ? "%.2f" : "0 (per vertex)");
    if (ImGui::Button("undo the drags")) std::fill(offsets_.begin(), offsets_.end(), glm::vec3(0));
    int mode = static_cast<int>(mode_);
    const char* modes[] = {"runtime only", "side by side", "split screen", "error heat map"};
    if (ImGui::Combo("compare", &mode, modes, 4)) mode_ = static_cast<Compare>(mode);
    if (mode_ == Compare::Error) ImGui::SliderFloat("error scale", &error_scale_, 0.01f, 1.0f);
    if (mode_ != Compare::Single) {
      ImGui::SliderInt("reference spp", &reference_spp_, 1, 4096, "%d",
                       ImGuiSliderFlags_Logarithmic);
      reference_panel();
    }
    labels(sample);
  }

  bool mouse_button(prt::sample::Sample& sample, prt::sample::MouseButton button, bool pressed,
                    double x, double y) override {
    if (button != prt::sample::MouseButton::Left) return false;
    if (!pressed) {
      const bool was = dragging_divider_ || picked_ >= 0;
      dragging_divider_ = false;
      picked_ = -1;
      return was;
    }
    const glm::vec2 at = sample.to_frame(x, y);
    if (showing_reference() && mode_ == Compare::Split &&
        std::abs(at.x - divider_) * sample.width() <= 8.0f)
      return dragging_divider_ = true;
    return pick(sample, at);
  }

  bool mouse_move(prt::sample::Sample& sample, double x, double y) override {
    const glm::vec2 at = sample.to_frame(x, y);
    if (dragging_divider_) {
      divider_ = std::clamp(at.x, 0.0f, 1.0f);
      return true;
    }
    if (picked_ < 0) return false;
    glm::vec3 floor;
    if (!plane_point(sample, at, grab_height_, &floor)) return true;
    const glm::vec3 path = scene_.instances[std::size_t(picked_)].path.at(time_).translation;
    const glm::vec3 wanted = floor + grab_offset_;
    offsets_[std::size_t(picked_)] = glm::vec3(wanted.x - path.x, 0.0f, wanted.z - path.z);
    return true;
  }

  void stop(prt::sample::Sample& sample) override {
    reference_.cancel();
    print_positions(sample);
    if (compared_)
      std::printf("prt-shadowfield: vs the reference (%d spp): relative RMSE %.5f (%.2f %%)\n",
                  reference_spp_, rmse_, 100.0 * rmse_);
    mesh_.reset();
    reference_mesh_.reset();
    heat_mesh_.reset();
    if (workers_) prt_workers_destroy(workers_);
    workers_ = nullptr;
    world_.reset();
  }

 private:
  struct Move {
    unsigned instance = 0;
    float x = 0.0f, z = 0.0f;
  };

  std::string scene_path_, compare_ = "single", reference_tool_;
  std::vector<std::string> move_options_;
  std::vector<Move> moves_;
  int bounces_ = 1, reference_spp_ = 256;
  bool log_product_ = false;
  float probe_spacing_ = 0.0f;  // prt_shadowfield_settings::bounce_probe_spacing
  unsigned threads_ = 0;
  double time_ = 0.0, time_step_ = 0.0, frame_ms_ = 0.0;
  float speed_ = 1.0f, divider_ = 0.5f, error_scale_ = 0.25f;
  bool paused_ = false, printed_positions_ = false, drew_a_frame_ = false;

  Compare mode_ = Compare::Single;
  std::chrono::steady_clock::time_point previous_;

  SceneFile scene_;
  std::unique_ptr<ShadowfieldWorld> world_;
  prt_workers* workers_ = nullptr;
  std::vector<glm::vec3> offsets_;  // per instance: where drags have moved it from its path
  std::vector<Placement> placements_;
  glm::vec3 eye_{0.0f};
  std::unique_ptr<GpuMesh> mesh_, reference_mesh_, heat_mesh_;

  std::uint64_t light_version_ = ~0ull;
  std::size_t light_map_ = ~std::size_t(0);
  std::vector<float> map_light_, light_;

  // Picking: the instance a left-drag holds, the height of the plane it slides on, and the
  // offset from where the cursor meets that plane to the instance's origin.
  int picked_ = -1;
  float grab_height_ = 0.0f;
  glm::vec3 grab_offset_{0.0f};
  bool dragging_divider_ = false;

  // The reference: what it renders (placements, light, bounces, eye, spp as text), the run, and
  // the radiance of the last one that finished.
  ReferenceRun reference_;
  // What this frame shows and the previous frame showed (a reference starts only once they are
  // the same, so that an orbit or a slider being dragged does not start one every frame).
  std::string running_key_, reference_key_, failed_key_, current_key_, previous_key_;
  std::vector<glm::vec3> reference_rgb_;
  std::string reference_note_;
  double rmse_ = 0.0;
  bool compared_ = false;

  void advance_time(double wall_seconds) {
    if (paused_) return;
    time_ += (time_step_ > 0.0 ? time_step_ : wall_seconds) * speed_;
    const double period = world_->period();
    if (period > 0.0 && time_ >= period) time_ = std::fmod(time_, period);
  }

  void place() {
    placements_.resize(scene_.instances.size());
    for (std::size_t i = 0; i < placements_.size(); ++i) {
      placements_[i] = scene_.instances[i].path.at(time_);
      placements_[i].translation += offsets_[i];
    }
    world_->place(placements_);
  }

  // The orbit camera looking from where the scene file's camera does, as far from the scene's
  // centre as its eye is from its target (the framework sets the camera after start()).
  void aim_camera(prt::sample::Sample& sample) const {
    const glm::vec3 d = scene_.eye - scene_.target;
    const float length = glm::length(d);
    if (!(length > 0.0f)) return;
    const float degrees = 180.0f / 3.14159265f;
    prt::sample::OrbitCamera& camera = sample.camera();
    camera.set_yaw_pitch(std::atan2(d.x, d.z) * degrees, std::asin(d.y / length) * degrees);
    const float aspect = runtime_aspect(sample);
    const float framed =
        glm::length(camera.camera(aspect).eye - 0.5f * (world_->lo() + world_->hi()));
    if (framed > 0.0f) camera.set_zoom(camera.zoom() * length / framed);
  }

  void prepare_light(prt::sample::Sample& sample) {
    prt::sample::Environments& envs = sample.environments();
    if (light_version_ == envs.light_version()) return;
    const std::uint32_t n2 = world_->order() * world_->order();
    if (light_map_ != envs.current_index()) {
      map_light_.assign(3u * n2, 0.0f);
      std::vector<float> faces;
      const prt_env_image env = prt::view::environment_image(envs.current(), nullptr, &faces);
      check_runtime(prt_sh_project(world_->order(), &env, map_light_.data()), "prt_sh_project");
      light_map_ = envs.current_index();
    }
    float rotation[9];
    prt::io::rotation_about_y_row_major(envs.rotation_degrees(), rotation);
    light_.resize(map_light_.size());
    check_runtime(prt_sh_rotate(world_->order(), rotation, map_light_.data(), light_.data(), 3),
                  "prt_sh_rotate");
    light_version_ = envs.light_version();
  }

  // The scene's product as the option or the panel sets it (the log fields are made here, once).
  void set_product() {
    check_runtime(prt_shadowfield_scene_set_product(
                      world_->scene(),
                      log_product_ ? PRT_SHADOWFIELD_PRODUCT_LOG : PRT_SHADOWFIELD_PRODUCT_TRIPLE),
                  "prt_shadowfield_scene_set_product");
  }

  // How bounce light is gathered, for the console and the overlay.
  std::string probe_note() const {
    if (probe_spacing_ <= 0.0f) return "per vertex";
    char note[64];
    std::snprintf(note, sizeof note, "at probes %g apart", double(probe_spacing_));
    return note;
  }

  void shade(prt::sample::Sample& sample) {
    prt_shadowfield_settings settings = prt::sized<prt_shadowfield_settings>();
    settings.bounces = std::uint32_t(bounces_);
    settings.bounce_probe_spacing = probe_spacing_;
    settings.backend = prt::sample::runtime_backend(sample.backend());
    prt_result result = world_->shade(sample, workers_, light_.data(), eye_, settings);
    if (result == PRT_ERROR_UNSUPPORTED_BACKEND && sample.backend() != prt::sample::Backend::Cpu) {
      sample.backend_unusable(sample.backend(),
                              std::string("prt_shadowfield_shade: ") + prt_result_string(result));
      settings.backend = PRT_BACKEND_CPU;
      result = world_->shade(sample, workers_, light_.data(), eye_, settings);
    }
    if (result != PRT_OK)
      throw SceneError(std::string("prt_shadowfield_shade failed: ") + prt_result_string(result) +
                       ": " + prt_context_last_message(world_->context()));
    world_->upload(*mesh_);
    mesh_->upload_colours(world_->radiance().data());
  }

  void overlay(prt::sample::Sample& sample) {
    char line[200];
    std::snprintf(line, sizeof line,
                  "t %.2f s%s | bounces %d%s%s | %s, %u thread(s) | frame %.1f ms", time_,
                  paused_ ? " (paused)" : "", bounces_, log_product_ ? " | log product" : "",
                  probe_spacing_ > 0.0f ? (" | bounce light " + probe_note()).c_str() : "",
                  prt::sample::backend_name(sample.backend()),
                  workers_ ? prt_workers_thread_count(workers_) : 1u, frame_ms_);
    sample.overlay_line(line);
    if (mode_ != Compare::Single && !reference_note_.empty()) sample.overlay_line(reference_note_);
  }

  // ---- Picking -------------------------------------------------------------------------------

  FrameRect runtime_viewport() const {
    // Side by side and the heat map keep the runtime in the left half, the reference or not
    // yet, so that the eye the reference is asked for is the eye it is shown with.
    const bool halves = mode_ == Compare::Side || mode_ == Compare::Error;
    return halves ? FrameRect{0.0f, 0.0f, 0.5f, 1.0f} : FrameRect{};
  }

  float runtime_aspect(const prt::sample::Sample& sample) const {
    const FrameRect v = runtime_viewport();
    return (v.x1 - v.x0) * float(sample.width()) / ((v.y1 - v.y0) * float(sample.height()));
  }

  // The ray through a point of the frame (fractions from the top left) in the runtime's view.
  bool ray(prt::sample::Sample& sample, const glm::vec2& at, glm::vec3* origin,
           glm::vec3* direction) const {
    const FrameRect v = runtime_viewport();
    const float x = 2.0f * (at.x - v.x0) / (v.x1 - v.x0) - 1.0f;
    const float y = 1.0f - 2.0f * (at.y - v.y0) / (v.y1 - v.y0);
    if (std::abs(x) > 1.0f || std::abs(y) > 1.0f) return false;
    const glm::mat4 inverse = glm::inverse(sample.camera().view_projection(runtime_aspect(sample)));
    const glm::vec4 a = inverse * glm::vec4(x, y, -1.0f, 1.0f);
    const glm::vec4 b = inverse * glm::vec4(x, y, 1.0f, 1.0f);
    *origin = glm::vec3(a) / a.w;
    *direction = glm::normalize(glm::vec3(b) / b.w - *origin);
    return true;
  }

  bool plane_point(prt::sample::Sample& sample, const glm::vec2& at, float height,
                   glm::vec3* point) const {
    glm::vec3 o, d;
    if (!ray(sample, at, &o, &d) || std::abs(d.y) < 1e-6f) return false;
    const float t = (height - o.y) / d.y;
    if (t <= 0.0f) return false;
    *point = o + t * d;
    return true;
  }

  // Picks the nearest instance whose bounding sphere the cursor's ray meets (instance 0, the
  // floor, is not picked: it is what the others slide on).
  bool pick(prt::sample::Sample& sample, const glm::vec2& at) {
    glm::vec3 o, d;
    if (!ray(sample, at, &o, &d)) return false;
    float nearest = INFINITY;
    for (std::size_t i = 1; i < placements_.size(); ++i) {
      const Sphere s = world_->bounding_sphere(i);
      const glm::vec3 oc = o - s.centre;
      const float b = glm::dot(oc, d), c = glm::dot(oc, oc) - s.radius * s.radius;
      const float disc = b * b - c;
      if (disc < 0.0f) continue;
      const float t = -b - std::sqrt(disc);
      if (t > 0.0f && t < nearest) nearest = t, picked_ = int(i);
    }
    if (picked_ < 0) return false;
    // The grabbed point slides on the horizontal plane through the sphere's centre, so that it
    // stays under the cursor.
    grab_height_ = world_->bounding_sphere(std::size_t(picked_)).centre.y;
    glm::vec3 floor;
    if (!plane_point(sample, at, grab_height_, &floor)) floor = o + nearest * d;
    grab_offset_ = placements_[std::size_t(picked_)].translation - floor;
    grab_offset_.y = 0.0f;
    return true;
  }

  // Where each instance is on the screen, for scripted input: its origin (on the floor) and
  // its bounding sphere's centre and radius, in pixels from the top left.
  void print_positions(prt::sample::Sample& sample) const {
    if (!world_) return;
    const FrameRect v = runtime_viewport();
    const glm::mat4 vp = sample.camera().view_projection(runtime_aspect(sample));
    const float w = float(sample.width()), h = float(sample.height());
    auto pixel = [&](const glm::vec3& p) {
      const glm::vec4 c = vp * glm::vec4(p, 1.0f);
      return glm::vec2((v.x0 + (v.x1 - v.x0) * (0.5f + 0.5f * c.x / c.w)) * w,
                       (v.y0 + (v.y1 - v.y0) * (0.5f - 0.5f * c.y / c.w)) * h);
    };
    for (std::size_t i = 0; i < placements_.size(); ++i) {
      const Sphere s = world_->bounding_sphere(i);
      const glm::vec2 base = pixel(placements_[i].translation), centre = pixel(s.centre);
      const glm::vec3 side = sample.camera().camera(runtime_aspect(sample)).right;
      const float radius = glm::length(pixel(s.centre + s.radius * side) - centre);
      std::printf("instance %zu (%s): origin at pixel %.1f %.1f, sphere at %.1f %.1f radius %.1f\n",
                  i, scene_.objects[scene_.instances[i].object].name.c_str(), base.x, base.y,
                  centre.x, centre.y, radius);
    }
  }

  // ---- The reference -------------------------------------------------------------------------

  bool showing_reference() const {
    return mode_ != Compare::Single && reference_key_ == current_key_ && !reference_rgb_.empty();
  }

  std::string key(prt::sample::Sample& sample) const {
    std::string k = std::to_string(bounces_) + " " + std::to_string(reference_spp_) + " " +
                    sample.environments().current_path() + " " +
                    std::to_string(sample.environments().rotation_degrees()) + " " +
                    vec3_text(eye_);
    for (const Placement& p : placements_)
      k += " " + vec3_text(p.translation) + " " +
           vec3_text({p.rotation.x, p.rotation.y, p.rotation.z}) + " " + std::to_string(p.scale);
    return k;
  }

  // Starts the reference when paused and something new is asked for; cancels a run that no
  // longer matches; takes in the one that finished.
  void update_reference(prt::sample::Sample& sample) {
    previous_key_ = current_key_;
    current_key_ = key(sample);
    if (mode_ == Compare::Single) {
      reference_.cancel();
      return;
    }
    if (reference_.state() == ReferenceRun::State::Running && running_key_ != current_key_) {
      reference_.cancel();
      reference_note_ = "reference: cancelled (the scene changed)";
    }
    const ReferenceRun::State state = reference_.poll();
    if (state == ReferenceRun::State::Done && running_key_ != reference_key_)
      take_reference(sample);
    if (state == ReferenceRun::State::Failed && running_key_ == current_key_) {
      if (failed_key_ != current_key_) sample.report(reference_.why());
      failed_key_ = current_key_;
      reference_note_ = reference_.why();
      return;  // not again for the same scene
    }
    const bool wanted =
        paused_ && picked_ < 0 && previous_key_ == current_key_ && reference_key_ != current_key_ &&
        !(reference_.state() != ReferenceRun::State::Idle && running_key_ == current_key_);
    if (wanted) start_reference(sample);
    if (reference_.state() == ReferenceRun::State::Running) {
      const double p = reference_.progress();
      char line[160];
      if (p >= 0.0)
        std::snprintf(line, sizeof line, "reference: %.0f %% (%.0f s)", 100.0 * p,
                      reference_.seconds());
      else
        std::snprintf(line, sizeof line, "reference: rendering (%.0f s)", reference_.seconds());
      reference_note_ = line;
    } else if (!paused_ && reference_key_ != current_key_) {
      reference_note_ = "reference: pause to render it";
    }
  }

  void start_reference(prt::sample::Sample& sample) {
    const prt::sample::Environments& envs = sample.environments();
    std::string env = fs::absolute(envs.current_path()).string();
    if (envs.rotation_degrees() != 0.0)
      env = write_turned_map(envs.current(), envs.rotation_degrees(),
                             (scratch_dir() / "turned.hdr").string());
    const std::string json = (scratch_dir() / "placed.json").string();
    write_placed_scene_file(scene_, placements_, "builtin:sky", json);
    const std::string out = (scratch_dir() / "reference.npy").string();
    fs::remove(out);
    running_key_ = current_key_;
    reference_.start(reference_tool_,
                     {"shadowfield-reference", json, "--time", "0", "--env", env, "--bounces",
                      std::to_string(bounces_), "--spp", std::to_string(reference_spp_), "--eye",
                      vec3_text(eye_), "-o", out},
                     (scratch_dir() / "reference.log").string());
    if (reference_.state() == ReferenceRun::State::Failed) {
      failed_key_ = current_key_;
      reference_note_ = reference_.why();
      sample.report(reference_note_);
    }
  }

  void take_reference(prt::sample::Sample& sample) {
    std::vector<glm::vec3> rgb;
    try {
      rgb = prt::io::read_npy_vec3((scratch_dir() / "reference.npy").string());
    } catch (const std::exception& e) {
      sample.report(std::string("reference: ") + e.what());
      reference_rgb_.clear();
      reference_key_ = running_key_;
      return;
    }
    if (rgb.size() != world_->vertex_count()) {
      sample.report("reference: " + std::to_string(rgb.size()) + " vertices, the scene has " +
                    std::to_string(world_->vertex_count()));
      reference_rgb_.clear();
      reference_key_ = running_key_;
      return;
    }
    reference_rgb_ = std::move(rgb);
    reference_key_ = running_key_;
    char line[160];
    std::snprintf(line, sizeof line, "reference: %d spp in %.1f s", reference_spp_,
                  reference_.seconds());
    reference_note_ = line;
  }

  void reference_panel() {
    switch (reference_.state()) {
      case ReferenceRun::State::Running: {
        const double p = reference_.progress();
        ImGui::ProgressBar(p >= 0.0 ? float(p) : 0.0f, ImVec2(-1.0f, 0.0f),
                           p >= 0.0 ? nullptr : "rendering");
        if (ImGui::Button("cancel")) reference_.cancel(), running_key_.clear();
        break;
      }
      default:
        ImGui::TextWrapped("%s", reference_note_.empty() ? "reference: pause to render it"
                                                         : reference_note_.c_str());
    }
  }

  std::vector<View> views() {
    std::vector<View> out;
    if (!showing_reference()) {
      const FrameRect v = runtime_viewport();
      out.push_back(view(*mesh_, v, v));
      return out;
    }
    world_->upload(*reference_mesh_);
    std::vector<float> flat(3 * reference_rgb_.size());
    for (std::size_t v = 0; v < reference_rgb_.size(); ++v)
      for (int c = 0; c < 3; ++c) flat[3 * v + c] = reference_rgb_[v][c];
    reference_mesh_->upload_colours(flat.data());
    std::vector<glm::vec3> x(reference_rgb_.size());
    const std::vector<float>& radiance = world_->radiance();
    for (std::size_t v = 0; v < x.size(); ++v)
      x[v] = glm::vec3(radiance[3 * v], radiance[3 * v + 1], radiance[3 * v + 2]);
    rmse_ = prt::io::relative_rmse(x, reference_rgb_);
    compared_ = true;
    char line[128];
    std::snprintf(line, sizeof line, "vs reference: relative RMSE %.2f %%", 100.0 * rmse_);
    reference_note_ = line;
    const FrameRect left{0.0f, 0.0f, 0.5f, 1.0f}, right{0.5f, 0.0f, 1.0f, 1.0f};
    if (mode_ == Compare::Split) {
      out.push_back(view(*mesh_, {}, {0.0f, 0.0f, divider_, 1.0f}));
      out.push_back(view(*reference_mesh_, {}, {divider_, 0.0f, 1.0f, 1.0f}));
    } else if (mode_ == Compare::Side) {
      out.push_back(view(*mesh_, left, left));
      out.push_back(view(*reference_mesh_, right, right));
    } else {
      const std::vector<float> error = prt::view::relative_vertex_error(x, reference_rgb_);
      for (std::size_t v = 0; v < x.size(); ++v) {
        const glm::vec3 c = prt::view::heat_colour(error[v], error_scale_);
        for (int k = 0; k < 3; ++k) flat[3 * v + k] = c[k];
      }
      world_->upload(*heat_mesh_);
      heat_mesh_->upload_colours(flat.data());
      out.push_back(view(*mesh_, left, left));
      View heat = view(*heat_mesh_, right, right);
      heat.display_colours = true;
      out.push_back(heat);
    }
    return out;
  }

  static View view(const GpuMesh& mesh, const FrameRect& viewport, const FrameRect& clip) {
    View v;
    v.mesh = &mesh;
    v.colour_buffer = mesh.own_colours();
    v.viewport = viewport;
    v.clip = clip;
    return v;
  }

  // What each half shows (overlay only, so screenshots show the scene alone).
  void labels(prt::sample::Sample& sample) const {
    if (!showing_reference()) return;
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const float w = float(sample.width()), h = float(sample.height());
    const ImU32 white = IM_COL32(255, 255, 255, 230);
    const float split = mode_ == Compare::Split ? divider_ : 0.5f;
    draw->AddText(ImVec2(8.0f, h - 24.0f), white, "runtime");
    draw->AddText(ImVec2(split * w + 8.0f, h - 24.0f), white,
                  mode_ == Compare::Error ? "error heat map" : "reference (path traced)");
    if (mode_ == Compare::Split)
      draw->AddLine(ImVec2(split * w, 0.0f), ImVec2(split * w, h), white, 2.0f);
  }
};

// `--env sky` (or no --env: the scenes' built-in sky) becomes the sky written as a .hdr.
std::vector<std::string> with_sky(int argc, char** argv) {
  std::vector<std::string> args(argv, argv + argc);
  bool env_given = false;
  for (std::size_t i = 1; i < args.size(); ++i) {
    if (args[i] == "--env" && i + 1 < args.size()) {
      env_given = true;
      if (args[i + 1] == "sky") args[i + 1] = write_builtin_sky(sky_path());
    } else if (args[i] == "--env=sky") {
      args[i] = "--env=" + write_builtin_sky(sky_path());
      env_given = true;
    } else if (args[i].rfind("--env=", 0) == 0) {
      env_given = true;
    }
  }
  const bool asks_help = std::find(args.begin(), args.end(), "--help") != args.end() ||
                         std::find(args.begin(), args.end(), "-h") != args.end();
  if (!env_given && !asks_help) {
    args.push_back("--env");
    args.push_back(write_builtin_sky(sky_path()));
  }
  return args;
}

}  // namespace
}  // namespace prt::shadowfield_app

int main(int argc, char** argv) {
  int status = 1;
  try {
    std::vector<std::string> args = prt::shadowfield_app::with_sky(argc, argv);
    prt::shadowfield_app::ShadowfieldApp app;
    for (const std::string& a : args)
      for (const char* option : {"--yaw", "--pitch", "--zoom"})
        if (a.rfind(option, 0) == 0) app.camera_given = true;
    std::vector<char*> pointers;
    for (std::string& a : args) pointers.push_back(a.data());
    pointers.push_back(nullptr);
    status = prt::sample::run_sample(
        "prt-shadowfield",
        "prt-shadowfield: rigid objects baked alone (technique shadowfield), moving, shadowing "
        "and lighting each other, compared with the path-traced reference "
        "(prtkit " PRT_VERSION_STRING ")",
        app, int(args.size()), pointers.data());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt-shadowfield: %s\n", e.what());
  }
  std::error_code ignored;
  std::filesystem::remove_all(prt::shadowfield_app::scratch_dir(), ignored);
  return status;
}
