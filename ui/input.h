// Input: SDL2 mouse and keyboard events -> sandbox actions.
//
// Needs: SDL2 events (already passed to ImGui by ui::Window) and a Sandbox. Mouse: left-drag
// a dynamic body (World::beginDrag/dragTo/endDrag), left-click empty space sets the controller
// target, right-drag pans, the wheel zooms about the cursor. Keys: space pause, s step,
// r reset, h or F1 help, +/- zoom. Events over an ImGui panel, or while ImGui is typing or
// dragging a widget, are left to ImGui.
#pragma once

#include <SDL.h>

#include "ui/sandbox.h"

namespace cablelab::ui {

void handleEvent(Sandbox& sandbox, const SDL_Event& event);

/// The shortcuts, for the help overlay: {key, action} pairs, null-terminated.
extern const char* const kShortcuts[][2];

}  // namespace cablelab::ui
