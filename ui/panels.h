// Panels: the sandbox's Dear ImGui windows, plain functions over a Sandbox.
//
// Needs: Dear ImGui with a frame in progress, ui/sandbox.h. Layout (pixels): a menu bar at the
// top, the Simulation panel on the left, the Inspector on the right, a status line at the
// bottom; the scene shows in between. Both side panels collapse (click the title bar's arrow)
// and resize (drag their inner edge); their default widths are kLeftWidth and kRightWidth
// times the UI scale, narrower on a small window, where the Inspector starts collapsed so the
// world view keeps most of the width. drawPanels() records each panel's rectangle in
// sandbox.panels so the mouse handler leaves those areas to ImGui.
#pragma once

#include <array>
#include <string>

#include "ui/sandbox.h"

namespace cablelab::ui {

inline constexpr float kLeftWidth = 290;
inline constexpr float kRightWidth = 320;
inline constexpr float kStatusHeight = 24;
/// Below this window width (px, at UI scale 1) the Inspector starts collapsed.
inline constexpr float kNarrowWindow = 1100;

/// UI-only state of the panels (not the simulation's).
struct PanelState {
  bool showOpen = false;             ///< the "open scene file" dialog is visible
  std::array<char, 512> openPath{};  ///< its text field
  std::array<char, 512> savePath{};  ///< the "save scene" field
  bool showSave = false;
  float layoutScale = 0;  ///< the UI scale the widths below were laid out for (0: not yet)
  float leftWidth = kLeftWidth, rightWidth = kRightWidth;
  bool collapseRight = false;  ///< collapse the Inspector on the next frame
  bool collapseLeft = false;
};

/// Every panel for one frame: menu bar, Simulation, Inspector, status line, help, errors.
void drawPanels(Sandbox& sandbox, PanelState& state);

/// Shows `text` as the tooltip of the last widget when the mouse rests on it.
void tooltip(const char* text);

// Rows that fit a narrow panel (640x480 leaves the Simulation panel about 200 px): widgets
// shrink to leave room for their label, and a widget that would not fit goes to the next row.

/// Width for a widget labelled `label`: `preferred` (px), less when the row has no room for it
/// and the label, never under three characters.
float fieldWidth(const char* label, float preferred);
/// Width of a button (SmallButton too) showing `label`.
float buttonWidth(const char* label);
/// Width of a checkbox with `label`.
float checkboxWidth(const char* label);
/// ImGui::SameLine() when an item `width` px wide still fits on the current row.
void sameLineIfRoom(float width);
/// The screen rectangle of the last widget drawn (px): where the scripted checks find it.
PanelRect lastItemRect();

}  // namespace cablelab::ui
