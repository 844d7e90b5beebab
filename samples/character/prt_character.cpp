// SPDX-License-Identifier: MIT
// prt-character: a skinned character's learned transfer (technique `pose`) shaded by the
// runtime every frame, in a window (or headless) on the sample framework. It plays the clips the
// blob was trained on (the joint rotations `prt-bake bake pose --ground-truth` writes beside it),
// with a timeline to scrub; per-joint sliders pose the character by hand, beyond the training
// range too; the environment turns; and a split screen puts the runtime's shading beside the
// ground truth, the transfer baked for the nearest training frame, with the relative RMSE
// between them. README.md says how to run it.
//
// Each frame it makes the calls a game would: prt_pose_skin for positions and normals in the
// model frame and the frame's placement, then prt_pose_shade with the skinned normals and the
// world light. The ground truth is plain SH dot products of the baked transfer with the same
// light turned into that frame's model frame (formats/SPEC.md §7.3).
#include <imgui.h>
#include <CLI/CLI.hpp>
#include <prt/prt.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "baked_frames.hpp"
#include "blob_scene.hpp"
#include "compare.hpp"
#include "env_image.hpp"
#include "prt/io/envmap.hpp"
#include "prt/io/radiance_error.hpp"
#include "sample_app.hpp"

namespace prt::character {
namespace {

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

using prt::sample::FrameRect;
using prt::sample::GpuMesh;
using prt::sample::View;
using prt::view::BlobScene;
using prt::view::check_runtime;
using prt::view::ViewerError;

enum class Compare { Single, Side, Split, Error };

// q = b ⊗ exp(r): the rotation whose SPEC §7.3 feature relative to the bind rotation b is the
// rotation vector r (radians), so that a slider at r gives back r as the model's input.
void from_rotation_vector(const float* b, const double* r, float* q) {
  const double angle = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  const double s = angle > 0.0 ? std::sin(0.5 * angle) / angle : 0.5;
  const double e[4] = {s * r[0], s * r[1], s * r[2], std::cos(0.5 * angle)};
  q[0] = float(b[3] * e[0] + b[0] * e[3] + b[1] * e[2] - b[2] * e[1]);
  q[1] = float(b[3] * e[1] - b[0] * e[2] + b[1] * e[3] + b[2] * e[0]);
  q[2] = float(b[3] * e[2] + b[0] * e[1] - b[1] * e[0] + b[2] * e[3]);
  q[3] = float(b[3] * e[3] - b[0] * e[0] - b[1] * e[1] - b[2] * e[2]);
}

// One picture of the character: its pose's positions (character space) and radiance.
struct Half {
  std::unique_ptr<GpuMesh> mesh;
  std::vector<float> positions, radiance;
};

class CharacterApp : public prt::sample::SampleApp {
 public:
  void add_options(CLI::App& app) override {
    app.add_option("BLOB", blob_path_, "A `pose` blob (prt-bake bake pose)")->required();
    app.add_option("--ground-truth", ground_truth_,
                   "PREFIX of prt-bake bake pose --ground-truth: the clips to play and the baked "
                   "frames to compare with");
    app.add_option("--compare", compare_,
                   "single|side|split|error: the runtime alone, beside the ground truth, in a "
                   "split screen with it, or beside the heat map of its error (default: split "
                   "with --ground-truth, else single)")
        ->check(CLI::IsMember({"single", "side", "split", "error"}));
    app.add_option("--divider", divider_, "Split screen: where the divider is (0..1 of the width)")
        ->check(CLI::Range(0.0f, 1.0f))
        ->capture_default_str();
    app.add_option("--error-scale", error_scale_, "Heat map: relative error shown as white")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--clip", clip_, "Clip to play (index in the bake's order)")
        ->capture_default_str();
    app.add_option("--time", time_, "Clip time to start at, seconds")->capture_default_str();
    app.add_option("--frame", start_frame_,
                   "Start at this baked training frame (its clip and time); paused");
    app.add_flag("--pause", paused_, "Start paused");
    app.add_option("--speed", speed_, "Playback speed (clip seconds per second)")
        ->capture_default_str();
    app.add_option("--time-step", time_step_,
                   "Clip seconds per frame while playing (0: the wall clock), for reproducible "
                   "headless runs")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--pose", pose_options_,
                   "J:X,Y,Z: pose joint J by hand, its rotation from the bind pose as a rotation "
                   "vector in degrees about its local axes (repeatable; the others keep the "
                   "clip's pose)");
    app.footer(
        "Keys: left-drag orbit (or the split's divider), right-drag turn the light, wheel zoom, "
        "F frame, P or F12 screenshot, H overlay, Esc quit.");
  }

  void check_options() override {
    if (compare_.empty()) compare_ = ground_truth_.empty() ? "single" : "split";
    const char* names[] = {"single", "side", "split", "error"};
    for (int i = 0; i < 4; ++i)
      if (compare_ == names[i]) mode_ = static_cast<Compare>(i);
    if (mode_ != Compare::Single && ground_truth_.empty())
      throw CLI::ValidationError("--compare", compare_ + " needs --ground-truth PREFIX");
    if (start_frame_ >= 0 && ground_truth_.empty())
      throw CLI::ValidationError("--frame", "needs --ground-truth PREFIX");
    for (const std::string& text : pose_options_) {
      HandPose p;
      char tail = 0;
      if (std::sscanf(text.c_str(), "%u:%lf,%lf,%lf%c", &p.joint, &p.degrees[0], &p.degrees[1],
                      &p.degrees[2], &tail) != 4)
        throw CLI::ValidationError("--pose", "expected J:X,Y,Z, got '" + text + "'");
      hand_poses_.push_back(p);
    }
  }

  void start(prt::sample::Sample& sample) override {
    scene_ = std::make_unique<BlobScene>(blob_path_);
    info_ = prt::sized<prt_pose_info>();
    const prt_result got = prt_pose_get_info(scene_->asset(), &info_);
    if (got != PRT_OK)
      scene_->fail(std::string("no `pose` section to draw: ") + prt_result_string(got));
    scene_->check_shaded_vertices(PRT_SECTION_PSTR, info_.vertex_count);
    const std::uint32_t joints = info_.joint_count, vertices = info_.vertex_count;
    n2_ = info_.order * info_.order;
    bind_.resize(4u * joints);
    check_runtime(prt_pose_bind_pose(scene_->asset(), bind_.data(), nullptr, nullptr),
                  "prt_pose_bind_pose");
    rotations_ = bind_;
    sliders_.assign(3u * joints, 0.0);
    hand_.assign(joints, 0);
    lo_.assign(3u * joints, -45.0);
    hi_.assign(3u * joints, 45.0);
    normals_.resize(3u * vertices);
    model_positions_.resize(3u * vertices);
    for (Half* half : {&runtime_, &truth_}) {
      half->positions.assign(scene_->mesh().positions, scene_->mesh().positions + 3u * vertices);
      half->radiance.assign(3u * vertices, 0.0f);
    }
    const prt::view::BlobMesh& mesh = scene_->mesh();
    runtime_.mesh =
        std::make_unique<GpuMesh>(mesh.positions, vertices, mesh.indices, mesh.triangle_count);
    std::printf("%s: %u vertices, %u joints, order %u, %s model PCA(%u, %u), %zu model bytes\n",
                blob_path_.c_str(), vertices, joints, info_.order,
                info_.model == PRT_POSE_MODEL_DIRECT ? "direct" : "residual", info_.pose_dims,
                info_.basis_dims, info_.model_bytes);
    if (!ground_truth_.empty()) open_ground_truth(mesh);
    for (const HandPose& p : hand_poses_) {
      if (p.joint >= joints)
        throw ViewerError("--pose " + std::to_string(p.joint) + ": the blob has " +
                          std::to_string(joints) + " joints");
      hand_[p.joint] = 1;
      for (int k = 0; k < 3; ++k) sliders_[3 * p.joint + k] = p.degrees[k];
    }
    sample.set_scene_bounds(runtime_.mesh->lo(), runtime_.mesh->hi(), true);
    sample.meter_exposure();
    previous_ = std::chrono::steady_clock::now();
  }

  std::vector<View> frame(prt::sample::Sample& sample) override {
    advance_time();
    pose();
    prepare_light(sample);
    shade_runtime(sample);
    std::vector<View> views;
    if (mode_ == Compare::Single || !baked_) {
      views.push_back(view(*runtime_.mesh, {}, {}));
      return views;
    }
    shade_truth();
    std::vector<glm::vec3> x(info_.vertex_count), ref(info_.vertex_count);
    for (std::uint32_t v = 0; v < info_.vertex_count; ++v) {
      x[v] = glm::vec3(runtime_.radiance[3 * v], runtime_.radiance[3 * v + 1],
                       runtime_.radiance[3 * v + 2]);
      ref[v] =
          glm::vec3(truth_.radiance[3 * v], truth_.radiance[3 * v + 1], truth_.radiance[3 * v + 2]);
    }
    rmse_ = prt::io::relative_rmse(x, ref);
    compared_ = true;
    char line[256];
    std::snprintf(line, sizeof line, "vs baked frame %u%s: RMSE %.2f %%", truth_frame_,
                  exact_ ? "" : " (another pose)", 100.0 * rmse_);
    sample.overlay_line(line);
    const FrameRect left{0.0f, 0.0f, 0.5f, 1.0f}, right{0.5f, 0.0f, 1.0f, 1.0f};
    if (mode_ == Compare::Split) {
      views.push_back(view(*runtime_.mesh, {}, {0.0f, 0.0f, divider_, 1.0f}));
      views.push_back(view(*truth_.mesh, {}, {divider_, 0.0f, 1.0f, 1.0f}));
    } else if (mode_ == Compare::Side) {
      views.push_back(view(*runtime_.mesh, left, left));
      views.push_back(view(*truth_.mesh, right, right));
    } else {
      const std::vector<float> error = prt::view::relative_vertex_error(x, ref);
      std::vector<float> colours(3u * info_.vertex_count);
      for (std::uint32_t v = 0; v < info_.vertex_count; ++v) {
        const glm::vec3 c = prt::view::heat_colour(error[v], error_scale_);
        colours[3 * v] = c.r, colours[3 * v + 1] = c.g, colours[3 * v + 2] = c.b;
      }
      heat_->upload_positions(runtime_.positions.data());
      heat_->upload_colours(colours.data());
      views.push_back(view(*runtime_.mesh, left, left));
      View heat = view(*heat_, right, right);
      heat.display_colours = true;
      views.push_back(heat);
    }
    return views;
  }

  void panel(prt::sample::Sample& sample) override {
    if (baked_) {
      int mode = static_cast<int>(mode_);
      const char* modes[] = {"runtime only", "side by side", "split screen", "error heat map"};
      if (ImGui::Combo("compare", &mode, modes, 4)) mode_ = static_cast<Compare>(mode);
      if (mode_ == Compare::Error) ImGui::SliderFloat("error scale", &error_scale_, 0.01f, 1.0f);
      int clip = int(clip_);
      if (baked_->clip_count() > 1 &&
          ImGui::SliderInt("clip", &clip, 0, int(baked_->clip_count()) - 1))
        clip_ = std::uint32_t(clip), time_ = clip_start();
      bool playing = !paused_;
      if (ImGui::Checkbox("play", &playing)) paused_ = !playing;
      ImGui::SameLine();
      ImGui::SetNextItemWidth(120.0f);
      ImGui::SliderFloat("speed", &speed_, 0.0f, 2.0f);
      float t = float(time_);
      if (ImGui::SliderFloat("time (s)", &t, float(clip_start()), float(clip_end()), "%.3f"))
        time_ = t, paused_ = true;
      if (ImGui::Button("< frame")) step_frame(-1);
      ImGui::SameLine();
      if (ImGui::Button("frame >")) step_frame(+1);
      ImGui::SameLine();
      ImGui::Text("nearest baked frame %u", truth_frame_);
    } else {
      ImGui::TextUnformatted("no --ground-truth: bind pose and hand pose only");
    }
    if (ImGui::Button("all joints back to the clip")) std::fill(hand_.begin(), hand_.end(), 0);
    if (ImGui::CollapsingHeader("joints (rotation vector from bind, degrees)")) {
      for (std::uint32_t j = 0; j < info_.joint_count; ++j) {
        if (j == info_.model_joint) continue;  // it turns the model frame: the light, not shape
        ImGui::PushID(int(j));
        bool by_hand = hand_[j] != 0;
        char label[64];
        std::snprintf(label, sizeof label, "joint %u by hand", j);
        if (ImGui::Checkbox(label, &by_hand)) hand_[j] = by_hand ? 1 : 0;
        const char* axes[] = {"x", "y", "z"};
        for (int k = 0; k < 3; ++k) {
          float value = float(sliders_[3 * j + k]);
          if (ImGui::SliderFloat(axes[k], &value, float(lo_[3 * j + k]), float(hi_[3 * j + k]),
                                 "%.1f")) {
            sliders_[3 * j + k] = value;
            hand_[j] = 1;
          }
        }
        ImGui::PopID();
      }
    }
    labels(sample);
  }

  bool mouse_button(prt::sample::Sample& sample, prt::sample::MouseButton button, bool pressed,
                    double x, double y) override {
    if (button != prt::sample::MouseButton::Left) return false;
    if (!pressed) {
      const bool was = dragging_;
      dragging_ = false;
      return was;
    }
    if (mode_ != Compare::Split || !baked_) return false;
    dragging_ = std::abs(sample.to_frame(x, y).x - divider_) * sample.width() <= 8.0f;
    return dragging_;
  }

  bool mouse_move(prt::sample::Sample& sample, double x, double y) override {
    if (!dragging_) return false;
    divider_ = std::clamp(sample.to_frame(x, y).x, 0.0f, 1.0f);
    return true;
  }

  void stop(prt::sample::Sample&) override {
    if (compared_)
      std::printf(
          "prt-character: vs baked frame %u (clip %u, %.3f s)%s: relative RMSE %.5f "
          "(%.2f %%)\n",
          truth_frame_, baked_->clip[truth_frame_], baked_->time[truth_frame_],
          exact_ ? "" : ", another pose", rmse_, 100.0 * rmse_);
    runtime_.mesh.reset();
    truth_.mesh.reset();
    heat_.reset();
  }

 private:
  struct HandPose {
    unsigned joint = 0;
    double degrees[3] = {0.0, 0.0, 0.0};
  };

  std::string blob_path_, ground_truth_, compare_;
  std::vector<std::string> pose_options_;
  std::vector<HandPose> hand_poses_;
  Compare mode_ = Compare::Single;
  float divider_ = 0.5f, error_scale_ = 0.25f, speed_ = 1.0f;
  double time_ = 0.0, time_step_ = 0.0;
  std::uint32_t clip_ = 0;
  long start_frame_ = -1;
  bool paused_ = false, dragging_ = false;
  std::chrono::steady_clock::time_point previous_;

  std::unique_ptr<BlobScene> scene_;
  prt_pose_info info_{};
  std::uint32_t n2_ = 0;
  std::vector<float> bind_, rotations_, normals_, model_positions_;
  std::vector<double> sliders_, lo_, hi_;  // J x 3 degrees, and the sliders' ranges
  std::vector<char> hand_;                 // per joint: posed by the sliders, not the clip

  std::unique_ptr<BakedFrames> baked_;
  std::uint32_t truth_frame_ = 0;
  bool exact_ = false;  // the runtime's pose is the baked frame's
  double rmse_ = 0.0;
  bool compared_ = false;  // a frame compared the halves: stop() prints the last figure

  std::uint64_t light_version_ = ~0ull;
  std::size_t light_map_ = ~std::size_t(0);
  std::vector<float> map_light_, light_;  // n² RGB: the map's projection, and turned about +Y

  Half runtime_, truth_;
  std::unique_ptr<GpuMesh> heat_;

  void open_ground_truth(const prt::view::BlobMesh& mesh) {
    try {
      baked_ = std::make_unique<BakedFrames>(
          read_baked_frames(ground_truth_, info_.vertex_count, n2_, info_.joint_count));
    } catch (const std::runtime_error& e) {
      throw ViewerError(e.what());
    }
    truth_.mesh = std::make_unique<GpuMesh>(mesh.positions, info_.vertex_count, mesh.indices,
                                            mesh.triangle_count);
    heat_ = std::make_unique<GpuMesh>(mesh.positions, info_.vertex_count, mesh.indices,
                                      mesh.triangle_count);
    // The sliders reach twice the furthest rotation the training frames make on each side of
    // the bind pose (at least 20 degrees), so the model can be driven past what it learned.
    std::vector<double> lo(3u * info_.joint_count, 0.0), hi(3u * info_.joint_count, 0.0);
    std::vector<float> features(3u * info_.joint_count);
    for (std::uint32_t f = 0; f < baked_->frames; ++f) {
      prt_pose_input input = prt::sized<prt_pose_input>();
      input.joint_rotations = baked_->frame_rotations(f);
      check_runtime(prt_pose_features(scene_->asset(), &input, features.data()),
                    "prt_pose_features");
      for (std::size_t i = 0; i < features.size(); ++i) {
        lo[i] = std::min(lo[i], features[i] * kDegrees);
        hi[i] = std::max(hi[i], features[i] * kDegrees);
      }
    }
    for (std::size_t i = 0; i < lo.size(); ++i) {
      lo_[i] = std::min(2.0 * lo[i], -20.0);
      hi_[i] = std::max(2.0 * hi[i], 20.0);
    }
    if (clip_ >= baked_->clip_count())
      throw ViewerError("--clip " + std::to_string(clip_) + ": the bake has " +
                        std::to_string(baked_->clip_count()) + " clip(s)");
    if (start_frame_ >= 0) {
      if (start_frame_ >= long(baked_->frames))
        throw ViewerError("--frame " + std::to_string(start_frame_) + ": the bake has " +
                          std::to_string(baked_->frames) + " frames");
      clip_ = baked_->clip[start_frame_];
      time_ = baked_->time[start_frame_];
      paused_ = true;
    }
    time_ = std::clamp(time_, clip_start(), clip_end());
    std::printf("%s: %u baked frames of %u clip(s); clip %u runs %.3f..%.3f s\n",
                ground_truth_.c_str(), baked_->frames, baked_->clip_count(), clip_, clip_start(),
                clip_end());
  }

  double clip_start() const {
    std::uint32_t first = 0, last = 0;
    baked_->clip_frames(clip_, &first, &last);
    return baked_->time[first];
  }
  double clip_end() const {
    std::uint32_t first = 0, last = 0;
    baked_->clip_frames(clip_, &first, &last);
    return baked_->time[last];
  }

  void step_frame(int step) {
    std::uint32_t first = 0, last = 0;
    baked_->clip_frames(clip_, &first, &last);
    const long f = std::clamp(long(truth_frame_) + step, long(first), long(last));
    time_ = baked_->time[f];
    paused_ = true;
  }

  void advance_time() {
    const auto now = std::chrono::steady_clock::now();
    const double wall = std::chrono::duration<double>(now - previous_).count();
    previous_ = now;
    if (!baked_ || paused_) return;
    time_ += (time_step_ > 0.0 ? time_step_ : wall) * speed_;
    const double start = clip_start(), length = clip_end() - start;
    if (time_ > clip_end()) time_ = length > 0.0 ? start + std::fmod(time_ - start, length) : start;
  }

  // The joint rotations of this frame: the clip's (or the bind pose without one), then the
  // joints posed by hand. The sliders of the other joints follow the clip, so that taking a
  // joint by hand starts from where the clip has it.
  void pose() {
    exact_ = false;
    if (baked_) {
      truth_frame_ = clip_pose(*baked_, clip_, time_, rotations_.data());
      exact_ = std::abs(baked_->time[truth_frame_] - time_) < 1e-6;
    } else {
      rotations_ = bind_;
    }
    std::vector<float> features(3u * info_.joint_count);
    prt_pose_input input = prt::sized<prt_pose_input>();
    input.joint_rotations = rotations_.data();
    check_runtime(prt_pose_features(scene_->asset(), &input, features.data()), "prt_pose_features");
    for (std::uint32_t j = 0; j < info_.joint_count; ++j) {
      if (!hand_[j]) {
        for (int k = 0; k < 3; ++k) sliders_[3 * j + k] = features[3 * j + k] * kDegrees;
        continue;
      }
      const double r[3] = {sliders_[3 * j] / kDegrees, sliders_[3 * j + 1] / kDegrees,
                           sliders_[3 * j + 2] / kDegrees};
      from_rotation_vector(&bind_[4 * j], r, &rotations_[4 * j]);
      exact_ = false;
    }
  }

  // The map's SH projection (once per map), turned about +Y by the environment's rotation with
  // prt_sh_rotate: the world light prt_pose_shade takes.
  void prepare_light(prt::sample::Sample& sample) {
    prt::sample::Environments& envs = sample.environments();
    if (light_version_ == envs.light_version()) return;
    if (light_map_ != envs.current_index()) {
      map_light_.assign(3u * n2_, 0.0f);
      std::vector<float> faces;
      const prt_env_image env = prt::view::environment_image(envs.current(), nullptr, &faces);
      check_runtime(prt_sh_project(info_.order, &env, map_light_.data()), "prt_sh_project");
      light_map_ = envs.current_index();
    }
    float rotation[9];
    prt::io::rotation_about_y_row_major(envs.rotation_degrees(), rotation);
    light_.resize(map_light_.size());
    check_runtime(prt_sh_rotate(info_.order, rotation, map_light_.data(), light_.data(), 3),
                  "prt_sh_rotate");
    light_version_ = envs.light_version();
  }

  // Skins the vertices at `rotations` into half.positions (character space); the model frame
  // [R_m | o_m] into frame (12 floats), the model-frame normals into normals_.
  void skin(const float* rotations, Half& half, float* frame) {
    prt_pose_input input = prt::sized<prt_pose_input>();
    input.joint_rotations = rotations;
    check_runtime(prt_pose_skin(scene_->asset(), &input, 0, info_.vertex_count,
                                model_positions_.data(), normals_.data(), frame),
                  "prt_pose_skin");
    for (std::uint32_t v = 0; v < info_.vertex_count; ++v) {
      const float* p = &model_positions_[3 * v];
      for (int r = 0; r < 3; ++r)
        half.positions[3 * v + r] = frame[4 * r] * p[0] + frame[4 * r + 1] * p[1] +
                                    frame[4 * r + 2] * p[2] + frame[4 * r + 3];
    }
    half.mesh->upload_positions(half.positions.data());
  }

  void shade_runtime(prt::sample::Sample& sample) {
    if (sample.backend() == prt::sample::Backend::Gl)
      sample.fall_back_to_cpu(blob_path_ +
                              ": pose has no GL backend yet (prt_pose_shade: "
                              "PRT_ERROR_UNSUPPORTED_BACKEND)");
    float frame[12];
    skin(rotations_.data(), runtime_, frame);
    prt_pose_input input = prt::sized<prt_pose_input>();
    input.joint_rotations = rotations_.data();
    prt_pose_light light = prt::sized<prt_pose_light>();
    light.light_rgb = light_.data();
    light.normals = normals_.data();  // skinned above: the runtime need not skin them again
    const prt_backend backend = prt::sample::runtime_backend(sample.backend());
    const prt_result result = sample.time_shading([&] {
      return prt_pose_shade(scene_->asset(), backend, &input, &light, 0, info_.vertex_count,
                            runtime_.radiance.data());
    });
    if (result != PRT_OK)
      throw ViewerError(blob_path_ + ": prt_pose_shade failed on backend " +
                        prt_backend_name(backend) + ": " + prt_result_string(result));
    runtime_.mesh->upload_colours(runtime_.radiance.data());
  }

  // The nearest baked frame at its own pose: its transfer (model frame) dotted with the light
  // turned into its model frame, L' = rotate(L, R_mᵀ).
  void shade_truth() {
    float frame[12];
    skin(baked_->frame_rotations(truth_frame_), truth_, frame);
    const float model_from_world[9] = {frame[0], frame[4], frame[8], frame[1], frame[5],
                                       frame[9], frame[2], frame[6], frame[10]};
    std::vector<float> light(light_.size());
    check_runtime(prt_sh_rotate(info_.order, model_from_world, light_.data(), light.data(), 3),
                  "prt_sh_rotate");
    const float* t = baked_->frame_transfer(truth_frame_);
    for (std::uint32_t v = 0; v < info_.vertex_count; ++v, t += n2_)
      for (int ch = 0; ch < 3; ++ch) {
        double sum = 0.0;
        for (std::uint32_t c = 0; c < n2_; ++c) sum += double(t[c]) * light[3 * c + ch];
        truth_.radiance[3 * v + ch] = float(sum);
      }
    truth_.mesh->upload_colours(truth_.radiance.data());
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
    if (!baked_ || mode_ == Compare::Single) return;
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const float w = float(sample.width()), h = float(sample.height());
    const ImU32 white = IM_COL32(255, 255, 255, 230);
    const float split = mode_ == Compare::Split ? divider_ : 0.5f;
    draw->AddText(ImVec2(8.0f, h - 24.0f), white, "runtime (learned model)");
    char right[96];
    std::snprintf(right, sizeof right, "%s, baked frame %u",
                  mode_ == Compare::Error ? "error heat map" : "ground truth", truth_frame_);
    draw->AddText(ImVec2(split * w + 8.0f, h - 24.0f), white, right);
    if (mode_ == Compare::Split)
      draw->AddLine(ImVec2(split * w, 0.0f), ImVec2(split * w, h), white, 2.0f);
  }
};

}  // namespace
}  // namespace prt::character

int main(int argc, char** argv) {
  try {
    prt::character::CharacterApp app;
    return prt::sample::run_sample(
        "prt-character",
        "prt-character: a skinned character's learned transfer (technique pose) played, posed "
        "and compared with its baked frames (prtkit " PRT_VERSION_STRING ")",
        app, argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt-character: %s\n", e.what());
    return 1;
  }
}
