// Input: SDL2 mouse and keyboard events -> sandbox actions.
//
// Needs: SDL2 events (already passed to ImGui by ui::Window) and a Sandbox. Mouse: a left
// click selects the body or cable under it; left-drag a dynamic body (a force-limited spring,
// Sandbox::beginDrag; while paused it poses the body); left-click empty space sets the
// controller target where a controller uses one (with Ctrl held, anywhere); right-drag pans,
// the wheel zooms about the cursor. A scene JSON file dropped on the window opens. Keys: see
// kShortcuts. Events over an ImGui panel, or while ImGui is typing or dragging a widget, are
// left to ImGui.
#pragma once

#include <SDL.h>

#include "ui/sandbox.h"

namespace cablelab::ui {

void handleEvent(Sandbox& sandbox, const SDL_Event& event);

/// The shortcuts, for the help overlay: {key, action} pairs, null-terminated.
extern const char* const kShortcuts[][2];

/// The speed steps of the speed control (simulated seconds per wall second), ascending.
inline constexpr double kSpeeds[] = {0.1, 0.25, 0.5, 1, 2, 4};

/// The next speed step up (+1) or down (-1) from `speed`.
double stepSpeed(double speed, int direction);

}  // namespace cablelab::ui
