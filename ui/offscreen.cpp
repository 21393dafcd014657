#include "ui/offscreen.h"

#include "ui/camera.h"
#include "ui/offscreen_context.h"
#include "ui/tension_scale.h"

namespace cablelab::ui {

Image renderSnapshot(const World& world, int width, int height, const Overlay& overlay,
                     const RenderOptions& options) {
  OffscreenContext context(width, height);
  const Camera camera = Camera::fit(world.scene().view, width, height);
  // The scene's own colour scale, the sandbox's and the recordings' (ui/tension_scale.h), so that
  // a colour means the same newtons in a snapshot as in the window.
  RenderOptions o = options;
  if (o.tensionScale <= 0) o.tensionScale = loadTensionScale(world.scene());
  return context.render([&](ImDrawList* text) { drawWorld(world, camera, overlay, o, text); });
}

Image renderSnapshot(const World& world, const Camera& camera, const Overlay& overlay,
                     const RenderOptions& options) {
  OffscreenContext context(camera.width, camera.height);
  return context.render(
      [&](ImDrawList* text) { drawWorld(world, camera, overlay, options, text); });
}

void writeSnapshotPng(const World& world, const std::string& path, int width, int height,
                      const Overlay& overlay) {
  writePng(renderSnapshot(world, width, height, overlay), path);
}

}  // namespace cablelab::ui
