// Small ImGui helpers shared by the panels (declared in ui/panels.h and ui/panel_sections.h).
#include <imgui.h>

#include <algorithm>

#include "ui/panel_sections.h"
#include "ui/panels.h"

namespace cablelab::ui {

void section(const char* title) {
  ImGui::Spacing();
  ImGui::Separator();
  ImGui::TextDisabled("%s", title);
}

void tooltip(const char* text) {
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28);
    ImGui::TextUnformatted(text);
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
}

float fieldWidth(const char* label, float preferred) {
  const float room = ImGui::GetContentRegionAvail().x -
                     ImGui::CalcTextSize(label, nullptr, true).x -
                     ImGui::GetStyle().ItemInnerSpacing.x;
  return std::max(std::min(preferred, room), 3 * ImGui::GetFontSize());
}

float buttonWidth(const char* label) {
  return ImGui::CalcTextSize(label, nullptr, true).x + 2 * ImGui::GetStyle().FramePadding.x;
}

float checkboxWidth(const char* label) {
  return ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x +
         ImGui::CalcTextSize(label, nullptr, true).x;
}

void sameLineIfRoom(float width) {
  const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
  if (ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + width <= right)
    ImGui::SameLine();
}

PanelRect lastItemRect() {
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  return {lo.x, lo.y, hi.x - lo.x, hi.y - lo.y};
}

}  // namespace cablelab::ui
