#include "ui/offscreen.h"

#include "ui/camera.h"
#include "ui/offscreen_context.h"
#include "ui/tension_scale.h"

namespace cablelab::ui {

namespace {

// The scene's own colour scale where none is given, the sandbox's and the recordings'
// (ui/tension_scale.h), so that a colour means the same newtons in a snapshot as in the window.
RenderOptions onTheScenesScale(const World& world, RenderOptions options) {
  if (options.tensionScale <= 0) options.tensionScale = loadTensionScale(world.scene());
  return options;
}

}  // namespace

Image renderSnapshot(const World& world, int width, int height, const Overlay& overlay,
                     const RenderOptions& options) {
  OffscreenContext context(width, height);  // checks the size before the camera clamps it
  const Camera camera = Camera::fit(world.scene().view, width, height);
  const RenderOptions o = onTheScenesScale(world, options);
  return context.render([&](ImDrawList* text) { drawWorld(world, camera, overlay, o, text); });
}

Image renderSnapshot(const World& world, const Camera& camera, const Overlay& overlay,
                     const RenderOptions& options) {
  OffscreenContext context(camera.width, camera.height);
  const RenderOptions o = onTheScenesScale(world, options);
  return context.render([&](ImDrawList* text) { drawWorld(world, camera, overlay, o, text); });
}

void writeSnapshotPng(const World& world, const std::string& path, int width, int height,
                      const Overlay& overlay) {
  writePng(renderSnapshot(world, width, height, overlay), path);
}

}  // namespace cablelab::ui
