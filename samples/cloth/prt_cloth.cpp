// SPDX-License-Identifier: MIT
// prt-cloth: woven cloth (technique `cloth`) shaded per pixel by the runtime, in a window (or
// headless) on the sample framework. The cloth is the blob's mesh or a built-in draped sheet; the
// fabric is one of the blob's, its live parameters on sliders; the light is the framework's
// environment fitted with spherical Gaussians whenever it turns; and a split screen puts the
// runtime's shading beside the brute-force reference of the exact model under the same map,
// computed over a few frames, with their relative RMSE. README.md says how to run it.
//
// Each frame it makes the calls a game would: prt_cloth_fit_light when the light changed, then
// per pixel of the G-buffer the framework draws (world normal, warp, view direction)
// prt_cloth_shade_workers on the CPU backends or prt_gl_cloth_shade on GL.
#include <imgui.h>
#include <CLI/CLI.hpp>
#include <prt/prt.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "blob_scene.hpp"
#include "cloth_blob.hpp"
#include "cloth_light.hpp"
#include "compare.hpp"
#include "draped_patch.hpp"
#include "env_image.hpp"
#include "fabric_controls.hpp"
#include "gallery.hpp"
#include "progressive_pixels.hpp"
#include "prt/io/radiance_error.hpp"
#include "sample_app.hpp"

namespace prt::cloth_app {
namespace {

using prt::sample::Backend;
using prt::sample::FrameRect;
using prt::sample::PixelSamples;
using prt::sample::Sample;
using prt::sample::View;
using prt::view::ViewerError;

enum class Compare { Single, Side, Split, Error };
enum class MeshChoice { Auto, Blob, Patch };

// A window refines the CPU-side pictures for about this long per frame, so that it stays
// responsive; runs with --frames (and headless ones) compute them whole.
constexpr double kWindowBudgetMs = 60.0;

std::string file_name(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

struct WorkersDeleter {
  void operator()(prt_workers* workers) const { prt_workers_destroy(workers); }
};

class ClothApp : public prt::sample::SampleApp {
 public:
  ClothApp() : runtime_shader_(*this), reference_shader_(*this), heat_shader_(*this) {}

  void add_options(CLI::App& app) override {
    cli_ = &app;
    app.add_option("BLOB", blob_path_, "A cloth blob (prt-bake bake cloth)")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("--fabric", fabric_name_, "The fabric to show (default: the blob's first)");
    app.add_option("--mesh", mesh_text_,
                   "auto|blob|patch: the blob's mesh (auto: when it has one) or the built-in "
                   "draped sheet")
        ->check(CLI::IsMember({"auto", "blob", "patch"}))
        ->capture_default_str();
    overrides_.add_options(app);
    app.add_option("--lobes", lobe_count_,
                   "Spherical Gaussians K the environment is fitted with (prt_cloth_fit_light)")
        ->check(CLI::Range(1u, PRT_CLOTH_MAX_LOBES))
        ->capture_default_str();
    app.add_option("--compare", compare_text_,
                   "single|side|split|error: the runtime alone, beside the brute-force reference, "
                   "in a split screen with it, or beside the heat map of its error")
        ->check(CLI::IsMember({"single", "side", "split", "error"}))
        ->capture_default_str();
    app.add_option("--divider", divider_, "Split screen: where the divider is (0..1 of the width)")
        ->check(CLI::Range(0.0f, 1.0f))
        ->capture_default_str();
    app.add_option("--error-scale", error_scale_, "Heat map: relative error shown as white")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--reference-size", reference_size_,
                   "The reference's lat-long grid the map is binned onto, WxH")
        ->capture_default_str();
    app.add_option("--reference-bright", reference_settings_.max_bright,
                   "Texels brighter than 20x the map's mean the reference keeps at full "
                   "resolution, at most")
        ->capture_default_str();
    app.add_option("--frame-budget", budget_ms_,
                   "Milliseconds per frame the CPU-side pictures are refined for (0: whole "
                   "pictures every frame; default 60 in a window, 0 headless or with --frames)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--gallery", gallery_path_,
                   "Render every fabric of the blob, one frame each, into this labelled PNG grid");
    app.footer(
        "Keys: left-drag orbit (or the split's divider), right-drag turn the light, wheel zoom, "
        "F frame, P or F12 screenshot, H overlay, Esc quit.");
  }

  void check_options() override {
    const char* compares[] = {"single", "side", "split", "error"};
    for (int i = 0; i < 4; ++i)
      if (compare_text_ == compares[i]) mode_ = Compare(i);
    mesh_choice_ = mesh_text_ == "blob"    ? MeshChoice::Blob
                   : mesh_text_ == "patch" ? MeshChoice::Patch
                                           : MeshChoice::Auto;
    char x = 0, tail = 0;
    if (std::sscanf(reference_size_.c_str(), "%d%c%d%c", &reference_settings_.width, &x,
                    &reference_settings_.height, &tail) != 3 ||
        (x != 'x' && x != 'X') || reference_settings_.width < 4 || reference_settings_.height < 2 ||
        reference_settings_.width > 4096 || reference_settings_.height > 2048)
      throw CLI::ValidationError(
          "--reference-size", "expected WxH from 4x2 to 4096x2048, got '" + reference_size_ + "'");
    overrides_.check();
    if (cli_->get_option("--frame-budget")->count() == 0)
      budget_ms_ = cli_->get_option("--headless")->count() || cli_->get_option("--frames")->count()
                       ? 0.0
                       : kWindowBudgetMs;
    // The blob is read here, so that a fabric or a mesh it lacks is a bad argument.
    blob_ = std::make_unique<ClothBlob>(blob_path_);
    if (!fabric_name_.empty()) {
      const int found = blob_->find(fabric_name_);
      if (found < 0)
        throw CLI::ValidationError("--fabric", blob_path_ + " has no fabric '" + fabric_name_ +
                                                   "'; it has: " + blob_->fabric_names());
      fabric_ = std::uint32_t(found);
    }
    for (const Fabric& fabric : blob_->fabrics()) overrides_.apply(fabric.defaults, fabric.name);
    params_ = overrides_.apply(blob_->fabrics()[fabric_].defaults, blob_->fabrics()[fabric_].name);
    if (mesh_choice_ == MeshChoice::Blob && !blob_->mesh_problem().empty())
      throw CLI::ValidationError("--mesh", blob_path_ + ": " + blob_->mesh_problem());
  }

  void start(Sample& sample) override {
    sample_ = &sample;
    open_mesh(sample);
    prt_workers* workers = nullptr;
    prt::view::check_runtime(prt_workers_create(blob_->context(), nullptr, &workers),
                             "prt_workers_create");
    workers_.reset(workers);
    probe_simd(sample);
    open_gl(sample);
    std::printf("%s: %u fabric(s): %s; %u tables, %zu table bytes, %u-bit\n", blob_path_.c_str(),
                blob_->info().fabric_count, blob_->fabric_names().c_str(),
                blob_->info().table_count, blob_->info().table_bytes, blob_->info().bits);
    std::printf("prt-cloth: %s; %u worker thread(s)\n", mesh_note_.c_str(),
                prt_workers_thread_count(workers_.get()));
    if (!gallery_path_.empty()) {
      gallery_index_ = 0;
      select_fabric(0, true);
    }
  }

  std::vector<View> frame(Sample& sample) override {
    if (gallery_active() && fabric_ != gallery_index_) select_fabric(gallery_index_, true);
    const bool lobes_moved = light_.update(blob_->context(), sample.environments(), lobe_count_);
    const bool texels_moved =
        comparing() && texels_.update(sample.environments(), reference_settings_);
    shade_version_ += lobes_moved;
    reference_version_ += texels_moved;
    light_turning_ = frames_++ > 0 && (lobes_moved || texels_moved);
    if (sample.backend() != backend_) ++shade_version_, backend_ = sample.backend();
    budget_left_ = budget_ms_;
    gl_drawn_ = false;
    describe(sample);

    std::vector<View> views;
    const FrameRect whole;
    // Halves of equal pixel widths, so that both sides of side and error see the same samples.
    const float w = float(std::max(sample.width(), 1)), half = std::floor(0.5f * w);
    const FrameRect left{0.0f, 0.0f, half / w, 1.0f}, right{(w - half) / w, 0.0f, 1.0f, 1.0f};
    switch (mode_) {
      case Compare::Single:
        views.push_back(pixel_view(runtime_shader_, whole, whole));
        break;
      case Compare::Split:
        views.push_back(pixel_view(runtime_shader_, whole, {0.0f, 0.0f, divider_, 1.0f}));
        views.push_back(pixel_view(reference_shader_, whole, {divider_, 0.0f, 1.0f, 1.0f}));
        break;
      case Compare::Side:
        views.push_back(pixel_view(runtime_shader_, left, left));
        views.push_back(pixel_view(reference_shader_, right, right));
        break;
      case Compare::Error:
        views.push_back(pixel_view(runtime_shader_, left, left));
        views.push_back(pixel_view(heat_shader_, right, right));
        views.back().display_colours = true;
        break;
    }
    return views;
  }

  void drawn(Sample& sample) override {
    const bool runtime_done = gl_drawn_ || runtime_.complete();
    settled_ = runtime_done && (!comparing() || reference_.complete());
    if (!gallery_active() || !settled_) return;
    prt::io::Rgb8Image picture;
    picture.rgb = sample.read_picture(&picture.width, &picture.height);
    gallery_pictures_.push_back(std::move(picture));
    std::printf("prt-cloth: gallery %u/%zu: %s\n", gallery_index_ + 1, blob_->fabrics().size(),
                blob_->fabrics()[gallery_index_].name.c_str());
    if (++gallery_index_ == blob_->fabrics().size()) write_gallery_file(sample);
  }

  // A light that turns every frame (--spin) never lets a picture computed over frames finish.
  bool busy() const override {
    return gallery_active() || (budget_ms_ > 0.0 && !settled_ && !light_turning_);
  }

  int default_supersample() const override { return 1; }

  void panel(Sample& sample) override {
    const std::vector<Fabric>& fabrics = blob_->fabrics();
    if (ImGui::BeginCombo("fabric", fabrics[fabric_].name.c_str())) {
      for (std::uint32_t f = 0; f < fabrics.size(); ++f)
        if (ImGui::Selectable(fabrics[f].name.c_str(), f == fabric_)) select_fabric(f, false);
      ImGui::EndCombo();
    }
    if (ImGui::Button("reset to the fabric's defaults")) select_fabric(fabric_, false);
    if (ImGui::CollapsingHeader("live parameters", ImGuiTreeNodeFlags_DefaultOpen) &&
        fabric_sliders(params_))
      parameters_changed();
    int lobes = int(lobe_count_);
    if (ImGui::SliderInt("light lobes K", &lobes, 1, 64)) lobe_count_ = std::uint32_t(lobes);
    ImGui::TextUnformatted(light_.describe().c_str());
    int mode = int(mode_);
    const char* modes[] = {"runtime only", "side by side", "split screen", "error heat map"};
    if (ImGui::Combo("compare", &mode, modes, 4)) mode_ = Compare(mode);
    if (mode_ == Compare::Error) ImGui::SliderFloat("error scale", &error_scale_, 0.01f, 1.0f);
    if (comparing()) ImGui::TextWrapped("reference light: %s", texels_.describe().c_str());
    labels(sample);
  }

  bool mouse_button(Sample& sample, prt::sample::MouseButton button, bool pressed, double x,
                    double) override {
    if (button != prt::sample::MouseButton::Left) return false;
    if (!pressed) {
      const bool was = dragging_;
      dragging_ = false;
      return was;
    }
    if (mode_ != Compare::Split) return false;
    dragging_ = std::abs(sample.to_frame(x, 0.0).x - divider_) * sample.width() <= 8.0f;
    return dragging_;
  }

  bool mouse_move(Sample& sample, double x, double) override {
    if (!dragging_) return false;
    divider_ = std::clamp(sample.to_frame(x, 0.0).x, 0.0f, 1.0f);
    return true;
  }

  void stop(Sample&) override {
    if (compared_ > 0)
      std::printf(
          "prt-cloth: runtime (%s) vs reference, fabric %s: relative RMSE %.5f (%.2f %%) over %zu "
          "pixels, the reference %.0f %% done\n",
          prt::sample::backend_name(backend_), blob_->fabrics()[fabric_].name.c_str(), rmse_,
          100.0 * rmse_, compared_, 100.0 * reference_.progress());
#if PRT_CLOTH_APP_GL
    prt_gl_cloth_destroy(gl_shader_);
    gl_shader_ = nullptr;
#endif
    workers_.reset();
    mesh_.reset();
  }

 private:
  // The three kinds of per-pixel views: the runtime's shading, the reference, the heat map.
  class RuntimeShader : public prt::sample::PixelShader {
   public:
    explicit RuntimeShader(ClothApp& app) : app_(app) {}
    bool uses_gl() const override { return app_.gl_ready(); }
    void shade_gl(const prt::sample::GlGBuffer& gbuffer) override { app_.shade_gl(gbuffer); }
    bool reads_gl_radiance() const override { return app_.comparing(); }
    void gl_radiance(const PixelSamples& samples, const std::vector<float>& rgb) override {
      app_.runtime_.set_all(samples, app_.shade_version_, rgb);
    }
    void shade(const PixelSamples& samples, std::vector<float>& rgb) override {
      app_.shade_runtime(samples, rgb);
    }

   private:
    ClothApp& app_;
  };
  class ReferenceShader : public prt::sample::PixelShader {
   public:
    explicit ReferenceShader(ClothApp& app) : app_(app) {}
    void shade(const PixelSamples& samples, std::vector<float>& rgb) override {
      app_.advance_reference(samples);
      app_.reference_.fill(rgb);
    }

   private:
    ClothApp& app_;
  };
  class HeatShader : public prt::sample::PixelShader {
   public:
    explicit HeatShader(ClothApp& app) : app_(app) {}
    void shade(const PixelSamples& samples, std::vector<float>& rgb) override {
      app_.advance_reference(samples);
      app_.heat_map(rgb);
    }

   private:
    ClothApp& app_;
  };

  CLI::App* cli_ = nullptr;
  std::string blob_path_, fabric_name_, mesh_text_ = "auto", compare_text_ = "single";
  std::string reference_size_ = "128x64", gallery_path_;
  FabricOverrides overrides_;
  MeshChoice mesh_choice_ = MeshChoice::Auto;
  Compare mode_ = Compare::Single;
  float divider_ = 0.5f, error_scale_ = 0.25f;
  std::uint32_t lobe_count_ = 10;
  double budget_ms_ = 0.0, budget_left_ = 0.0;
  bool dragging_ = false;

  std::unique_ptr<ClothBlob> blob_;
  std::uint32_t fabric_ = 0;
  prt_cloth_params params_{};
  std::unique_ptr<prt::sample::GpuMesh> mesh_;
  std::string mesh_note_;
  std::unique_ptr<prt_workers, WorkersDeleter> workers_;
  Sample* sample_ = nullptr;
  Backend backend_ = Backend::Cpu;
#if PRT_CLOTH_APP_GL
  prt_gl_cloth_shader* gl_shader_ = nullptr;
#endif
  bool gl_drawn_ = false;  // the GL backend drew this frame's runtime view

  FittedLight light_;
  ReferenceSettings reference_settings_;
  ReferenceTexels texels_;
  // What the pictures are computed from: bumped when it changes.
  std::uint64_t shade_version_ = 1, reference_version_ = 1;
  ProgressivePixels runtime_, reference_;
  double reference_ms_ = 0.0;   // spent on the current reference
  bool settled_ = false;        // the last frame showed finished pictures
  bool light_turning_ = false;  // the light changed since the frame before
  std::uint64_t frames_ = 0;
  double rmse_ = 0.0;
  std::size_t compared_ = 0;  // pixels the last figure is over

  std::uint32_t gallery_index_ = 0;
  std::vector<prt::io::Rgb8Image> gallery_pictures_;

  RuntimeShader runtime_shader_;
  ReferenceShader reference_shader_;
  HeatShader heat_shader_;

  bool comparing() const {
    return mode_ != Compare::Single;
  }
  bool gallery_active() const {
    return !gallery_path_.empty() && blob_ && gallery_index_ < blob_->fabrics().size();
  }
  bool gl_ready() const {
#if PRT_CLOTH_APP_GL
    return gl_shader_ && sample_ && sample_->backend() == Backend::Gl;
#else
    return false;
#endif
  }

  View pixel_view(prt::sample::PixelShader& shader, const FrameRect& viewport,
                  const FrameRect& clip) const {
    View v;
    v.mesh = mesh_.get();
    v.pixel_shader = &shader;
    v.viewport = viewport;
    v.clip = clip;
    return v;
  }

  // The fabric's defaults (with the command line's values in a gallery), and pictures anew.
  void select_fabric(std::uint32_t fabric, bool with_overrides) {
    const Fabric& f = blob_->fabrics()[fabric];
    fabric_ = fabric;
    params_ = with_overrides ? overrides_.apply(f.defaults, f.name) : f.defaults;
    parameters_changed();
  }
  void parameters_changed() {
    ++shade_version_;
    ++reference_version_;
    settled_ = false;
  }

  void open_mesh(Sample& sample) {
    FramedMesh mesh;
    const std::string problem = blob_->mesh_problem();
    if (mesh_choice_ != MeshChoice::Patch && problem.empty()) {
      mesh = blob_->mesh();
      mesh_note_ = "the blob's mesh";
    } else {
      mesh = draped_patch();
      mesh_note_ = "the built-in draped sheet";
      if (mesh_choice_ == MeshChoice::Auto) mesh_note_ += " (" + problem + ")";
    }
    mesh_note_ += ", " + std::to_string(mesh.vertex_count()) + " vertices, " +
                  std::to_string(mesh.triangle_count()) + " triangles";
    mesh_ = std::make_unique<prt::sample::GpuMesh>(mesh.positions.data(), mesh.normals.data(),
                                                   mesh.warps.data(), mesh.vertex_count(),
                                                   mesh.indices.data(), mesh.triangle_count());
    sample.set_scene_bounds(mesh_->lo(), mesh_->hi(), true);
    sample.meter_exposure();
  }

  // Whether cloth's SIMD backend runs here: the context may allow SIMD (SSE4.1, say) where
  // cloth's kernels (AVX2 + FMA) cannot, or the runtime may not have them.
  void probe_simd(Sample& sample) {
    const float n[3] = {0.0f, 1.0f, 0.0f}, u[3] = {1.0f, 0.0f, 0.0f}, v[3] = {0.0f, 1.0f, 0.0f};
    prt_cloth_pixels pixels = prt::sized<prt_cloth_pixels>();
    pixels.normals = n, pixels.warps = u, pixels.views = v;
    prt_cloth_light light = prt::sized<prt_cloth_light>();
    float rgb[3];
    const prt_result r = prt_cloth_shade(blob_->asset(), PRT_BACKEND_SIMD, 0, nullptr, &light,
                                         nullptr, &pixels, 0, 1, rgb);
    if (r != PRT_OK)
      sample.backend_unusable(Backend::Simd,
                              std::string("cloth's simd backend: prt_cloth_shade: ") +
                                  prt_result_string(r) + "; cpu shades instead");
  }

  void open_gl(Sample& sample) {
#if PRT_CLOTH_APP_GL
    const prt_result r = prt_gl_cloth_create(blob_->context(), blob_->asset(), sample.gl_loader(),
                                             sample.gl_loader_user(), &gl_shader_);
    if (r != PRT_OK)
      sample.backend_unusable(Backend::Gl,
                              std::string("cloth's gl backend: prt_gl_cloth_create: ") +
                                  prt_context_last_message(blob_->context()) +
                                  "; a CPU backend shades instead");
#else
    sample.backend_unusable(Backend::Gl,
                            "cloth's gl backend (prt_gl_cloth_shade) is not in the runtime this "
                            "was built with; a CPU backend shades instead");
#endif
  }

  void shade_gl(const prt::sample::GlGBuffer& gbuffer) {
#if PRT_CLOTH_APP_GL
    prt_gl_cloth_gbuffer g = prt::sized<prt_gl_cloth_gbuffer>();
    g.normal_texture = gbuffer.normal_texture;
    g.warp_texture = gbuffer.tangent_texture;
    g.view_texture = gbuffer.view_texture;
    const prt_result r = sample_->time_shading([&] {
      return prt_gl_cloth_shade(gl_shader_, fabric_, &params_, &light_.light(), nullptr, &g);
    });
    if (r != PRT_OK)
      sample_->backend_unusable(Backend::Gl,
                                std::string("prt_gl_cloth_shade: ") + prt_result_string(r));
    gl_drawn_ = true;
#else
    (void)gbuffer;
#endif
  }

  prt_cloth_pixels ordered(const ProgressivePixels& p) const {
    prt_cloth_pixels pixels = prt::sized<prt_cloth_pixels>();
    pixels.normals = p.ordered_normals();
    pixels.warps = p.ordered_tangents();
    pixels.views = p.ordered_views();
    return pixels;
  }

  // The runtime's radiance of the samples on a CPU backend, a share per frame in a window.
  void shade_runtime(const PixelSamples& samples, std::vector<float>& rgb) {
    const Backend backend = sample_->backend() == Backend::Gl ? Backend::Cpu : sample_->backend();
    runtime_.track(samples, shade_version_, budget_ms_ > 0.0);
    const prt_cloth_pixels pixels = ordered(runtime_);
    auto compute = [&](std::uint32_t first, std::uint32_t count, float* out) {
      const prt_result r = sample_->time_shading([&] {
        return prt_cloth_shade_workers(workers_.get(), blob_->asset(),
                                       prt::sample::runtime_backend(backend), fabric_, &params_,
                                       &light_.light(), nullptr, &pixels, first, count, out);
      });
      if (r == PRT_ERROR_UNSUPPORTED_BACKEND) {
        sample_->backend_unusable(backend, std::string("prt_cloth_shade on ") +
                                               prt::sample::backend_name(backend) + ": " +
                                               prt_result_string(r));
        ++shade_version_;  // shaded again on the backend that takes over
      } else if (r != PRT_OK) {
        throw ViewerError(std::string("prt_cloth_shade_workers failed: ") + prt_result_string(r));
      }
    };
    if (!runtime_.complete())
      budget_left_ -=
          runtime_.advance(budget_ms_ > 0.0 ? std::max(budget_left_, 1.0) : 0.0, compute);
    runtime_.fill(rgb);
  }

  // The reference's next share of the samples (all of it without a frame budget), once a frame.
  void advance_reference(const PixelSamples& samples) {
    if (reference_.track(samples, reference_version_)) reference_ms_ = 0.0;
    const Fabric& fabric = blob_->fabrics()[fabric_];
    const prt_cloth_pixels pixels = ordered(reference_);
    auto compute = [&](std::uint32_t first, std::uint32_t count, float* out) {
      prt::view::check_runtime(
          prt_cloth_reference_workers(workers_.get(), &params_, &fabric.weave, &texels_.texels(),
                                      &pixels, first, count, out),
          "prt_cloth_reference_workers");
    };
    if (!reference_.complete() && (budget_ms_ == 0.0 || budget_left_ > 0.0)) {
      const double spent = reference_.advance(budget_ms_ > 0.0 ? budget_left_ : 0.0, compute);
      budget_left_ -= spent;
      reference_ms_ += spent;
    }
    measure_error();
  }

  // The relative RMSE of the runtime against the reference over the pixels both have.
  void measure_error() {
    if (runtime_.version() != shade_version_) return;
    const PairedValues pairs = paired_values(runtime_, reference_);
    double norm = 0.0;
    for (const glm::vec3& r : pairs.b) norm += glm::dot(r, r);
    if (!(norm > 0.0)) return;
    rmse_ = prt::io::relative_rmse(pairs.a, pairs.b);
    compared_ = pairs.a.size();
  }

  // Heat colours of |runtime - reference| over the mean |reference|; NaN (not drawn) where
  // either is not computed yet.
  void heat_map(std::vector<float>& rgb) const {
    rgb.assign(3 * reference_.samples().size(), std::nanf(""));
    if (runtime_.version() != shade_version_) return;
    const PairedValues pairs = paired_values(runtime_, reference_);
    const std::vector<float> error = prt::view::relative_vertex_error(pairs.a, pairs.b);
    for (std::size_t i = 0; i < error.size(); ++i) {
      const glm::vec3 c = prt::view::heat_colour(error[i], error_scale_);
      float* out = &rgb[3 * pairs.b_sample[i]];
      out[0] = c.r, out[1] = c.g, out[2] = c.b;
    }
  }

  // This frame's overlay lines (the figures of the frame before).
  void describe(Sample& sample) const {
    const Fabric& fabric = blob_->fabrics()[fabric_];
    sample.overlay_line("fabric " + fabric.name + " on " + mesh_note_);
    sample.overlay_line("light: " + light_.describe());
    char line[256];
    if (!gl_ready() && !runtime_.complete()) {
      std::snprintf(line, sizeof line, "runtime: %.0f %% of %zu pixels",
                    100.0 * runtime_.progress(), runtime_.size());
      sample.overlay_line(line);
    }
    if (!comparing()) return;
    std::uint32_t tangents = fabric.weave.tangent_count[0] + fabric.weave.tangent_count[1];
    std::snprintf(line, sizeof line,
                  "reference: %.0f %% of %zu pixels, %.1f s (%u texels x %u tangents a pixel)",
                  100.0 * reference_.progress(), reference_.size(), reference_ms_ / 1000.0,
                  texels_.count(), tangents);
    sample.overlay_line(line);
    if (compared_ > 0) {
      std::snprintf(line, sizeof line, "vs reference: relative RMSE %.2f %% over %zu pixels",
                    100.0 * rmse_, compared_);
      sample.overlay_line(line);
    }
  }

  void write_gallery_file(Sample& sample) {
    std::vector<std::string> names;
    for (const Fabric& f : blob_->fabrics()) names.push_back(f.name);
    const prt::sample::Environments& envs = sample.environments();
    char caption[512];
    std::snprintf(caption, sizeof caption, "%s under %s turned %.0f deg, %s backend, %u lobes",
                  file_name(blob_path_).c_str(), file_name(envs.current_path()).c_str(),
                  envs.rotation_degrees(), prt::sample::backend_name(backend_), lobe_count_);
    write_gallery(gallery_path_, gallery_pictures_, names, caption);
    std::printf("wrote %s (%zu fabrics)\n", gallery_path_.c_str(), gallery_pictures_.size());
  }

  // What each half shows (overlay only, so screenshots show the scene alone).
  void labels(Sample& sample) const {
    if (!comparing()) return;
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const float w = float(sample.width()), h = float(sample.height());
    const ImU32 white = IM_COL32(255, 255, 255, 230);
    const float split = mode_ == Compare::Split ? divider_ : 0.5f;
    draw->AddText(ImVec2(8.0f, h - 24.0f), white, "runtime");
    draw->AddText(ImVec2(split * w + 8.0f, h - 24.0f), white,
                  mode_ == Compare::Error ? "error heat map" : "brute-force reference");
    if (mode_ == Compare::Split)
      draw->AddLine(ImVec2(split * w, 0.0f), ImVec2(split * w, h), white, 2.0f);
  }
};

}  // namespace
}  // namespace prt::cloth_app

int main(int argc, char** argv) {
  try {
    prt::cloth_app::ClothApp app;
    return prt::sample::run_sample(
        "prt-cloth",
        "prt-cloth: woven cloth (technique cloth) shaded per pixel under a turning environment, "
        "its fabric's parameters live, beside the brute-force reference (prtkit " PRT_VERSION_STRING
        ")",
        app, argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt-cloth: %s\n", e.what());
    return 1;
  }
}
