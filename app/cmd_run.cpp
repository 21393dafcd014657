// cablelab run SCENE: headless simulation with CSV output (and a PNG of the final state).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/command.h"
#include "app/options.h"
#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"
#ifdef CABLELAB_HAVE_OFFSCREEN
#include "ui/offscreen.h"
#endif

namespace cablelab::app {
namespace {

// Writes t, then NAME.x .y .theta .vx .vy .omega per body, then NAME.length .tension .wraps per
// cable (and NAME.span<k>.tension where a wheel splits it), then NAME.value .rate .force per named
// joint (m or rad, m/s or rad/s, the servo's N or N m over the step).
class CsvWriter {
 public:
  CsvWriter(const std::string& path, const World& world)
      : path_(path), out_(openOutputFile(path, "--csv")) {
    out_ << "t";
    for (const BodyDef& b : world.scene().bodies)
      for (const char* c : {".x", ".y", ".theta", ".vx", ".vy", ".omega"})
        out_ << "," << b.name << c;
    for (int i = 0; i < world.cableCount(); ++i)
      for (const char* c : {".length", ".tension", ".wraps"})
        out_ << "," << world.cable(i).name() << c;
    // Cables split by wheels that grip them: one tension per span, NAME.span<k>.tension.
    for (int i = 0; i < world.cableCount(); ++i) {
      int spans = 1;
      for (const PulleyDef& p : world.cable(i).def().pulleys) spans += gripsCable(p);
      spans_.push_back(spans > 1 ? spans : 0);
      for (int k = 0; k < spans_.back(); ++k)
        out_ << "," << world.cable(i).name() << ".span" << k << ".tension";
    }
    for (int j = 0; j < world.jointCount(); ++j) {
      const std::string& name = world.scene().joints[j].name;
      if (name.empty()) continue;
      joints_.push_back(j);
      for (const char* c : {".value", ".rate", ".force"}) out_ << "," << name << c;
    }
    out_ << "\n";
  }
  void row(const World& world) {
    char buf[32];
    auto num = [&](double v) {
      std::snprintf(buf, sizeof buf, "%.17g", v);
      out_ << "," << buf;
    };
    std::snprintf(buf, sizeof buf, "%.17g", world.time());
    out_ << buf;
    for (int i = 0; i < world.bodyCount(); ++i) {
      const BodyState& b = world.body(i);
      num(b.position.x()), num(b.position.y()), num(b.angle);
      num(b.velocity.x()), num(b.velocity.y()), num(b.angularVelocity);
    }
    for (int i = 0; i < world.cableCount(); ++i) {
      const Cable& c = world.cable(i);
      num(c.length()), num(c.tension());
      out_ << "," << c.wraps();
    }
    for (int i = 0; i < world.cableCount(); ++i)
      for (int k = 0; k < spans_[i]; ++k) {
        const Cable& c = world.cable(i);
        num(k < c.spanCount() ? c.spanTension(k) : c.tension());
      }
    for (const int j : joints_) {
      const JointState q = world.joint(j);
      num(q.value), num(q.speed), num(q.force);
    }
    out_ << "\n";
  }
  void finish() { finishOutputFile(out_, path_, "--csv"); }

 private:
  std::string path_;
  std::ofstream out_;
  std::vector<int> spans_;   ///< span tension columns per cable
  std::vector<int> joints_;  ///< the named joints, in column order
};

const bool runRegistered = registerCommand(
    "run", "Run a scene headless (CSV per step, PNG of the end state)", [](CLI::App& sub) {
      struct Options {
        std::string scene, csv, png;
        std::vector<std::string> sets;
        double time = 5.0, dt = 0;
        int substeps = 0;
      };
      auto o = std::make_shared<Options>();
      sub.add_option("scene", o->scene,
                     "Built-in scene name (see `cablelab scenes`) or a scene JSON file")
          ->required();
      sub.add_option("--set", o->sets, "Scene parameter NAME=VALUE (repeatable)");
      sub.add_option("--time", o->time, "Simulated time (s)")->capture_default_str();
      CLI::Option* dtOption = sub.add_option("--dt", o->dt, "Time step (s); default: the scene's");
      CLI::Option* substepsOption =
          sub.add_option("--substeps", o->substeps, "Sub-steps per step; default: the scene's");
      sub.add_option("--csv", o->csv, "Write one row per step to this CSV file");
      sub.add_option("--png", o->png, "Write a snapshot of the final state to this PNG file");
      return [o, dtOption, substepsOption] {
        if (dtOption->count() && !(o->dt > 0 && o->dt <= 1))
          badOption("--dt", "must be in (0, 1] s" + gotValue(o->dt));
        if (substepsOption->count() && (o->substeps < 1 || o->substeps > 1000))
          badOption("--substeps", "must be 1..1000" + gotValue(o->substeps));
        std::vector<std::pair<std::string, double>> overrides;
        for (const std::string& s : o->sets) overrides.push_back(parseSetting(s));
        World world(makeScene(o->scene, overrides), o->scene);
        const double dt = o->dt > 0 ? o->dt : world.scene().dt;
        const int substeps = o->substeps > 0 ? o->substeps : world.scene().substeps;
        requireFinite(o->time, "--time", 0, 1e7);
        const long steps = std::lround(o->time / dt);
        if (steps > 100000000)
          badOption("--time", "more than 1e8 steps; raise --dt" + gotValue(o->time));

#ifndef CABLELAB_HAVE_OFFSCREEN
        if (!o->png.empty()) badOption("--png", "this build has no offscreen renderer");
#endif
        requireOutputFile(o->png, "--png");
        std::unique_ptr<CsvWriter> csv;
        if (!o->csv.empty()) {
          csv = std::make_unique<CsvWriter>(o->csv, world);
          csv->row(world);
        }
        Progress progress("run " + o->scene, steps);
        std::vector<double> stepMicros;
        stepMicros.reserve(std::min<long>(steps, 1000000));
        for (long i = 0; i < steps; ++i) {
          world.step(dt, substeps);
          if (static_cast<long>(stepMicros.size()) < 1000000)
            stepMicros.push_back(world.lastStepStats().stepMicros);
          if (csv) csv->row(world);
          progress.update(i + 1);
        }
        progress.done();
        if (csv) csv->finish();
#ifdef CABLELAB_HAVE_OFFSCREEN
        if (!o->png.empty()) ui::writeSnapshotPng(world, o->png, 800, 600);
#endif
        nlohmann::json out = {{"scene", world.scene().name}, {"steps", steps},
                              {"time", world.time()},        {"dt", dt},
                              {"substeps", substeps},        {"step_us_median", median(stepMicros)},
                              {"warnings", world.warnings()}};
        printJson(out.dump());
        return 0;
      };
    });

}  // namespace
}  // namespace cablelab::app
