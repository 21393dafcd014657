// cablelab reach: figure 4-4, the box positions the Jacobian controller reaches versus the range
// of the fingertips themselves.
#include <cstdio>
#include <nlohmann/json.hpp>
#include <thread>

#include "app/command.h"
#include "app/options.h"
#include "engine/core/error.h"
#include "engine/hand/hand_reach.h"
#ifdef CABLELAB_HAVE_OFFSCREEN
#include "ui/plot.h"
#endif

namespace cablelab::app {
namespace {

const bool registered = registerCommand(
    "reach", "Box positions the hand's controller reaches vs the fingertips' range (fig. 4-4)",
    [](CLI::App& sub) {
      struct Options {
        int grid = 50;
        std::string png;
      };
      auto o = std::make_shared<Options>();
      sub.add_option("--grid", o->grid, "N: try an N x N grid of targets")->capture_default_str();
      sub.add_option("--png", o->png, "Draw both sets to this PNG file");
      return [o] {
        if (o->grid < 1 || o->grid > 1000)
          badOption("--grid", "must be a whole number in [1, 1000]" + gotValue(o->grid));
#ifndef CABLELAB_HAVE_OFFSCREEN
        if (!o->png.empty()) badOption("--png", "this build has no offscreen renderer");
#endif
        requireOutputFile(o->png, "--png");
        ReachOptions options;
        options.grid = o->grid;
        options.threads =
            static_cast<int>(std::max(1u, std::min(2u, std::thread::hardware_concurrency())));
        Progress progress("reach", static_cast<long>(o->grid) * o->grid);
        const ReachResult r =
            runReach(options, HandModel{}, [&](long done, long) { progress.update(done); });
        progress.done();
        const double ratio = r.fingertipArea > 0 ? r.objectArea / r.fingertipArea : 0.0;
#ifdef CABLELAB_HAVE_OFFSCREEN
        if (!o->png.empty()) {
          // Figure 4-4: the controller's reach (light, drawn first) under the fingertips' (dark).
          auto coordinates = [](const std::vector<Vec2>& points, int axis) {
            std::vector<double> v;
            for (const Vec2& p : points) v.push_back(p[axis]);
            return v;
          };
          char title[160];
          std::snprintf(title, sizeof title,
                        "Reachable box positions (%d x %d targets): object / fingertip area = %.2f",
                        o->grid, o->grid, ratio);
          ui::Plot plot(title, "x (m)", "y (m)");
          plot.equalAspect = true;
          char label[96];
          std::snprintf(label, sizeof label, "box, Jacobian controller (%.2f m^2)", r.objectArea);
          plot.series.push_back({label, coordinates(r.objectPoints, 0),
                                 coordinates(r.objectPoints, 1), ui::PlotSeries::Style::Markers,
                                 ui::Colour{0.55f, 0.78f, 0.95f, 1.0f}});
          std::snprintf(label, sizeof label, "fingertips, rigid pinch (%.2f m^2)", r.fingertipArea);
          plot.series.push_back({label, coordinates(r.fingertipPoints, 0),
                                 coordinates(r.fingertipPoints, 1), ui::PlotSeries::Style::Markers,
                                 ui::Colour{0.1f, 0.2f, 0.55f, 1.0f}});
          plot.xRange = std::array<double, 2>{r.lower.x(), r.upper.x()};
          plot.yRange = std::array<double, 2>{r.lower.y(), r.upper.y()};
          try {
            ui::writePlotPng(plot, o->png, 800, 900);
          } catch (const std::exception& e) {
            badOption("--png", std::string("cannot write the file: ") + e.what());
          }
        }
#endif
        printJson(nlohmann::json{{"object_area", r.objectArea},
                                 {"fingertip_area", r.fingertipArea},
                                 {"ratio", ratio},
                                 {"points", r.points},
                                 {"object_points", r.objectPoints.size()},
                                 {"fingertip_points", r.fingertipPoints.size()},
                                 {"seconds", r.seconds}}
                      .dump());
        return 0;
      };
    });

}  // namespace
}  // namespace cablelab::app
