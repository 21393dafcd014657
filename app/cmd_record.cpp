// `cablelab record SCENE --out F.mp4|F.gif [--time T] [--fps N] [--size WxH] [--set
// NAME=VALUE]...`: a headless clip of a scene, one frame per 1/fps s of simulated time, drawn by
// the sandbox's renderer offscreen (OSMesa) and written by the sandbox's own recorder
// (ui/recorder.h: the same time stamp, colours and encoders as the window's Record button). The
// extension picks the format: .mp4 is H.264 (FFmpeg), anything else an animated GIF.
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
#include "ui/clip.h"
#include "ui/offscreen_context.h"
#include "ui/recorder.h"
#include "ui/renderer.h"
#include "ui/tension_scale.h"

namespace cablelab::app {
namespace {

struct RecordOptions {
  std::string scene, out, size = "800x600", view;
  std::vector<std::string> sets;
  double time = 5, fps = 30;
};

/// The --view camera "CX,CY,MPP" (centre in m, metres per pixel), as `gui --frames N --record F`
/// reports it (record_view), or the scene's own view fitted to the image when empty.
ui::Camera recordCamera(const std::string& view, const World& world, int width, int height) {
  if (view.empty()) return ui::Camera::fit(world.scene().view, width, height);
  const std::vector<double> v = parseNumberList(view, 3, kCommandLine, "--view", "CX,CY,MPP");
  if (!(v[2] > 0)) badOption("--view", "metres per pixel must be positive" + gotValue(v[2]));
  ui::Camera camera;
  camera.center = Vec2(v[0], v[1]);
  camera.metresPerPixel = v[2];
  camera.width = width;
  camera.height = height;
  return camera;
}

int record(const RecordOptions& o) {
  const ui::ClipFormat format = ui::clipFormatFor(o.out);
  const double maxFps = ui::maxClipFps(format);
  // GIF delays are whole centiseconds, and viewers slow frames under 2 cs down to 10 cs.
  if (!std::isfinite(o.fps) || o.fps < 1 || o.fps > maxFps)
    badOption("--fps", "must be a number in [1, " + formatNumber(maxFps) + "] frames per second" +
                           gotValue(o.fps));
  requireFinite(o.time, "--time", 0, 3600);
  const auto [width, height] = parsePixelSize(o.size, kCommandLine, "--size", 16, 4096);
  if (format == ui::ClipFormat::Mp4 && !ui::mp4Available())
    badOption("--out", ui::kNoMp4 + gotValue(o.out));
  if (format == ui::ClipFormat::Mp4 && (width % 2 || height % 2))
    badOption("--size", "an MP4 needs an even width and height" + gotValue(o.size));
  requireWritable(o.out, "--out");
  std::vector<std::pair<std::string, double>> overrides;
  for (const std::string& s : o.sets) overrides.push_back(parseSetting(s));
  World world(makeScene(o.scene, overrides), o.scene);
  const ui::Camera camera = recordCamera(o.view, world, width, height);

  ui::Recorder recorder;
  try {
    recorder.start(o.out, width, height, o.fps, 0);
  } catch (const std::exception& e) {
    badOption("--out", std::string("cannot write the file: ") + e.what());
  }
  ui::OffscreenContext context(width, height);
  // The window's colour scale (from the scene's loads) and marker key, so that a clip of a
  // scene looks the same recorded here or in the window.
  ui::RenderOptions options;
  options.tensionScale = ui::loadTensionScale(world.scene());
  options.markerLegend = true;
  const double dt = world.scene().dt;
  const int substeps = world.scene().substeps;
  const long frames = std::lround(std::floor(o.time * o.fps + 1e-9)) + 1;
  Progress progress("record", frames);
  for (long k = 0; k < frames; ++k) {
    // The step nearest to the frame's time k / fps.
    const long step = std::lround(k / o.fps / dt);
    while (world.stepCount() < step) world.step(dt, substeps);
    ui::Overlay overlay;
    overlay.notes = ui::clipNotes(world, o.scene);
    recorder.add(context.render([&](ImDrawList* text) {
      ui::drawWorld(world, camera, overlay, options, text);
    }),
                 world.time());
    progress.update(k + 1);
  }
  const std::string summary = recorder.stop();
  if (recorder.failed()) throw std::runtime_error(summary);
  progress.done();
  return 0;
}

const bool recordRegistered = registerCommand(
    "record",
    "Headless clip of a scene, MP4 (H.264) or animated GIF by the extension (offscreen renderer, "
    "one frame per 1/fps s)",
    [](CLI::App& sub) {
      auto o = std::make_shared<RecordOptions>();
      sub.add_option("scene", o->scene, "built-in scene name or scene JSON file")->required();
      sub.add_option("--out", o->out, "clip to write: F.mp4 (H.264) or F.gif")->required();
      sub.add_option("--time", o->time, "seconds of simulated time to record (default 5)");
      sub.add_option(
          "--fps", o->fps,
          "frames per second of simulated time, 1..50 for GIF, 1..120 for MP4 (default 30)");
      sub.add_option("--size", o->size, "image size WxH in pixels (default 800x600)");
      sub.add_option("--view", o->view,
                     "CX,CY,MPP: the view's centre (m) and metres per pixel, as `gui --frames N "
                     "--record F` reports it (record_view; default: the scene's view fitted to "
                     "the image)");
      sub.add_option("--set", o->sets, "scene parameter NAME=VALUE (repeatable)");
      return [o]() { return record(*o); };
    });

}  // namespace
}  // namespace cablelab::app
