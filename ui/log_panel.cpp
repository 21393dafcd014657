// The Inspector's Log section: what the engine said, in its own words, newest last
// (ui/event_log.h); the view itself shows only the plain-words banner (ui/plain_words.h).
#include <imgui.h>

#include <cstdio>

#include "ui/panel_sections.h"

namespace cablelab::ui {

void logSection(Sandbox& sandbox) {
  const auto& entries = sandbox.log.entries();
  char title[64];
  std::snprintf(title, sizeof title, "Log (%zu)###log", entries.size());
  if (!ImGui::CollapsingHeader(title)) {
    tooltip(
        "What the simulation engine reported, in its own terms: for the curious and for "
        "bug reports. Nothing here needs an action.");
    return;
  }
  if (entries.empty()) {
    ImGui::TextDisabled("nothing reported");
    return;
  }
  if (ImGui::SmallButton("Clear")) sandbox.log.clear();
  tooltip("Empty the log.");
  ImGui::PushTextWrapPos(0);
  for (const LogEntry& e : entries)
    ImGui::TextDisabled("%s, t %.3f s: %s", e.scene.c_str(), e.time, e.text.c_str());
  ImGui::PopTextWrapPos();
}

}  // namespace cablelab::ui
