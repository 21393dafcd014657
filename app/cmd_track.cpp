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
#include "engine/hand/hand_io.h"
#include "engine/scenes/scene_hand.h"
#include "engine/scenes/scene_registry.h"
#ifdef CABLELAB_HAVE_OFFSCREEN
#include "ui/plot.h"
#endif

namespace cablelab::app {
namespace {

#ifdef CABLELAB_HAVE_OFFSCREEN
/// Figure 4-5: target (dashed) and the box's x and y against time, for the chosen law and, as a
/// thin line, another one (PD next to PID shows the offset PD leaves and PID removes; PID next to
/// MPC how much sooner the plan arrives).
void writeTrackPng(const std::string& path, const TrackOptions& options, const TrackResult& r,
                   const TrackResult& other, const char* law, const char* otherLaw) {
  auto series = [](const TrackResult& run, auto pick) {
    std::vector<double> v;
    for (const TrackSample& s : run.samples) v.push_back(pick(s));
    return v;
  };
  const std::vector<double> t = series(r, [](const TrackSample& s) { return s.t; });
  const std::vector<double> to = series(other, [](const TrackSample& s) { return s.t; });
  char title[200];
  std::snprintf(title, sizeof title,
                "Box position, %s: %s final error %.3g mm, %s %.3g mm (start %.0f mm off)",
                options.rampTime > 0 ? "ramp" : "constant target", law, 1e3 * r.finalError,
                otherLaw, 1e3 * other.finalError, 1e3 * r.startError);
  ui::Plot plot(title, "time (s)", "position (m)");
  const ui::Colour blue{0.12f, 0.38f, 0.75f, 1.0f}, red{0.85f, 0.25f, 0.15f, 1.0f};
  const ui::Colour paleBlue{0.55f, 0.7f, 0.95f, 1.0f}, paleRed{0.95f, 0.65f, 0.55f, 1.0f};
  using Style = ui::PlotSeries::Style;
  plot.series.push_back({"target x", t,
                         series(r, [](const TrackSample& s) { return s.target.x(); }),
                         Style::Dashed, blue});
  plot.series.push_back({"target y", t,
                         series(r, [](const TrackSample& s) { return s.target.y(); }),
                         Style::Dashed, red});
  plot.series.push_back({std::string("box x, ") + otherLaw, to,
                         series(other, [](const TrackSample& s) { return s.box.x(); }), Style::Line,
                         paleBlue});
  plot.series.push_back({std::string("box y, ") + otherLaw, to,
                         series(other, [](const TrackSample& s) { return s.box.y(); }), Style::Line,
                         paleRed});
  plot.series.push_back({std::string("box x, ") + law, t,
                         series(r, [](const TrackSample& s) { return s.box.x(); }), Style::Line,
                         blue});
  plot.series.push_back({std::string("box y, ") + law, t,
                         series(r, [](const TrackSample& s) { return s.box.y(); }), Style::Line,
                         red});
  plot.xRange = std::array<double, 2>{0.0, options.time};
  try {
    ui::writePlotPng(plot, path);
  } catch (const std::exception& e) {
    badOption("--png", std::string("cannot write the file: ") + e.what());
  }
}

/// The law as the figure names it.
const char* lawLabel(const TrackOptions& o) {
  return o.law == HandLaw::Mpc ? "MPC" : o.pid ? "PID" : "PD";
}
#endif

/// `track --compare`: both laws on the same seeded targets; the figure shows the first target.
int runCompare(const std::string& png, const std::string& csv, const CompareOptions& compare,
               const HandModel& model) {
  if (!csv.empty()) badOption("--csv", "cannot be combined with --compare");
#ifndef CABLELAB_HAVE_OFFSCREEN
  if (!png.empty()) badOption("--png", "this build has no offscreen renderer");
#endif
  requireOutputFile(png, "--png");
  Progress progress("track --compare", 2L * compare.targets);
  const CompareResult r =
      compareLaws(compare, model, [&](long done, long) { progress.update(done); });
  progress.done();
#ifdef CABLELAB_HAVE_OFFSCREEN
  if (!png.empty()) {
    TrackOptions first;
    first.target = r.targets.front();
    first.time = compare.time;
    first.law = HandLaw::Mpc;
    writeTrackPng(png, first, r.mpc.front(), r.jacobian.front(), "MPC", "PID");
  }
#endif
  printJson(compareSummary(r, compare).dump());
  return 0;
}

const bool trackRegistered = registerCommand(
    "track", "Hand closes a pinch grasp, then the Jacobian controller tracks a target (fig. 4-5)",
    [](CLI::App& sub) {
      struct Options {
        std::string target, ramp, start, csv, png;
        std::vector<std::string> sets;
        double time = 15;
        bool pid = false;
        std::string controller = "jacobian";
        int horizon = HandMpcParams{}.horizon;
        bool compare = false;
        unsigned seed = 1;
      };
      auto o = std::make_shared<Options>();
      sub.add_option("--target", o->target,
                     "Constant target box centre X,Y (m), and angle THETA (rad; needs --set "
                     "turn=1): X,Y[,THETA]; default 0,0");
      sub.add_option("--ramp", o->ramp,
                     "Linear ramp from the start at control time to X,Y over SECONDS: X,Y,SECONDS");
      sub.add_option("--start", o->start,
                     "Box centre X,Y (m) the hand grasps it at; default 0,0, or 0.1,0.1 when the "
                     "target is within 5 cm of 0,0");
      sub.add_option("--time", o->time, "Simulated time (s)")->capture_default_str();
      sub.add_option("--set", o->sets,
                     "Hand scene parameter NAME=VALUE (repeatable; as `run hand`), e.g. turn=1");
      sub.add_flag("--pid", o->pid,
                   "Add the integral term to the outer loop (removes the steady offset)");
      sub.add_option("--controller", o->controller,
                     "Outer loop: jacobian (the thesis's controller) or mpc (model-predictive "
                     "control, plans --horizon updates ahead)")
          ->capture_default_str();
      sub.add_option("--horizon", o->horizon, "MPC: updates planned ahead (0.053 s each)")
          ->capture_default_str();
      sub.add_flag("--compare", o->compare,
                   "Run PID and MPC on the same 20 seeded targets and print each law's median "
                   "time to 5 mm, final error, overshoot, grasp losses and joint-limit hits");
      sub.add_option("--seed", o->seed, "--compare: seed of the targets' draw")
          ->capture_default_str();
      sub.add_option("--csv", o->csv,
                     "Write t,target_x,target_y,x,y,target_angle,angle per step to this CSV file");
      sub.add_option("--png", o->png,
                     "Plot target (dashed) and response (solid; the other law, PD or PID, pale) "
                     "to this PNG file");
      return [o] {
        std::vector<std::pair<std::string, double>> overrides;
        for (const std::string& s : o->sets) overrides.push_back(parseSetting(s));
        const HandModel model = handModelWithSettings(overrides);
        TrackRequest request;
        if (!o->target.empty())
          setTarget(request, targetNumbers(o->target, kCommandLine, "--target"), kCommandLine,
                    "--target");
        if (!o->ramp.empty()) {
          const auto v = parseNumberList(o->ramp, 3, kCommandLine, "--ramp", "X,Y,SECONDS");
          request.ramp = {v[0], v[1], v[2]};
        }
        if (!o->start.empty()) {
          const auto v = parseNumberList(o->start, 2, kCommandLine, "--start", "X,Y");
          request.start = Vec2(v[0], v[1]);
        }
        request.time = o->time;
        request.pid = o->pid;
        request.law = handLaw(o->controller, kCommandLine, "--controller");
        request.horizon = o->horizon;
        const TrackOptions options = trackOptions(request, model);
        if (o->compare) {
          CompareOptions compare;
          compare.seed = o->seed;
          compare.horizon = options.mpc.horizon;
          compare.time = options.time;
          return runCompare(o->png, o->csv, compare, model);
        }
#ifndef CABLELAB_HAVE_OFFSCREEN
        if (!o->png.empty()) badOption("--png", "this build has no offscreen renderer");
#endif
        requireOutputFile(o->png, "--png");
        std::unique_ptr<std::ofstream> csv;
        if (!o->csv.empty()) csv = std::make_unique<std::ofstream>(openOutputFile(o->csv, "--csv"));

        const long steps = std::lround(options.time * 60.0);  // the hand scene's dt is 1/60 s
        Progress progress("track", o->png.empty() ? steps : 2 * steps);
        const TrackResult r =
            runTracking(options, model, [&](long done, long) { progress.update(done); });
        // The figure's other law: PID beside MPC, else PD beside PID and PID beside PD.
        TrackOptions swapped = options;
        swapped.law = HandLaw::Jacobian;
        swapped.pid = options.law == HandLaw::Mpc || !options.pid;
        TrackResult other;
        if (!o->png.empty())
          other =
              runTracking(swapped, model, [&](long done, long) { progress.update(steps + done); });
        progress.done();

        if (csv) {
          *csv << "t,target_x,target_y,x,y,target_angle,angle\n";
          char line[240];
          for (const TrackSample& s : r.samples) {
            std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", s.t,
                          s.target.x(), s.target.y(), s.box.x(), s.box.y(), s.targetAngle, s.angle);
            *csv << line;
          }
          finishOutputFile(*csv, o->csv, "--csv");
        }
#ifdef CABLELAB_HAVE_OFFSCREEN
        if (!o->png.empty())
          writeTrackPng(o->png, options, r, other, lawLabel(options), lawLabel(swapped));
#endif
        printJson(trackSummary(r, options.law).dump());
        return 0;
      };
    });

}  // namespace
}  // namespace cablelab::app
