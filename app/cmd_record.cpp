// `cablelab record SCENE --out F.gif [--time T] [--fps N] [--size WxH] [--set NAME=VALUE]...`:
// a headless animated GIF of a scene, one frame per 1/fps s of simulated time, drawn by the
// sandbox's renderer offscreen (OSMesa) and encoded by giflib (ui/gif.h).
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/command.h"
#include "app/options.h"
#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/core/parse.h"
#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"
#include "ui/camera.h"
#include "ui/gif.h"
#include "ui/offscreen_context.h"
#include "ui/renderer.h"
#include "ui/tension_scale.h"

namespace cablelab::app {
namespace {

struct RecordOptions {
  std::string scene, out, size = "800x600";
  std::vector<std::string> sets;
  double time = 5, fps = 30;
};

std::string timeNote(double t) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "t = %.2f s", t);
  return buffer;
}

int record(const RecordOptions& o) {
  // GIF delays are whole centiseconds, and viewers slow frames under 2 cs down to 10 cs.
  if (!std::isfinite(o.fps) || o.fps < 1 || o.fps > 50)
    badOption("--fps", "must be a number in [1, 50] frames per second" + gotValue(o.fps));
  requireFinite(o.time, "--time", 0, 3600);
  const auto [width, height] = parsePixelSize(o.size, kCommandLine, "--size", 16, 4096);
  requireWritable(o.out, "--out");
  std::vector<std::pair<std::string, double>> overrides;
  for (const std::string& s : o.sets) overrides.push_back(parseSetting(s));
  World world(makeScene(o.scene, overrides), o.scene);

  std::unique_ptr<ui::GifWriter> gif;
  try {
    gif = std::make_unique<ui::GifWriter>(o.out, width, height, 1 / o.fps);
  } catch (const std::exception& e) {
    badOption("--out", std::string("cannot write the file: ") + e.what());
  }
  ui::OffscreenContext context(width, height);
  const ui::Camera camera = ui::Camera::fit(world.scene().view, width, height);
  ui::RenderOptions options;
  options.tensionScale = ui::expectedTensionScale(world.scene());
  const double dt = world.scene().dt;
  const int substeps = world.scene().substeps;
  const long frames = std::lround(std::floor(o.time * o.fps + 1e-9)) + 1;
  Progress progress("record", frames);
  for (long k = 0; k < frames; ++k) {
    // The step nearest to the frame's time k / fps.
    const long step = std::lround(k / o.fps / dt);
    while (world.stepCount() < step) world.step(dt, substeps);
    ui::Overlay overlay;
    overlay.notes.push_back(world.scene().name.empty() ? o.scene : world.scene().name);
    overlay.notes.push_back(timeNote(world.time()));
    gif->add(context.render(
        [&](ImDrawList* text) { ui::drawWorld(world, camera, overlay, options, text); }));
    progress.update(k + 1);
  }
  gif->close();
  progress.done();
  return 0;
}

const bool recordRegistered = registerCommand(
    "record", "Headless animated GIF of a scene (offscreen renderer, one frame per 1/fps s)",
    [](CLI::App& sub) {
      auto o = std::make_shared<RecordOptions>();
      sub.add_option("scene", o->scene, "built-in scene name or scene JSON file")->required();
      sub.add_option("--out", o->out, "GIF file to write")->required();
      sub.add_option("--time", o->time, "seconds of simulated time to record (default 5)");
      sub.add_option("--fps", o->fps, "frames per second of simulated time, 1..50 (default 30)");
      sub.add_option("--size", o->size, "image size WxH in pixels (default 800x600)");
      sub.add_option("--set", o->sets, "scene parameter NAME=VALUE (repeatable)");
      return [o]() { return record(*o); };
    });

}  // namespace
}  // namespace cablelab::app
