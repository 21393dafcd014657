// Small ImGui helpers shared by the panels (declared in ui/panels.h and ui/panel_sections.h).
#include <imgui.h>

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

}  // namespace cablelab::ui
