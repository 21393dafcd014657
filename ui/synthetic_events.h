// Synthetic SDL input for the scripted runs (--test-input, --script): the events a user's
// mouse and keyboard would send, pushed onto SDL's queue for the next poll.
#pragma once

#include <SDL.h>

#include "engine/core/math.h"

namespace cablelab::ui {

/// A mouse motion, button down or button up at `screen` (px) in window `windowId`.
void pushMouseEvent(Uint32 windowId, Uint32 type, const Vec2& screen,
                    Uint8 button = SDL_BUTTON_LEFT);
/// A key press and release.
void pushKeyPress(Uint32 windowId, SDL_Keycode key);

}  // namespace cablelab::ui
