// InputScript: the sandbox's self-test (`cablelab-gui --test-input`). It pushes synthetic SDL
// mouse events (SDL_PushEvent) that go through the normal event path: press on a dynamic body,
// drag it, hold, release; then click empty space. It checks that the body followed the mouse
// and that the click set the controller target; then presses h and space and checks that the
// help opened and the pause toggled. Reports JSON on stdout.
//
// Needs: an SDL video subsystem (the sandbox's Window), a Sandbox with a loaded scene.
#pragma once

#include <SDL.h>

#include <string>

#include "ui/sandbox.h"

namespace cablelab::ui {

class InputScript {
 public:
  explicit InputScript(Uint32 windowId) : windowId_(windowId) {}

  /// Called once per frame before events are polled; pushes this frame's events and checks
  /// the previous ones. Returns false when the script has finished.
  bool beforeFrame(Sandbox& sandbox, int frame);

  bool passed() const { return passed_; }
  /// One JSON object describing the checks.
  std::string report() const;

 private:
  void push(Uint32 type, const Vec2& screen, Uint8 button = SDL_BUTTON_LEFT);
  void pushKey(SDL_Keycode key);

  Uint32 windowId_;
  int body_ = -1;
  std::string bodyName_;
  Vec2 from_ = Vec2::Zero(), to_ = Vec2::Zero();    ///< screen (px)
  Vec2 start_ = Vec2::Zero(), end_ = Vec2::Zero();  ///< body position (m)
  Vec2 goal_ = Vec2::Zero();                        ///< world point under `to_` (m)
  Vec2 click_ = Vec2::Zero();                       ///< empty-space click (px)
  bool dragSeen_ = false, targetSet_ = false, passed_ = false;
  bool pausedBefore_ = false, keysOk_ = false;
  double targetError_ = -1;
  std::string failure_;
};

}  // namespace cablelab::ui
