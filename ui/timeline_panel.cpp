// The Timeline row of the Simulation panel (ui/timeline_panel.h).
#include "ui/timeline_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "ui/panels.h"
#include "ui/timeline.h"

namespace cablelab::ui {

void stepBack(Sandbox& sandbox) {
  if (!sandbox.timeline) return;
  sandbox.paused = true;
  if (!sandbox.timeline->stepBack(sandbox))
    sandbox.message = sandbox.timeline->frameCount() == 0
                          ? "nothing to go back to yet: run the scene first"
                          : "this is the oldest moment kept (the last 30 s are kept)";
}

void timelinePanel(Sandbox& sandbox) {
  Timeline& t = *sandbox.timeline;
  if (t.frameCount() < 2) {
    // Wrapped: at projector scale the line is wider than the panel (shown after every edit).
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("timeline: run the scene to go back in it");
    ImGui::PopStyleColor();
    tooltip("The last 30 s of the run are kept: go back to any moment and play on from there.");
    return;
  }
  if (ImGui::ArrowButton("##back", ImGuiDir_Left)) stepBack(sandbox);
  tooltip("One step back (b); pauses.");
  ImGui::SameLine();
  const float forward = ImGui::GetFrameHeight() + ImGui::GetStyle().ItemSpacing.x;
  ImGui::SetNextItemWidth(
      std::max(fieldWidth("time", ImGui::GetFontSize() * 8) - forward, 3 * ImGui::GetFontSize()));
  const float oldest = static_cast<float>(t.frame(0).time);
  const float newest = static_cast<float>(t.frame(t.frameCount() - 1).time);
  float now = static_cast<float>(t.frame(std::max(t.current(), 0)).time);
  if (ImGui::SliderFloat("##time", &now, oldest, newest, "%.2f s"))
    t.rewindTo(sandbox, t.frameAt(now + 1e-6f));
  tooltip(
      "Drag to go back to any moment of the last 30 s (pauses). Play from there: the run goes "
      "on from that moment exactly as it did, until you change something.");
  ImGui::SameLine();
  if (ImGui::ArrowButton("##forward", ImGuiDir_Right) && t.rewound())
    t.rewindTo(sandbox, t.current() + 1);
  tooltip("One step forward along the kept run (pauses).");
  ImGui::SameLine();
  ImGui::TextUnformatted("time");
}

}  // namespace cablelab::ui
