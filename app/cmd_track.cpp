// cablelab track: figure 4-5, the hand closes into a pinch grasp and the Jacobian controller
// drives the box to a constant or ramped target.
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "app/command.h"
#include "app/options.h"
#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/core/parse.h"
#include "engine/hand/hand_tracking.h"
#include "engine/scenes/scene_registry.h"
#ifdef CABLELAB_HAVE_OFFSCREEN
#include "ui/plot.h"
#endif

namespace cablelab::app {
namespace {

const bool registered = registerCommand(
    "track", "Hand closes a pinch grasp, then the Jacobian controller tracks a target (fig. 4-5)",
    [](CLI::App& sub) {
      struct Options {
        std::string target, ramp, csv, png;
        double time = 15;
        bool pid = false;
      };
      auto o = std::make_shared<Options>();
      sub.add_option("--target", o->target, "Constant target box centre X,Y (m); default 0,0");
      sub.add_option("--ramp", o->ramp,
                     "Linear ramp from (0,0) at grasp time to X,Y over SECONDS: X,Y,SECONDS");
      sub.add_option("--time", o->time, "Simulated time (s)")->capture_default_str();
      sub.add_flag("--pid", o->pid,
                   "Add the integral term to the outer loop (removes the steady offset)");
      sub.add_option("--csv", o->csv, "Write t,target_x,target_y,x,y per step to this CSV file");
      sub.add_option("--png", o->png, "Plot target (dashed) and response (solid) to this PNG file");
      return [o] {
        TrackOptions options;
        if (!o->target.empty() && !o->ramp.empty())
          badOption("--ramp", "give either --target or --ramp, not both");
        if (!o->target.empty()) {
          const auto v = parseNumberList(o->target, 2, kCommandLine, "--target", "X,Y");
          options.target = Vec2(v[0], v[1]);
        }
        if (!o->ramp.empty()) {
          const auto v = parseNumberList(o->ramp, 3, kCommandLine, "--ramp", "X,Y,SECONDS");
          if (v[2] <= 0) badOption("--ramp", "SECONDS must be positive" + gotValue(v[2]));
          options.target = Vec2(v[0], v[1]);
          options.rampTime = v[2];
        }
        requireFinite(options.target.norm(), o->ramp.empty() ? "--target" : "--ramp", 0, 100);
        requireFinite(o->time, "--time", 0, 1e5);
        options.time = o->time;
        options.pid = o->pid;
#ifndef CABLELAB_HAVE_OFFSCREEN
        if (!o->png.empty()) badOption("--png", "this build has no offscreen renderer");
#endif
        requireOutputFile(o->png, "--png");
        std::unique_ptr<std::ofstream> csv;
        if (!o->csv.empty()) csv = std::make_unique<std::ofstream>(openOutputFile(o->csv, "--csv"));

        Progress progress("track",
                          std::lround(options.time * 60.0));  // the hand scene's dt is 1/60 s
        const TrackResult r =
            runTracking(options, HandModel{}, [&](long done, long) { progress.update(done); });
        progress.done();

        if (csv) {
          *csv << "t,target_x,target_y,x,y\n";
          char line[160];
          for (const TrackSample& s : r.samples) {
            std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g\n", s.t, s.target.x(),
                          s.target.y(), s.box.x(), s.box.y());
            *csv << line;
          }
          finishOutputFile(*csv, o->csv, "--csv");
        }
#ifdef CABLELAB_HAVE_OFFSCREEN
        if (!o->png.empty()) {
          // Figure 4-5: target (dashed) and response (solid), x and y against time.
          std::vector<double> t, tx, ty, bx, by;
          for (const TrackSample& s : r.samples) {
            t.push_back(s.t), tx.push_back(s.target.x()), ty.push_back(s.target.y());
            bx.push_back(s.box.x()), by.push_back(s.box.y());
          }
          char title[160];
          std::snprintf(title, sizeof title,
                        "Box position, %s%s: final error %.3g mm, grasp at %.2f s",
                        options.rampTime > 0 ? "ramp" : "constant target",
                        options.pid ? ", PID" : ", PD", 1e3 * r.finalError, r.graspTime);
          ui::Plot plot(title, "time (s)", "position (m)");
          const ui::Colour blue{0.12f, 0.38f, 0.75f, 1.0f}, red{0.85f, 0.25f, 0.15f, 1.0f};
          plot.series.push_back({"target x", t, tx, ui::PlotSeries::Style::Dashed, blue});
          plot.series.push_back({"box x", t, bx, ui::PlotSeries::Style::Line, blue});
          plot.series.push_back({"target y", t, ty, ui::PlotSeries::Style::Dashed, red});
          plot.series.push_back({"box y", t, by, ui::PlotSeries::Style::Line, red});
          plot.xRange = std::array<double, 2>{0.0, options.time};
          try {
            ui::writePlotPng(plot, o->png);
          } catch (const std::exception& e) {
            badOption("--png", std::string("cannot write the file: ") + e.what());
          }
        }
#endif
        printJson(nlohmann::json{
            {"final_error", r.finalError}, {"rms_error", r.rmsError}, {"grasp_time", r.graspTime}}
                      .dump());
        return 0;
      };
    });

}  // namespace
}  // namespace cablelab::app
