// cablelab bench: the headline performance figures, all measured in this process and this run
// (docs/cli.md). Medians throughout; the measuring code lives in the engine (bench_scenes.h,
// statics_bench.h, hand_controller.h, hand_reach.h) and is shared with tests/bench/.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "app/command.h"
#include "app/options.h"
#include "engine/dynamics/world.h"
#include "engine/hand/hand_controller.h"
#include "engine/hand/hand_reach.h"
#include "engine/scenes/bench_scenes.h"
#include "engine/scenes/scale_scenes.h"
#include "engine/scenes/scene_registry.h"
#include "engine/statics/statics_bench.h"
#ifdef CABLELAB_HAVE_MUJOCO
#include "engine/mujoco/mujoco_world.h"
#endif

namespace cablelab::app {
namespace {

constexpr int kFullReachGrid = 50;

nlohmann::json machine() {
  std::string cpu = "unknown";
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) cpu = line.substr(line.find_first_not_of(" \t", colon + 1));
      break;
    }
#ifdef NDEBUG
  const bool optimised = true;
#else
  const bool optimised = false;
#endif
  return {{"cores", std::thread::hardware_concurrency()},
          {"cpu", cpu},
          {"compiler", __VERSION__},
          {"ndebug", optimised}};
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Issue 11's scale cases, stepped by cablelab and by MuJoCo from the same SceneDef
// (engine/scenes/scale_scenes.h; the files in tests/data/bench/ are these scenes), in
// interleaved rounds: each round steps every case a few times, cablelab then MuJoCo, so that
// the VM's drifting speed hits every N alike (the growth exponent compares them; measured one
// after the other, a slow spell over N = 1024 alone once read 1.16 where the cases side by side
// read 1.01). `steps[k]` steps of case k in all. Medians per step (us).
struct ScaleTiming {
  double cablelab = 0, cable = 0, mujoco = 0;
};

std::vector<ScaleTiming> measureScaleCases(const std::vector<ScaleCase>& cases,
                                           const std::vector<int>& steps, int rounds) {
  using Clock = std::chrono::steady_clock;
  std::vector<std::unique_ptr<World>> worlds;
#ifdef CABLELAB_HAVE_MUJOCO
  std::vector<std::unique_ptr<MujocoWorld>> mujocos;
#endif
  for (const ScaleCase& c : cases) {
    worlds.push_back(std::make_unique<World>(c.scene, c.scene.name));
    for (int i = 0; i < 5; ++i) worlds.back()->step(c.scene.dt, c.scene.substeps);
#ifdef CABLELAB_HAVE_MUJOCO
    mujocos.push_back(std::make_unique<MujocoWorld>(c.scene));
    for (int i = 0; i < 5; ++i) mujocos.back()->step();
#endif
  }
  std::vector<std::vector<double>> ours(cases.size()), cable(cases.size()), theirs(cases.size());
  for (int round = 0; round < rounds; ++round)
    for (size_t k = 0; k < cases.size(); ++k) {
      const SceneDef& scene = cases[k].scene;
      const int n = std::max(1, steps[k] / rounds);
      for (int i = 0; i < n; ++i) {
        const auto t0 = Clock::now();
        worlds[k]->step(scene.dt, scene.substeps);
        ours[k].push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
        cable[k].push_back(worlds[k]->lastStepStats().cableMicros);
      }
#ifdef CABLELAB_HAVE_MUJOCO
      for (int i = 0; i < n; ++i) {
        const auto t0 = Clock::now();
        mujocos[k]->step();
        theirs[k].push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
      }
#endif
    }
  std::vector<ScaleTiming> timings;
  for (size_t k = 0; k < cases.size(); ++k)
    timings.push_back({median(ours[k]), median(cable[k]), median(theirs[k])});
  return timings;
}

// One big island (a chain or a net of cables, engine/scenes/scale_scenes.h): medians of
// individually timed steps, the whole step and its cable part (us).
ScaleTiming measureBigIsland(const SceneDef& scene, int steps, int rounds) {
  using Clock = std::chrono::steady_clock;
  World world(scene, scene.name);
  for (int i = 0; i < 3; ++i) world.step(scene.dt, scene.substeps);
  std::vector<double> step, cable;
  for (int i = 0; i < steps * rounds; ++i) {
    const auto t0 = Clock::now();
    world.step(scene.dt, scene.substeps);
    step.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
    cable.push_back(world.lastStepStats().cableMicros);
  }
  return {median(step), median(cable), 0};
}

// Least-squares slope of log(y) against log(x).
double logLogSlope(const std::vector<std::pair<double, double>>& points) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [x0, y0] : points) {
    const double x = std::log(x0), y = std::log(y0);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double k = static_cast<double>(points.size());
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

const bool benchRegistered = registerCommand(
    "bench", "Measure the headline performance figures (docs/cli.md)", [](CLI::App& sub) {
      struct Options {
        bool json = false, quick = false;
      };
      auto o = std::make_shared<Options>();
      sub.add_flag("--json", o->json, "Print one JSON object instead of a table");
      sub.add_flag("--quick", o->quick,
                   "Fewer samples and a 20 x 20 reach grid scaled to 50 x 50 (under 20 s)");
      return [o] {
        using Clock = std::chrono::steady_clock;
        const auto start = Clock::now();
        const bool quick = o->quick;
        nlohmann::json out;
        out["quick"] = quick;
        // One bar over the stages (hand, scenes, scale, big islands, 3 x statics, controller,
        // reach), the stage under way as its note.
        Progress progress("bench", 9);
        long stagesDone = 0;
        auto stage = [&](const std::string& what) { progress.update(stagesDone++, what); };

        // 1. The hand scene with and without its cables, interleaved rounds.
        stage("hand scene step, with and without cables");
        const SceneDef hand = makeScene("hand");
        const int handSteps = quick ? 3000 : 20000;
        const SceneTiming h = measureScene(hand, 60, handSteps, quick ? 4 : 10);
        out["box2d_step_us"] = h.withoutCables.stepMicros;
        out["cable_step_us"] = h.withCables.stepMicros;
        out["cable_overhead"] = h.overhead;
        out["wrap_point_ns"] = h.withCables.wrapPointNanos;
        out["wrap_point_substep_ns"] = h.withCables.substepWrapPointNanos;
        out["hand"] = {{"steps", h.withCables.steps},
                       {"substeps", hand.substeps},
                       {"dt", hand.dt},
                       {"wrap_points_mean", h.withCables.meanWrapPoints},
                       {"cable_us", h.withCables.cableMicros}};

        // Every other built-in scene, for context (same method).
        stage("other built-in scenes");
        nlohmann::json scenes = nlohmann::json::object();
        for (const SceneInfo& info : builtinScenes()) {
          const SceneTiming t =
              info.name == "hand" ? h
                                  : measureScene(makeScene(info.name), 30, quick ? 1000 : 5000, 4);
          nlohmann::json spans = nlohmann::json::object();
          for (const auto& [cable, tensions] : t.withCables.spanTensions) spans[cable] = tensions;
          scenes[info.name] = {{"box2d_step_us", t.withoutCables.stepMicros},
                               {"cable_step_us", t.withCables.stepMicros},
                               {"cable_overhead", t.overhead},
                               {"wrap_points_mean", t.withCables.meanWrapPoints},
                               {"span_tensions_n", spans}};
        }
        out["scenes"] = scenes;

        // 1b. Scale: cablelab against MuJoCo on the same worlds, and how the cable cost grows.
        stage("scale: Atwood machines and the 64-pulley cable, cablelab and MuJoCo");
        nlohmann::json scaleTable = nlohmann::json::object(), ratios = nlohmann::json::object();
        std::vector<std::pair<double, double>> growth;  // (cables, cable us), Atwood cases
        const std::vector<ScaleCase> cases = scaleCases();
        const int scaleRounds = 12;
        std::vector<int> caseSteps;
        for (const ScaleCase& c : cases) {
          const int cables = static_cast<int>(c.scene.cables.size());
          caseSteps.push_back(scaleRounds *
                              std::max(quick ? 2 : 5, (quick ? 500 : 2000) / (cables + 4)));
        }
        const std::vector<ScaleTiming> timings = measureScaleCases(cases, caseSteps, scaleRounds);
        for (size_t k = 0; k < cases.size(); ++k) {
          const ScaleCase& c = cases[k];
          const ScaleTiming& t = timings[k];
          const int cables = static_cast<int>(c.scene.cables.size());
          scaleTable[c.name] = {{"cablelab_us", t.cablelab},
                                {"cable_us", t.cable},
                                {"cables", cables},
                                {"steps", caseSteps[k]}};
#ifdef CABLELAB_HAVE_MUJOCO
          scaleTable[c.name]["mujoco_us"] = t.mujoco;
          ratios[c.name] = t.cablelab / t.mujoco;
#else
          ratios[c.name] = nullptr;
#endif
          if (c.name.rfind("atwood_", 0) == 0 && cables >= 16) growth.push_back({cables, t.cable});
        }
        out["scale"] = scaleTable;
        out["mujoco_ratio"] = ratios;  // cablelab step / MuJoCo step, per case; < 1: faster
        // Least-squares slope of log(cable us) against log(N), N = 16 .. 1024.
        double sx = 0, sy = 0, sxx = 0, sxy = 0;
        for (const auto& [n, us] : growth) {
          const double x = std::log(n), y = std::log(us);
          sx += x, sy += y, sxx += x * x, sxy += x * y;
        }
        const double k = static_cast<double>(growth.size());
        out["cable_overhead_exponent"] = (k * sxy - sx * sy) / (k * sxx - sx * sx);

        // 1c. One big island: chains of N links (16 .. 1024) and nets; the sparse path solves
        // those above its threshold (docs/model.md, "Big islands").
        stage("big islands: chains and nets of cables");
        nlohmann::json bigTable = nlohmann::json::object();
        std::vector<std::pair<double, double>> chainGrowth;  // (links, step us), N >= 64
        for (const ScaleCase& c : bigIslandCases()) {
          const int cables = static_cast<int>(c.scene.cables.size());
          if (cables > 1000 && c.name.rfind("net_", 0) == 0) continue;  // ~1 s a step
          const int steps = std::max(quick ? 2 : 5, (quick ? 1000 : 4000) / (cables + 4));
          const ScaleTiming t = measureBigIsland(c.scene, steps, 3);
          bigTable[c.name] = {{"step_us", t.cablelab},
                              {"cable_us", t.cable},
                              {"cables", cables},
                              {"bodies", c.scene.bodies.size()},
                              {"steps", 3 * steps}};
          if (c.name.rfind("chain_", 0) == 0 && cables >= 64)  // above the sparse threshold
            chainGrowth.push_back({cables, t.cablelab});
        }
        out["big_island"] = bigTable;
        // Log-log slope of the chain's step time over N = 64 .. 1024 links (sparse path).
        out["big_island_exponent"] = logLogSlope(chainGrowth);

        // 2. Statics solvers, cold start, seeded random instances.
        const int instances = quick ? 150 : 1000;
        nlohmann::json socp = nlohmann::json::object(), newton = nlohmann::json::object();
        for (int n : {2, 4, 8}) {
          stage("statics, " + std::to_string(n) + " cables");
          const StaticsTimings t = measureStatics(n, instances, 42);
          socp[std::to_string(n)] = t.socpMicros;
          newton[std::to_string(n)] = t.newtonMicros;
        }
        out["statics_socp_us"] = socp;
        out["statics_newton_us"] = newton;
        out["statics_instances"] = instances;

        // 3. Controller update.
        stage("controller update");
        out["controller_update_us"] = measureControllerUpdateMicros(quick ? 5000 : 20000);

        // 4. The reach sweep, the code `cablelab reach` runs (same options).
        const int grid = quick ? 20 : kFullReachGrid;
        stage("reach sweep, " + std::to_string(grid) + " x " + std::to_string(grid));
        ReachOptions reach;
        reach.grid = grid;
        reach.threads =
            static_cast<int>(std::max(1u, std::min(2u, std::thread::hardware_concurrency())));
        const ReachResult r =
            runReach(reach, HandModel{}, [&](long, long) { progress.update(stagesDone - 1); });
        progress.done();
        const double scale = double(kFullReachGrid) * kFullReachGrid / (double(grid) * grid);
        out["reach_sweep_s"] = r.seconds * scale;
        out["reach_sweep"] = {
            {"grid", grid},
            {"measured_s", r.seconds},
            {"threads", reach.threads},
            {"scaled_to_50x50", quick},
            {"note", quick ? "--quick: a 20 x 20 grid timed and scaled by 6.25 to 50 x 50"
                           : "50 x 50 grid timed"}};

        out["machine"] = machine();
        out["bench_s"] = std::chrono::duration<double>(Clock::now() - start).count();

        if (o->json) {
          printJson(out.dump());
          return 0;
        }
        const nlohmann::json& m = out["machine"];
        std::printf("cablelab bench%s  (%s, %d cores)\n", quick ? " --quick" : "",
                    m["cpu"].get<std::string>().c_str(), m["cores"].get<int>());
        std::printf("  %-34s %12s\n", "figure (median)", "value");
        auto row = [](const char* name, double v, const char* unit) {
          std::printf("  %-34s %12.3f %s\n", name, v, unit);
        };
        row("hand step, Box2D alone", out["box2d_step_us"], "us");
        row("hand step, with cables", out["cable_step_us"], "us");
        row("cable overhead", 100.0 * out["cable_overhead"].get<double>(), "%");
        row("cable update + solve per wrap point", out["wrap_point_ns"], "ns/step");
        for (const char* n : {"2", "4", "8"}) {
          row(("statics SOCP, " + std::string(n) + " cables").c_str(), socp[n], "us");
          row(("statics Newton, " + std::string(n) + " cables").c_str(), newton[n], "us");
        }
        row("controller update", out["controller_update_us"], "us");
        row(quick ? "reach sweep 50x50 (scaled from 20x20)" : "reach sweep 50x50",
            out["reach_sweep_s"], "s");
        std::printf("  scale (step us: cablelab / MuJoCo / ratio; cable us):\n");
        for (const auto& [name, c] : scaleTable.items())
          std::printf("    %-12s %10.1f %10.1f %8.3f %10.1f\n", name.c_str(),
                      c["cablelab_us"].get<double>(), c.value("mujoco_us", 0.0),
                      ratios[name].is_null() ? 0.0 : ratios[name].get<double>(),
                      c["cable_us"].get<double>());
        row("cable cost growth exponent (N = 16..1024)", out["cable_overhead_exponent"], "");
        std::printf("  big islands (step us; cable us):\n");
        for (const auto& [name, c] : bigTable.items())
          std::printf("    %-12s %10.1f %10.1f\n", name.c_str(), c["step_us"].get<double>(),
                      c["cable_us"].get<double>());
        row("big island growth exponent (chain, N = 64..1024)", out["big_island_exponent"], "");
        std::printf("  per scene (step us: Box2D alone / with cables / overhead):\n");
        for (const auto& [name, s] : scenes.items())
          std::printf("    %-10s %9.2f %9.2f %8.1f %%\n", name.c_str(),
                      s["box2d_step_us"].get<double>(), s["cable_step_us"].get<double>(),
                      100 * s["cable_overhead"].get<double>());
        return 0;
      };
    });

}  // namespace
}  // namespace cablelab::app
