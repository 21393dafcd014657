// Panels: the sandbox's Dear ImGui windows, plain functions over a Sandbox.
//
// Needs: Dear ImGui with a frame in progress, ui/sandbox.h. Layout (pixels): a menu bar at the
// top, the Simulation panel on the left (kLeftWidth), the Inspector on the right
// (kRightWidth), a status line at the bottom; the scene shows in between. drawPanels() records
// each panel's rectangle in sandbox.panels so the mouse handler leaves those areas to ImGui.
#pragma once

#include <array>
#include <string>

#include "ui/sandbox.h"

namespace cablelab::ui {

inline constexpr float kLeftWidth = 290;
inline constexpr float kRightWidth = 320;
inline constexpr float kStatusHeight = 24;

/// UI-only state of the panels (not the simulation's).
struct PanelState {
  bool showOpen = false;             ///< the "open scene file" dialog is visible
  std::array<char, 512> openPath{};  ///< its text field
};

/// Every panel for one frame: menu bar, Simulation, Inspector, status line, help, errors.
void drawPanels(Sandbox& sandbox, PanelState& state);

}  // namespace cablelab::ui
