#include "ui/offscreen.h"

#include "ui/camera.h"
#include "ui/offscreen_context.h"

namespace cablelab::ui {

Image renderSnapshot(const World& world, int width, int height, const Overlay& overlay,
                     const RenderOptions& options) {
  OffscreenContext context(width, height);
  const Camera camera = Camera::fit(world.scene().view, width, height);
  return context.render(
      [&](ImDrawList* text) { drawWorld(world, camera, overlay, options, text); });
}

void writeSnapshotPng(const World& world, const std::string& path, int width, int height,
                      const Overlay& overlay) {
  writePng(renderSnapshot(world, width, height, overlay), path);
}

}  // namespace cablelab::ui
