// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/scene_panel.h"

#include <imgui.h>

#include <string>

namespace voxlink::viewer {

bool drawScenePanel(SceneSession& s, std::optional<size_t>& selected, std::string& message) {
  bool changed = false;
  AnimationClock& clock = s.clock();
  bool playing = clock.playing();
  if (ImGui::Checkbox("play", &playing)) clock.setPlaying(playing);
  ImGui::SameLine();
  float time = float(clock.time());
  ImGui::SetNextItemWidth(260);
  if (ImGui::SliderFloat("time (s)", &time, 0.0f, float(clock.span()), "%.2f")) {
    s.setTime(time);
    changed = true;
  }
  ImGui::TextDisabled("Ctrl + left drag: move the object under the cursor, else the selected one");
  for (size_t i = 0; i < s.movingCount(); ++i) {
    ImGui::PushID(int(i));
    if (ImGui::Selectable(s.movingName(i).c_str(), selected == i, 0, ImVec2(220, 0)))
      selected = selected == i ? std::nullopt : std::optional(i);  // a second click deselects
    ImGui::SameLine();
    if (s.held(i)) {
      ImGui::Text("held where dragged");
      ImGui::SameLine();
      if (ImGui::SmallButton("back to its animation")) {
        s.release(i);
        changed = true;
      }
    } else {
      ImGui::TextDisabled("animated");
    }
    ImGui::PopID();
  }
  if (!s.staticObjects().empty())
    ImGui::TextDisabled("Static objects (Ctrl + left drag on one, or \"move it\", makes it move):");
  for (const StaticObject& m : s.staticObjects()) {
    ImGui::PushID(int(1000000 + m.object));
    ImGui::Text("%s", s.objectName(m.object).c_str());
    ImGui::SameLine();
    if (const auto p = s.promoting(); p && p->first == m.object) {
      ImGui::ProgressBar(float(p->second), ImVec2(160, 0), "rebuilding the static part");
    } else if (ImGui::SmallButton("move it")) {
      if (Status st = s.promote(m.object); !st) message = st.message();
    }
    ImGui::PopID();
  }
  const auto& clamp = s.lastClamp();
  if (clamp[0] || clamp[1] || clamp[2]) {
    std::string axes;
    for (int a = 0; a < 3; ++a)
      if (clamp[size_t(a)]) axes += std::string(axes.empty() ? "" : ", ") + "xyz"[a];
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.55f, 0.3f, 1.0f));
    ImGui::Text("drag clamped at the grid's face on %s", axes.c_str());
    ImGui::PopStyleColor();
  }
  return changed;
}

}  // namespace voxlink::viewer
