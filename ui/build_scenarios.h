// Build scenarios: `cablelab-gui --script build-NAME --script-out F.json` starts a new scene and
// builds one element of it with the Build panel's tools, by synthetic mouse clicks and keys in the
// window (the normal event path, ui/input.cpp), then saves the scene to F.json. One scenario per
// element the Build panel makes; tests/ui/gui_test.cpp compares each saved file with a scene
// written by hand and runs both.
//
// Tools and the panels' fields (size, mass, body type, the Inspector's joint and cable fields) are
// set the way the panels set them: ImGui 1.86 reads the pointer from SDL_GetMouseState, which
// pushed events do not move, so the script cannot click the panels' widgets.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "ui/authoring.h"

namespace cablelab::ui {

struct BuildStep {
  enum class Kind { Tool, Click, ShiftClick, AltClick, RightClick, Undo, Redo, DeleteKey, Setting };
  Kind kind = Kind::Click;
  Authoring::Tool tool = Authoring::Tool::None;  ///< Tool
  Vec2 at = Vec2::Zero();                        ///< clicks: world point (m)
  std::function<void(Sandbox&)> set;             ///< Setting: what the panel field does
};

struct BuildScenario {
  std::string name;  ///< "build-..."
  std::vector<BuildStep> steps;
};

/// Steps the window plays each built scene for after saving it (the poses the report gives).
inline constexpr int kBuildPlaySteps = 30;

/// Every build scenario.
const std::vector<BuildScenario>& buildScenarios();
/// The build scenario called `name`; null if none.
const BuildScenario* findBuildScenario(const std::string& name);

/// Plays `step` in window `windowId` as the user does: clicks as synthetic SDL events at the
/// step's point in the view, tools and fields as the panels and the Build menu set them. A
/// modifier key (Shift, Alt, Ctrl) stays held in SDL's modifier state until the caller clears it
/// (the next frame: the events are handled in this one).
void playBuildStep(Sandbox& sandbox, std::uint32_t windowId, const BuildStep& step);

}  // namespace cablelab::ui
