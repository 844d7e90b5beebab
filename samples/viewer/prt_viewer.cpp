// SPDX-License-Identifier: MIT
// prt-viewer: blobs of any technique in techniques.cpp, lit by environment maps and shaded by
// the runtime every frame, in a window (or headless) on the sample framework: one blob, two side
// by side or in a split screen, or one beside its error against a reference; or a baked scene
// (a .prts manifest, scene_view.hpp). Each technique's live parameters are controls; blobs and
// maps dropped on the window are opened. README.md says how to run it and its keys.
#include <imgui.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "live_parameter_panel.hpp"
#include "path_names.hpp"
#include "sample_app.hpp"
#include "scene_view.hpp"
#include "viewer_compare.hpp"
#include "viewer_slot.hpp"

namespace prt::view {
namespace {

class ViewerApp : public prt::sample::SampleApp {
 public:
  void add_options(CLI::App& app) override {
    cli_ = &app;
    app.add_option("BLOB", blob_paths_,
                   "One blob (.prtk), or two to compare; or a scene manifest (.prts)")
        ->required()
        ->expected(1, 2);
    app.add_option("--compare", compare_,
                   "single|side|split|error (default: single for one blob, side for two, error "
                   "with --reference)")
        ->check(CLI::IsMember({"single", "side", "split", "error"}));
    app.add_option("--reference", reference_,
                   "prt-bake reference --vertex-out of the first blob's scene: its error as a heat "
                   "map and the relative RMSE");
    app.add_option("--error-scale", error_scale_,
                   "Heat map: relative error shown as white (as prt-view)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--divider", divider_, "Split screen: where the divider is (0..1 of the width)")
        ->check(CLI::Range(0.0f, 1.0f))
        ->capture_default_str();
    app.footer("Techniques: " + chooser_.names() +
               ". Keys: left-drag orbit, right-drag turn the light, wheel zoom, F frame, P or F12 "
               "screenshot, H overlay, Esc quit; drop a .prtk to open it, an .hdr to add the map. "
               "A scene (prt-bake scene's OUT/scene.prts) is shaded with prt_scene_shade.");
    chooser_.add_options(app);
  }

  void check_options() override {
    if (std::any_of(blob_paths_.begin(), blob_paths_.end(), is_scene_manifest)) {
      if (blob_paths_.size() != 1 || !compare_.empty() || !reference_.empty())
        throw CLI::ValidationError(
            "BLOB", "a scene (.prts) is shown alone: no second blob, --compare or --reference");
      const CLI::Option* option = cli_->get_option("--backend");
      const std::string backend =
          option->count() ? option->as<std::string>() : option->get_default_str();
      scene_ = std::make_unique<SceneView>(blob_paths_[0], backend);
      return;
    }
    if (compare_.empty())
      compare_ = !reference_.empty() ? "error" : blob_paths_.size() == 2 ? "side" : "single";
    mode_ = parse_compare_mode(compare_);
    const bool two = mode_ == CompareMode::Side || mode_ == CompareMode::Split;
    if (two && blob_paths_.size() != 2)
      throw CLI::ValidationError("--compare", compare_ + " needs two blobs");
    if (mode_ == CompareMode::Error && reference_.empty())
      throw CLI::ValidationError("--compare", "error needs --reference REF.npy");
  }

  void start(prt::sample::Sample& sample) override {
    if (scene_) return scene_->start(sample);
    for (const std::string& path : blob_paths_) open_blob(sample, path, slots_.size());
    if (!reference_.empty()) open_reference();
  }

  std::vector<prt::sample::View> frame(prt::sample::Sample& sample) override {
    using prt::sample::View;
    if (scene_) return scene_->frame(sample);
    std::vector<View> views;
    const bool error = mode_ == CompareMode::Error && error_view_;
    const GLuint a = slots_[0]->shade(sample, error);
    if (mode_ == CompareMode::Single) {
      views.push_back(view(*slots_[0], a, {}, {}));
    } else if (error) {
      rmse_ = error_view_->update(slots_[0]->radiance(), error_scale_);
      views.push_back(view(*slots_[0], a, left_half(), left_half()));
      View heat;
      heat.mesh = &error_view_->mesh();
      heat.colour_buffer = error_view_->mesh().own_colours();
      heat.display_colours = true;
      heat.viewport = heat.clip = right_half();
      views.push_back(heat);
      char line[256];
      std::snprintf(line, sizeof line, "error vs %s: relative RMSE %.2f %%",
                    file_name(error_view_->reference_path()).c_str(), 100.0 * rmse_);
      sample.overlay_line(line);
    } else if (slots_.size() == 2) {
      const GLuint b = slots_[1]->shade(sample, false);
      if (mode_ == CompareMode::Side) {
        views.push_back(view(*slots_[0], a, left_half(), left_half()));
        views.push_back(view(*slots_[1], b, right_half(), right_half()));
      } else {
        views.push_back(view(*slots_[0], a, {}, left_of(divider_)));
        views.push_back(view(*slots_[1], b, {}, right_of(divider_)));
      }
    }
    return views;
  }

  void panel(prt::sample::Sample& sample) override {
    if (scene_) return scene_->panel(sample);
    int mode = static_cast<int>(mode_);
    const char* modes[] = {"one blob", "side by side", "split screen", "error vs reference"};
    if (ImGui::Combo("compare", &mode, modes, 4)) {
      const CompareMode wanted = static_cast<CompareMode>(mode);
      const bool two = wanted == CompareMode::Side || wanted == CompareMode::Split;
      if ((!two || slots_.size() == 2) && (wanted != CompareMode::Error || error_view_))
        mode_ = wanted;
    }
    for (std::size_t i = 0; i < slots_.size(); ++i) {
      ViewerSlot& slot = *slots_[i];
      ImGui::Text("%c: %s  (%s)", char('A' + i), file_name(slot.path()).c_str(),
                  slot.technique_name().c_str());
      if (live_parameter_panel(slot.technique().live_parameters(), slot.path().c_str()))
        slot.invalidate_light();
    }
    if (mode_ == CompareMode::Error) ImGui::SliderFloat("error scale", &error_scale_, 0.01f, 1.0f);
    labels(sample);
  }

  bool mouse_button(prt::sample::Sample& sample, prt::sample::MouseButton button, bool pressed,
                    double x, double y) override {
    if (button != prt::sample::MouseButton::Left) return false;
    if (!pressed) {
      const bool was = dragging_divider_;
      dragging_divider_ = false;
      return was;
    }
    if (mode_ != CompareMode::Split) return false;
    const float at = sample.to_frame(x, y).x;
    dragging_divider_ = std::abs(at - divider_) * sample.width() <= 8.0f;
    return dragging_divider_;
  }

  bool mouse_move(prt::sample::Sample& sample, double x, double y) override {
    if (!dragging_divider_) return false;
    divider_ = std::clamp(sample.to_frame(x, y).x, 0.0f, 1.0f);
    return true;
  }

  void drop(prt::sample::Sample& sample, const std::vector<std::string>& paths) override {
    for (const std::string& path : paths) {
      try {
        if (has_extension(path, ".hdr")) {
          sample.environments().add(path);
          sample.meter_exposure();
          std::printf("prt-viewer: added the map %s\n", path.c_str());
        } else if (scene_) {
          scene_->open(sample, path);
          std::printf("prt-viewer: opened %s\n", path.c_str());
        } else {
          open_blob(sample, path, 0);
          std::printf("prt-viewer: opened %s\n", path.c_str());
        }
      } catch (const std::exception& e) {
        sample.report(e.what());
      }
    }
  }

  void stop(prt::sample::Sample&) override {
    if (scene_) scene_->release_gl();
    if (error_view_) {
      std::printf("error vs %s: relative RMSE %.5f (%.2f %%)\n",
                  error_view_->reference_path().c_str(), rmse_, 100.0 * rmse_);
      error_view_->release_gl();
    }
    for (const std::unique_ptr<ViewerSlot>& slot : slots_) slot->release_gl();
  }

 private:
  ViewTechniques chooser_;  // --technique and the techniques' options
  std::vector<std::string> blob_paths_;
  std::string compare_, reference_;
  CompareMode mode_ = CompareMode::Single;
  float error_scale_ = 0.25f, divider_ = 0.5f;
  bool dragging_divider_ = false;
  double rmse_ = 0.0;
  std::vector<std::unique_ptr<ViewerSlot>> slots_;
  std::unique_ptr<ErrorView> error_view_;
  CLI::App* cli_ = nullptr;           // for the framework's --backend, which a scene reads
  std::unique_ptr<SceneView> scene_;  // the scene mode, instead of the slots

  static prt::sample::View view(const ViewerSlot& slot, GLuint colours,
                                const prt::sample::FrameRect& viewport,
                                const prt::sample::FrameRect& clip) {
    prt::sample::View v;
    v.mesh = &slot.mesh();
    v.colour_buffer = colours;
    v.viewport = viewport;
    v.clip = clip;
    return v;
  }

  // Opens `path` into slot `index` (replacing the blob there, or adding one); the first blob
  // frames the camera.
  void open_blob(prt::sample::Sample& sample, const std::string& path, std::size_t index) {
    auto slot = std::make_unique<ViewerSlot>(path, chooser_);
    if (index == 0) sample.set_scene_bounds(slot->mesh().lo(), slot->mesh().hi(), true);
    if (index < slots_.size()) {
      slots_[index]->release_gl();
      slots_[index] = std::move(slot);
      if (index == 0 && error_view_) {
        error_view_.reset();  // the reference belongs to the blob it was rendered for
        if (mode_ == CompareMode::Error) mode_ = CompareMode::Single;
      }
    } else {
      slots_.push_back(std::move(slot));
    }
    sample.meter_exposure();
  }

  void open_reference() {
    error_view_ = std::make_unique<ErrorView>(reference_, slots_[0]->blob_mesh());
  }

  // Labels over each half in the compare modes and the split screen's divider (overlay only, so
  // screenshots show the scene alone).
  void labels(prt::sample::Sample& sample) const {
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const float w = float(sample.width()), h = float(sample.height());
    const ImU32 white = IM_COL32(255, 255, 255, 230);
    auto label = [&](float x, std::size_t slot, const char* what) {
      const std::string text = std::string(what) + file_name(slots_[slot]->path()) + " (" +
                               slots_[slot]->technique_name() + ")";
      draw->AddText(ImVec2(x + 8.0f, h - 24.0f), white, text.c_str());
    };
    if (mode_ == CompareMode::Side || mode_ == CompareMode::Split) {
      const float split = mode_ == CompareMode::Side ? 0.5f : divider_;
      label(0.0f, 0, "A: ");
      label(split * w, 1, "B: ");
      if (mode_ == CompareMode::Split)
        draw->AddLine(ImVec2(split * w, 0.0f), ImVec2(split * w, h), white, 2.0f);
    } else if (mode_ == CompareMode::Error) {
      label(0.0f, 0, "");
      draw->AddText(ImVec2(0.5f * w + 8.0f, h - 24.0f), white, "error heat map");
    }
  }
};

}  // namespace
}  // namespace prt::view

int main(int argc, char** argv) {
  try {
    prt::view::ViewerApp app;
    return prt::sample::run_sample(
        "prt-viewer",
        "prt-viewer: blobs shaded by the prtkit runtime under environment maps, in a window "
        "(prtkit " PRT_VERSION_STRING ")",
        app, argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt-viewer: %s\n", e.what());
    return 1;
  }
}
