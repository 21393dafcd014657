// Synthetic SDL input for the scripted runs (--test-input, --script): the events a user's
// mouse and keyboard would send, pushed onto SDL's queue for the next poll.
#pragma once

#include <SDL.h>

#include "engine/core/math.h"

namespace cablelab::ui {

/// A mouse motion, button down or button up at `screen` (px) in window `windowId`.
void pushMouseEvent(Uint32 windowId, Uint32 type, const Vec2& screen,
                    Uint8 button = SDL_BUTTON_LEFT);
/// Moves the pointer itself to `screen` (px) in window `windowId` and pushes the motion event:
/// Dear ImGui's SDL backend reads the pointer from SDL's mouse state, which pushed motion events
/// leave alone, so a click on a menu or a widget needs the pointer there first.
void movePointer(Uint32 windowId, const Vec2& screen);
/// A key press and release.
void pushKeyPress(Uint32 windowId, SDL_Keycode key);
/// A key press (SDL_KEYDOWN) or release (SDL_KEYUP) alone: Dear ImGui reads a key held in one
/// frame and let go in a later one (both in one frame, it sees neither).
void pushKeyEvent(Uint32 windowId, Uint32 type, SDL_Keycode key);
/// Text typed into the widget that has the keyboard (UTF-8, at most 31 bytes).
void pushText(Uint32 windowId, const char* text);

}  // namespace cablelab::ui
