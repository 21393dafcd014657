#include "ui/synthetic_events.h"

#include <cmath>
#include <cstring>

namespace cablelab::ui {

void pushMouseEvent(Uint32 windowId, Uint32 type, const Vec2& screen, Uint8 button) {
  SDL_Event event{};
  event.type = type;
  const int x = static_cast<int>(std::lround(screen.x())),
            y = static_cast<int>(std::lround(screen.y()));
  if (type == SDL_MOUSEMOTION) {
    event.motion.windowID = windowId;
    event.motion.x = x;
    event.motion.y = y;
  } else {
    event.button.windowID = windowId;
    event.button.button = button;
    event.button.state = type == SDL_MOUSEBUTTONDOWN ? SDL_PRESSED : SDL_RELEASED;
    event.button.clicks = 1;
    event.button.x = x;
    event.button.y = y;
  }
  SDL_PushEvent(&event);
}

void movePointer(Uint32 windowId, const Vec2& screen) {
  SDL_WarpMouseInWindow(SDL_GetWindowFromID(windowId), static_cast<int>(std::lround(screen.x())),
                        static_cast<int>(std::lround(screen.y())));
  pushMouseEvent(windowId, SDL_MOUSEMOTION, screen);
}

void pushKeyPress(Uint32 windowId, SDL_Keycode key) {
  for (Uint32 type : {SDL_KEYDOWN, SDL_KEYUP}) pushKeyEvent(windowId, type, key);
}

void pushKeyEvent(Uint32 windowId, Uint32 type, SDL_Keycode key) {
  SDL_Event event{};
  event.type = type;
  event.key.windowID = windowId;
  event.key.state = type == SDL_KEYDOWN ? SDL_PRESSED : SDL_RELEASED;
  event.key.keysym.sym = key;
  event.key.keysym.scancode = SDL_GetScancodeFromKey(key);
  SDL_PushEvent(&event);
}

void pushText(Uint32 windowId, const char* text) {
  SDL_Event event{};
  event.type = SDL_TEXTINPUT;
  event.text.windowID = windowId;
  std::strncpy(event.text.text, text, sizeof event.text.text - 1);
  SDL_PushEvent(&event);
}

}  // namespace cablelab::ui
