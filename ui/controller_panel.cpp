#include "ui/controller_panel.h"

#include <imgui.h>

namespace cablelab::ui {

// TODO(lead): the hand's Jacobian controller. Until then the panel only shows the target.
void drawControllerPanel(Sandbox& sandbox) {
  if (sandbox.target)
    ImGui::Text("target (%.3f, %.3f) m", sandbox.target->x(), sandbox.target->y());
  else
    ImGui::TextDisabled("click empty space to set a target");
  if (sandbox.target && ImGui::Button("Clear target")) sandbox.target.reset();
  ImGui::TextDisabled("no controller for this scene yet");
}

void controllerBeforeStep(Sandbox& sandbox, World& world) {}

}  // namespace cablelab::ui
