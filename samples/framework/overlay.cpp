// SPDX-License-Identifier: MIT
#include "overlay.hpp"

#include <imgui.h>

namespace prt::sample {
namespace {

void figures(const OverlayState& s) {
  ImGui::Text("%.1f fps   shading %.3f ms (%s%s)", s.fps, s.shading_ms, backend_name(*s.backend),
              *s.backend == Backend::Gl ? ", to glFinish" : "");
  ImGui::TextDisabled("%s", s.renderer.c_str());
  for (const std::string& line : s.lines) ImGui::TextUnformatted(line.c_str());
  for (const std::string& message : s.messages)
    ImGui::TextColored(ImVec4(1.0f, 0.55f, 0.3f, 1.0f), "%s", message.c_str());
}

void backends(const OverlayState& s) {
  ImGui::TextUnformatted("backend");
  for (Backend b : {Backend::Cpu, Backend::Simd, Backend::Gl}) {
    ImGui::SameLine();
    if (!s.backend_usable[int(b)]) {
      ImGui::TextDisabled("%s", backend_name(b));
      if (!s.backend_notes[int(b)].empty() && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", s.backend_notes[int(b)].c_str());
      continue;
    }
    if (ImGui::RadioButton(backend_name(b), *s.backend == b)) *s.backend = b;
  }
}

void environment(const OverlayState& s) {
  Environments& envs = *s.environments;
  if (ImGui::BeginCombo("map", envs.current_path().c_str())) {
    for (std::size_t i = 0; i < envs.size(); ++i)
      if (ImGui::Selectable(envs.path(i).c_str(), i == envs.current_index())) envs.select(i);
    ImGui::EndCombo();
  }
  float rotation = float(envs.rotation_degrees());
  if (ImGui::SliderFloat("light turn", &rotation, -180.0f, 180.0f, "%.1f deg"))
    envs.set_rotation_degrees(rotation);
  float spin = float(envs.spin_degrees_per_second);
  if (ImGui::SliderFloat("auto-spin", &spin, -90.0f, 90.0f, "%.0f deg/s"))
    envs.spin_degrees_per_second = spin;
}

void picture(const OverlayState& s) {
  RenderSettings& settings = *s.settings;
  ImGui::SliderFloat("exposure", &settings.exposure_ev, -10.0f, 10.0f, "%+.2f EV");
  ImGui::SameLine();
  if (ImGui::Button("meter")) *s.auto_exposure = true;
  int tone = settings.tone_map == ToneMap::Filmic ? 0 : 1;
  if (ImGui::Combo("tone map", &tone, "filmic (ACES)\0linear (clamp)\0"))
    settings.tone_map = tone == 0 ? ToneMap::Filmic : ToneMap::Linear;
  ImGui::Text("camera yaw %.1f  pitch %.1f  zoom %.2f", s.camera->yaw_degrees(),
              s.camera->pitch_degrees(), s.camera->zoom());
  ImGui::SameLine();
  if (ImGui::SmallButton("frame")) s.reframe();
}

}  // namespace

void draw_overlay(const OverlayState& state, const std::function<void()>& app_panel) {
  ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(380.0f, 0.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.75f);
  if (ImGui::Begin("prtkit")) {
    figures(state);
    ImGui::Separator();
    backends(state);
    environment(state);
    picture(state);
    ImGui::Separator();
    app_panel();
    ImGui::Separator();
    ImGui::TextDisabled("drag: orbit  right-drag: light  wheel: zoom");
    ImGui::TextDisabled("F: frame  P/F12: shot  H: overlay  Esc: quit");
    ImGui::TextDisabled("drop a .prtk or an .hdr on the window");
  }
  ImGui::End();
}

}  // namespace prt::sample
