// SPDX-License-Identifier: MIT
#include "live_parameter_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <climits>
#include <string>

namespace prt::view {

bool live_parameter_panel(const std::vector<LiveParameter>& parameters, const char* id) {
  bool changed = false;
  ImGui::PushID(id);
  for (const LiveParameter& p : parameters) {
    const std::string label = p.label;
    switch (p.kind) {
      case LiveParameter::Kind::Bool: {
        bool value = p.get() != 0.0;
        if (ImGui::Checkbox(label.c_str(), &value)) {
          p.set(value ? 1.0 : 0.0);
          changed = true;
        }
        break;
      }
      case LiveParameter::Kind::Int: {
        int value = int(std::min(p.get(), double(INT_MAX)));
        const int lo = int(p.min), hi = int(std::min(p.max, double(INT_MAX)));
        if (ImGui::SliderInt(label.c_str(), &value, lo, hi)) {
          p.set(value);
          changed = true;
        }
        break;
      }
      case LiveParameter::Kind::Float: {
        float value = float(p.get());
        if (ImGui::SliderFloat(label.c_str(), &value, float(p.min), float(p.max))) {
          p.set(value);
          changed = true;
        }
        break;
      }
    }
    if (ImGui::IsItemHovered() && !p.help.empty()) ImGui::SetTooltip("%s", p.help.c_str());
  }
  ImGui::PopID();
  return changed;
}

}  // namespace prt::view
