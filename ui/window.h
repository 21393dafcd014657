// Window: the SDL2 + OpenGL platform for the sandbox, with Dear ImGui's SDL2 and OpenGL2
// backends (both inside Debian's libimgui.a; header imgui_impl_sdl.h in ImGui 1.86).
//
// Needs: SDL2 and libGL, and NOT libOSMesa in the same binary (ui/README.md). The context is
// OpenGL 2.1 (compatibility), which the legacy renderer and the ImGui OpenGL2 backend need.
// Frame protocol: pollEvents() -> beginFrame() -> draw (GL + ImGui) -> endFrame().
#pragma once

#include <SDL.h>

#include <functional>
#include <string>

#include "ui/image.h"

namespace cablelab::ui {

class Window {
 public:
  /// Opens a width x height window with a GL context and an ImGui context; width or height 0:
  /// fitted to the display (90% of its usable area, at least 640x480 where the display allows).
  /// Throws std::runtime_error with SDL's message on failure. `vsync` false: frames uncapped.
  Window(const std::string& title, int width, int height, bool vsync);

  /// Rebuilds the font (13 px times `scale`) and the style sizes; call between frames.
  void setUiScale(float scale);
  /// A UI scale suited to the display: 1 up to 1080 rows, more on larger displays.
  float suggestedUiScale() const;
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  /// Feeds every pending event to ImGui, then to `handler`. Returns false once the user
  /// closed the window.
  bool pollEvents(const std::function<void(const SDL_Event&)>& handler);
  /// Starts an ImGui frame and sets the GL viewport to the whole window.
  void beginFrame();
  /// Renders ImGui over what was drawn; when `capture` is not null, reads the finished frame
  /// into it (top row first) before presenting it.
  void endFrame(Image* capture = nullptr);

  int width() const { return width_; }
  /// SDL's id of this window (for synthetic events).
  Uint32 id() const { return SDL_GetWindowID(window_); }
  int height() const { return height_; }

 private:
  SDL_Window* window_ = nullptr;
  SDL_GLContext gl_ = nullptr;
  int width_ = 0, height_ = 0;
  bool closed_ = false;
  float uiScale_ = 1;
};

}  // namespace cablelab::ui
