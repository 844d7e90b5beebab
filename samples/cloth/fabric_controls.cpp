// SPDX-License-Identifier: MIT
#include "fabric_controls.hpp"

#include <imgui.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>

namespace prt::cloth_app {
namespace {

constexpr float kDegrees = 57.29577951308232f;
const char* const kThreadNames[2] = {"warp", "weft"};

}  // namespace

void FabricOverrides::add_options(CLI::App& app) {
  const std::string group = "Fabric (the fabric's defaults unless given)";
  for (int j = 0; j < 2; ++j) {
    Thread& t = threads_[j];
    const std::string p = std::string("--") + kThreadNames[j] + "-";
    const std::string which = j == 0 ? "thread 1 (the warp)" : "thread 2 (the weft)";
    app.add_option(p + "eta", t.eta, "Index of refraction of " + which + ", 1..4")
        ->check(CLI::Range(1.0f, 4.0f))
        ->group(group);
    app.add_option(p + "albedo", t.albedo_text, "Volume albedo of " + which + ": R,G,B in 0..1")
        ->group(group);
    app.add_option(p + "kd", t.kd,
                   "Isotropic fraction of the volume scattering of " + which + ", 0..1")
        ->check(CLI::Range(0.0f, 1.0f))
        ->group(group);
    app.add_option(p + "gamma-s", t.gamma_s_degrees,
                   "Width of the surface lobe of " + which + ", degrees (0, 180]")
        ->check(CLI::Range(1e-3f, 180.0f))
        ->group(group);
    app.add_option(p + "gamma-v", t.gamma_v_degrees,
                   "Width of the volume lobe of " + which + ", degrees (0, 180]")
        ->check(CLI::Range(1e-3f, 180.0f))
        ->group(group);
    app.add_option(p + "coverage", t.coverage,
                   "Area fraction of " + which + ", 0..1 (the two add up to at most 1)")
        ->check(CLI::Range(0.0f, 1.0f))
        ->group(group);
  }
}

void FabricOverrides::check() {
  for (int j = 0; j < 2; ++j) {
    Thread& t = threads_[j];
    if (t.albedo_text.empty()) continue;
    float rgb[3];
    char tail = 0;
    if (std::sscanf(t.albedo_text.c_str(), "%f,%f,%f%c", &rgb[0], &rgb[1], &rgb[2], &tail) != 3 ||
        !std::all_of(rgb, rgb + 3, [](float v) { return v >= 0.0f && v <= 1.0f; }))
      throw CLI::ValidationError(std::string("--") + kThreadNames[j] + "-albedo",
                                 "expected R,G,B each in 0..1, got '" + t.albedo_text + "'");
    for (int c = 0; c < 3; ++c) t.albedo[c] = rgb[c];
  }
}

bool FabricOverrides::empty() const {
  for (const Thread& t : threads_)
    if (t.eta || t.kd || t.gamma_s_degrees || t.gamma_v_degrees || t.coverage || t.albedo[0])
      return false;
  return true;
}

prt_cloth_params FabricOverrides::apply(const prt_cloth_params& defaults,
                                        const std::string& fabric) const {
  prt_cloth_params p = defaults;
  for (int j = 0; j < 2; ++j) {
    const Thread& t = threads_[j];
    prt_cloth_thread& out = p.threads[j];
    if (t.eta) out.eta = *t.eta;
    if (t.kd) out.kd = *t.kd;
    if (t.gamma_s_degrees) out.gamma_s = *t.gamma_s_degrees / kDegrees;
    if (t.gamma_v_degrees) out.gamma_v = *t.gamma_v_degrees / kDegrees;
    if (t.coverage) out.coverage = *t.coverage;
    for (int c = 0; c < 3; ++c)
      if (t.albedo[c]) out.albedo[c] = *t.albedo[c];
  }
  if (prt_cloth_params_validate(&p) != PRT_OK) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "fabric %s: coverages %.3g (warp) and %.3g (weft) add up to more than 1",
                  fabric.c_str(), p.threads[0].coverage, p.threads[1].coverage);
    throw CLI::ValidationError("--warp-coverage/--weft-coverage", text);
  }
  return p;
}

bool fabric_sliders(prt_cloth_params& params) {
  bool changed = false;
  for (int j = 0; j < 2; ++j) {
    prt_cloth_thread& t = params.threads[j];
    ImGui::PushID(j);
    ImGui::TextUnformatted(j == 0 ? "thread 1: warp" : "thread 2: weft");
    changed |= ImGui::SliderFloat("eta", &t.eta, 1.0f, 4.0f, "%.3f");
    changed |= ImGui::SliderFloat3("albedo", t.albedo, 0.0f, 1.0f, "%.3f");
    changed |= ImGui::SliderFloat("k_d", &t.kd, 0.0f, 1.0f, "%.3f");
    float gamma_s = t.gamma_s * kDegrees, gamma_v = t.gamma_v * kDegrees;
    if (ImGui::SliderFloat("gamma_s (deg)", &gamma_s, 0.1f, 90.0f, "%.2f",
                           ImGuiSliderFlags_Logarithmic)) {
      t.gamma_s = std::max(gamma_s, 0.1f) / kDegrees;
      changed = true;
    }
    if (ImGui::SliderFloat("gamma_v (deg)", &gamma_v, 0.1f, 90.0f, "%.2f",
                           ImGuiSliderFlags_Logarithmic)) {
      t.gamma_v = std::max(gamma_v, 0.1f) / kDegrees;
      changed = true;
    }
    if (ImGui::SliderFloat("coverage", &t.coverage, 0.0f, 1.0f, "%.3f")) {
      float& other = params.threads[1 - j].coverage;
      other = std::min(other, 1.0f - t.coverage);
      changed = true;
    }
    ImGui::PopID();
  }
  return changed;
}

std::string describe_thread(const prt_cloth_thread& t) {
  char text[200];
  std::snprintf(
      text, sizeof text,
      "eta %.3g, albedo (%.3g, %.3g, %.3g), k_d %.3g, gamma_s %.3g deg, gamma_v %.3g deg, "
      "coverage %.3g",
      t.eta, t.albedo[0], t.albedo[1], t.albedo[2], t.kd, t.gamma_s * kDegrees,
      t.gamma_v * kDegrees, t.coverage);
  return text;
}

}  // namespace prt::cloth_app
