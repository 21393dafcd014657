// `cablelab snapshot SCENE --out F.png [--size WxH] [--time T]`: an offscreen PNG of a scene.
#include <cmath>
#include <cstdio>
#include <string>

#include "app/command.h"
#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/core/parse.h"
#include "engine/dynamics/world.h"
#include "ui/offscreen.h"
#include "ui/scene_catalog.h"

namespace cablelab::app {
namespace {

const bool snapshotRegistered = registerCommand(
    "snapshot", "Offscreen PNG of a scene after T seconds (OSMesa, no display needed)",
    [](CLI::App& sub) {
      auto scene = std::make_shared<std::string>();
      auto out = std::make_shared<std::string>();
      auto size = std::make_shared<std::string>("800x600");
      auto time = std::make_shared<double>(0.0);
      sub.add_option("scene", *scene, "built-in scene name or scene JSON file")->required();
      sub.add_option("--out", *out, "PNG file to write")->required();
      sub.add_option("--size", *size, "image size WxH in pixels (default 800x600)");
      sub.add_option("--time", *time, "seconds to simulate before the snapshot (default 0)");
      return [=]() {
        const PixelSize s = parsePixelSize(*size, kCommandLine, "--size", 16, 8192);
        if (!std::isfinite(*time) || *time < 0)
          throw InputError(kCommandLine, "--time",
                           "must be a finite number >= 0" + gotValue(*time));
        requireWritable(*out, "--out");
        World world(ui::loadScene(*scene), *scene);
        const double dt = world.scene().dt;
        const long steps = std::lround(*time / dt);
        for (long i = 0; i < steps; ++i) world.step(dt, world.scene().substeps);
        ui::writeSnapshotPng(world, *out, s.width, s.height);
        return 0;
      };
    });

}  // namespace
}  // namespace cablelab::app
