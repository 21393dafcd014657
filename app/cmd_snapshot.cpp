// `cablelab snapshot SCENE --out F.png [--size WxH] [--time T] [--set NAME=VALUE]...
//  [--compare REF.png [--tolerance S]]`: an offscreen PNG of a scene, optionally checked against
// a reference image (exit 0: match, 1: differ and F.diff.png shows where, 2: bad input).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/command.h"
#include "app/options.h"
#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/core/parse.h"
#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"
#include "ui/image.h"
#include "ui/offscreen.h"
#include "ui/scene_catalog.h"

namespace cablelab::app {
namespace {

/// A pixel differs from the reference when a colour channel differs by more than this many
/// levels of 255: well above rounding noise, well below any change a user would see.
constexpr int kColourThreshold = 8;
/// Default --tolerance: the share of pixels allowed to differ (0.1%).
constexpr double kDefaultTolerance = 0.001;

/// F.png -> F.diff.png (any other name gets .diff.png appended).
std::string diffPathFor(const std::string& out) {
  std::filesystem::path p(out);
  if (p.extension() == ".png") p.replace_extension();
  return p.string() + ".diff.png";
}

struct SnapshotOptions {
  std::string scene, out, size, compare;
  std::vector<std::string> sets;
  double time = 0, tolerance = kDefaultTolerance;
  bool toleranceGiven = false;
};

/// Writes the snapshot and, with --compare, checks it; returns the exit code.
int snapshot(const SnapshotOptions& o) {
  if (!std::isfinite(o.time) || o.time < 0)
    badOption("--time", "must be a finite number >= 0" + gotValue(o.time));
  if (o.toleranceGiven && o.compare.empty())
    badOption("--tolerance", "needs --compare REF.png" + gotValue(o.tolerance));
  requireFinite(o.tolerance, "--tolerance", 0, 1);
  requireWritable(o.out, "--out");
  // The reference first: a bad one fails before the simulation, and sets the default size.
  ui::Image reference;
  if (!o.compare.empty()) {
    reference = ui::readPng(o.compare);
    requireWritable(diffPathFor(o.out), "--out");
  }
  PixelSize size{800, 600};
  if (!o.size.empty())
    size = parsePixelSize(o.size, kCommandLine, "--size", 16, 8192);
  else if (!o.compare.empty())
    size = {reference.width, reference.height};
  if (!o.compare.empty() && (size.width != reference.width || size.height != reference.height))
    badOption("--size", "must be the reference image's size " + std::to_string(reference.width) +
                            "x" + std::to_string(reference.height) + " (" + o.compare + ")" +
                            gotValue(o.size));

  std::vector<std::pair<std::string, double>> overrides;
  for (const std::string& s : o.sets) overrides.push_back(parseSetting(s));
  World world(ui::loadScene(o.scene, overrides), o.scene);
  const double dt = world.scene().dt;
  const long steps = std::lround(o.time / dt);
  for (long i = 0; i < steps; ++i) world.step(dt, world.scene().substeps);
  const ui::Image image = ui::renderSnapshot(world, size.width, size.height);
  ui::writePng(image, o.out);
  if (o.compare.empty()) return 0;

  const ui::ImageComparison c = ui::compareImages(reference, image, kColourThreshold);
  const bool match = c.share() <= o.tolerance;
  const std::string diff = diffPathFor(o.out);
  std::error_code ignored;
  if (match)
    std::filesystem::remove(diff, ignored);  // an old diff would mislead
  else
    ui::writePng(c.diff, diff);
  nlohmann::json report = {{"out", o.out},
                           {"reference", o.compare},
                           {"match", match},
                           {"differing_pixels", c.differing},
                           {"pixels", c.pixels},
                           {"share", c.share()},
                           {"tolerance", o.tolerance},
                           {"colour_threshold", kColourThreshold},
                           {"diff", match ? nlohmann::json(nullptr) : nlohmann::json(diff)}};
  printJson(report.dump());
  if (match) return 0;
  char share[64];
  std::snprintf(share, sizeof share, "%.3g%% of its pixels (tolerance %.3g%%)", 100 * c.share(),
                100 * o.tolerance);
  std::cerr << o.out << ": differs from " << o.compare << " in " << share << "; where: " << diff
            << "\n";
  return 1;
}

const bool snapshotRegistered = registerCommand(
    "snapshot", "Offscreen PNG of a scene after T seconds (OSMesa, no display needed)",
    [](CLI::App& sub) {
      auto o = std::make_shared<SnapshotOptions>();
      sub.add_option("scene", o->scene, "built-in scene name or scene JSON file")->required();
      sub.add_option("--out", o->out, "PNG file to write")->required()->type_name("F.png");
      sub.add_option("--size", o->size,
                     "image size WxH in pixels (default 800x600, or the --compare image's)")
          ->type_name("WxH");
      sub.add_option("--time", o->time, "seconds to simulate before the snapshot (default 0)");
      sub.add_option("--set", o->sets, "scene parameter NAME=VALUE (repeatable; as `run`)")
          ->type_name("NAME=VALUE");
      sub.add_option("--compare", o->compare,
                     "reference PNG: exit 0 if the snapshot matches it within --tolerance, 1 if "
                     "not (and write F.diff.png: the reference in grey, differing pixels red)")
          ->type_name("REF.png");
      CLI::Option* tolerance = sub.add_option(
          "--tolerance", o->tolerance,
          "share of pixels (0..1) allowed to differ from --compare; a pixel differs when its "
          "red, green or blue differs by more than " +
              std::to_string(kColourThreshold) + " levels of 255 (default 0.001 = 0.1%)");
      return [o, tolerance]() {
        o->toleranceGiven = tolerance->count() > 0;
        return snapshot(*o);
      };
    });

}  // namespace
}  // namespace cablelab::app
