// cablelab reach: figure 4-4, the box positions the Jacobian controller reaches versus the range
// of the fingertips themselves.
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "app/command.h"
#include "app/options.h"
#include "app/reach_on_dask.h"
#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/hand/hand_io.h"
#include "engine/scenes/scene_hand.h"
#include "engine/scenes/scene_registry.h"
#ifdef CABLELAB_HAVE_OFFSCREEN
#include "ui/plot.h"
#endif

namespace cablelab::app {
namespace {

#ifdef CABLELAB_HAVE_OFFSCREEN
/// Grid points as x or y coordinates.
std::vector<double> coordinates(const std::vector<Vec2>& points, int axis) {
  std::vector<double> v;
  for (const Vec2& p : points) v.push_back(p[axis]);
  return v;
}

/// Figure 4-4: the quasi-static prediction (lightest, largest markers first), the simulated set
/// on it, and the fingertips' range on top.
void writeReachPng(const std::string& path, const ReachResult& r, int grid, double ratio) {
  char title[200];
  std::snprintf(title, sizeof title,
                "Reachable box positions (%d x %d targets, %s): object / fingertip area = %.2f",
                grid, grid, r.model == ReachModel::Simulation ? "simulated" : "quasi-static",
                ratio);
  ui::Plot plot(title, "x (m)", "y (m)");
  plot.equalAspect = true;
  // One marker per grid point (disjoint sets): the plot's draw list has 16-bit indices, and
  // overlaid sets on a 50 x 50 grid exceed them.
  const bool simulated = r.model == ReachModel::Simulation;
  std::vector<Vec2> predicted, beyond, tips, missed;
  for (const ReachTarget& t : r.targets) {
    const bool reached = simulated ? t.simulated : t.quasiStatic;
    if (t.fingertip)
      (reached || !simulated ? tips : missed).push_back(t.point);
    else if (reached)
      beyond.push_back(t.point);
    else if (t.quasiStatic)
      predicted.push_back(t.point);
  }
  char label[120];
  using Style = ui::PlotSeries::Style;
  auto add = [&](const std::vector<Vec2>& points, ui::Colour colour) {
    plot.series.push_back(
        {label, coordinates(points, 0), coordinates(points, 1), Style::Markers, colour});
  };
  if (simulated) {
    std::snprintf(label, sizeof label, "quasi-static prediction only (set %.2f m^2)",
                  r.quasiStaticArea);
    add(predicted, ui::Colour{0.8f, 0.85f, 0.9f, 1.0f});
  }
  std::snprintf(label, sizeof label, "box reached beyond the fingertips (set %.2f m^2)",
                r.objectArea);
  add(beyond, ui::Colour{0.95f, 0.55f, 0.15f, 1.0f});
  std::snprintf(label, sizeof label, "fingertips, rigid pinch (%.2f m^2)%s", r.fingertipArea,
                simulated ? ", box reached" : "");
  add(tips, ui::Colour{0.1f, 0.2f, 0.55f, 1.0f});
  if (simulated) {
    std::snprintf(label, sizeof label, "fingertips, not reached in simulation (%zu)",
                  missed.size());
    add(missed, ui::Colour{0.85f, 0.1f, 0.1f, 1.0f});
  }
  plot.xRange = std::array<double, 2>{r.lower.x(), r.upper.x()};
  plot.yRange = std::array<double, 2>{r.lower.y(), r.upper.y()};
  try {
    ui::writePlotPng(plot, path, 800, 900);
  } catch (const std::exception& e) {
    badOption("--png", std::string("cannot write the file: ") + e.what());
  }
}
#endif

/// `reach --angles`: one sweep per box angle, each target asked for (x, y, angle).
int reachAtAngles(ReachOptions options, const HandModel& hand, const std::vector<double>& angles,
                  const std::string& csvPath, const std::string& png,
                  const std::string& scheduler) {
  if (!scheduler.empty()) badOption("--angles", "cannot be combined with --scheduler");
  if (!png.empty()) badOption("--angles", "cannot be combined with --png");
  std::unique_ptr<std::ofstream> csv;
  if (!csvPath.empty()) {
    csv = std::make_unique<std::ofstream>(openOutputFile(csvPath, "--csv"));
    *csv << "angle,x,y,object_reached,fingertip_reachable\n";
  }
  Progress progress("reach", static_cast<long>(angles.size()) * options.grid * options.grid);
  nlohmann::json results = nlohmann::json::array();
  long before = 0;
  for (const double angle : angles) {
    options.angle = angle;
    const ReachResult r =
        runReach(options, hand, [&](long done, long) { progress.update(before + done); });
    before += static_cast<long>(r.targets.size());
    nlohmann::json j = reachSummary(r, options);
    j["angle"] = angle;
    results.push_back(j);
    char line[160];
    for (const ReachTarget& t : r.targets)
      if (csv) {
        std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%d,%d\n", angle, t.point.x(),
                      t.point.y(), int(objectReached(r, t)), int(t.fingertip));
        *csv << line;
      }
  }
  progress.done();
  if (csv) finishOutputFile(*csv, csvPath, "--csv");
  printJson(nlohmann::json{{"angles", results}}.dump());
  return 0;
}

const bool reachRegistered = registerCommand(
    "reach", "Box positions the hand's controller reaches vs the fingertips' range (fig. 4-4)",
    [](CLI::App& sub) {
      struct Options {
        int grid = 50;
        std::string model = "simulation", csv, png, scheduler;
        bool pd = false;
        std::vector<std::string> sets;
        std::string angles;
        std::string controller = "jacobian";
        int horizon = HandMpcParams{}.horizon;
      };
      auto o = std::make_shared<Options>();
      sub.add_option("--grid", o->grid, "N: try an N x N grid of targets")->capture_default_str();
      sub.add_option("--model", o->model,
                     "simulation: every target is a full dynamic run of `track --target X,Y "
                     "--pid`; quasi-static: the statics model stands in for the hand")
          ->capture_default_str();
      sub.add_flag("--pd", o->pd, "Simulate the PD law (no integral term) instead of PID");
      sub.add_option("--controller", o->controller,
                     "Simulated runs' outer loop: jacobian or mpc (as `track --controller`)")
          ->capture_default_str();
      sub.add_option("--horizon", o->horizon, "MPC: updates planned ahead")->capture_default_str();
      sub.add_option("--csv", o->csv,
                     "Write x,y,object_reached,fingertip_reachable per target to this CSV file");
      sub.add_option("--png", o->png, "Draw the sets to this PNG file");
      sub.add_option("--scheduler", o->scheduler,
                     "Run the targets on this Dask scheduler's workers (tcp://HOST:PORT; they "
                     "need the cablelab Python module); same JSON and CSV");
      sub.add_option("--angles", o->angles,
                     "A,B,...: the reach at each of these box angles (rad; needs --set turn=1 "
                     "unless 0): JSON {\"angles\": [one result per angle]}, CSV column angle");
      sub.add_option("--set", o->sets,
                     "Hand scene parameter NAME=VALUE (repeatable; as `run hand`), e.g. turn=1");
      return [o] {
        std::vector<std::pair<std::string, double>> overrides;
        for (const std::string& s : o->sets) overrides.push_back(parseSetting(s));
        const HandModel hand = handModelWithSettings(overrides);
        const ReachOptions options =
            reachOptions(o->grid, o->model, o->pd, 0,
                         handLaw(o->controller, kCommandLine, "--controller"), o->horizon);
        if (!o->angles.empty())
          return reachAtAngles(options, hand, reachAngles(o->angles, hand), o->csv, o->png,
                               o->scheduler);
        // The Dask workers build the default hand (python/cablelab/_reach_on_dask.py).
        if (!o->scheduler.empty() && !o->sets.empty())
          badOption("--set", "cannot be combined with --scheduler");
        if (!o->scheduler.empty() && options.law != HandLaw::Jacobian)
          badOption("--controller", "mpc cannot be combined with --scheduler");
#ifndef CABLELAB_HAVE_OFFSCREEN
        if (!o->png.empty()) badOption("--png", "this build has no offscreen renderer");
#endif
        requireOutputFile(o->png, "--png");
        std::unique_ptr<std::ofstream> csv;
        if (!o->csv.empty()) csv = std::make_unique<std::ofstream>(openOutputFile(o->csv, "--csv"));
        // Local threads report targets done; on Dask the grid's rows are the tasks.
        const bool local = o->scheduler.empty();
        Progress progress("reach", local ? static_cast<long>(o->grid) * o->grid : o->grid);
        const ReachResult r =
            local ? runReach(options, hand, [&](long done, long) { progress.update(done); })
                  : runReachOnDask(o->scheduler, options, progress);
        progress.done();
        if (csv) {
          *csv << "x,y,object_reached,fingertip_reachable\n";
          char line[120];
          for (const ReachTarget& t : r.targets) {
            std::snprintf(line, sizeof line, "%.17g,%.17g,%d,%d\n", t.point.x(), t.point.y(),
                          int(objectReached(r, t)), int(t.fingertip));
            *csv << line;
          }
          finishOutputFile(*csv, o->csv, "--csv");
        }
#ifdef CABLELAB_HAVE_OFFSCREEN
        if (!o->png.empty())
          writeReachPng(o->png, r, o->grid,
                        r.fingertipArea > 0 ? r.objectArea / r.fingertipArea : 0.0);
#endif
        printJson(reachSummary(r, options).dump());
        return 0;
      };
    });

}  // namespace
}  // namespace cablelab::app
