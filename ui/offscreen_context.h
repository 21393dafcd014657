// OffscreenContext: an OSMesa (software) OpenGL compatibility context plus a Dear ImGui
// context, for rendering frames with no display.
//
// Needs: libOSMesa and NOT libGL in the same binary (a binary linking both renders blank OSMesa
// images; see ui/README.md), Dear ImGui's OpenGL2 backend (in Debian's libimgui.a). ImGui needs
// no platform backend here: the context sets io.DisplaySize itself. The previous ImGui context
// is restored after each frame, so an offscreen frame can be made from inside another ImGui app.
#pragma once

#include <functional>
#include <memory>

#include "ui/image.h"

struct ImDrawList;

namespace cablelab::ui {

class OffscreenContext {
 public:
  /// Creates a width x height RGBA context; throws std::runtime_error if OSMesa fails.
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  int width() const;
  int height() const;

  /// One frame: makes the context current, starts an ImGui frame, calls `draw` (which may issue
  /// GL calls and add to the given ImGui draw list), renders ImGui on top and returns the pixels.
  Image render(const std::function<void(ImDrawList* text)>& draw);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cablelab::ui
