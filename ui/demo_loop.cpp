#include "ui/demo_loop.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace cablelab::ui {
namespace demo_loop {

constexpr double kMoving = 0.05;       // m/s: a body this fast has started the run
constexpr double kAtRest = 0.01;       // m/s (and rad/s, scaled by 0.2 m): a body this slow rests
constexpr double kStageMargin = 0.05;  // of the stage's larger side: room round the stage

/// The largest speed of the dynamic bodies (m/s; a rotation counts as its speed at 0.2 m).
double fastest(const World& world) {
  double v = 0;
  for (int i = 0; i < world.bodyCount(); ++i) {
    if (world.scene().bodies[i].type != BodyType::Dynamic) continue;
    const BodyState& s = world.body(i);
    v = std::max({v, s.velocity.norm(), 0.2 * std::abs(s.angularVelocity)});
  }
  return v;
}

/// True when a dynamic body is farther off the stage than the stage is large.
bool offStage(const WorldBounds& stage, const World& world) {
  if (stage.empty()) return false;
  const double size = std::max((stage.hi - stage.lo).maxCoeff(), 0.1);
  for (int i = 0; i < world.bodyCount(); ++i) {
    if (world.scene().bodies[i].type != BodyType::Dynamic) continue;
    const Vec2 p = world.body(i).position;
    if ((p - p.cwiseMax(stage.lo).cwiseMin(stage.hi)).norm() > size) return true;
  }
  return false;
}

}  // namespace demo_loop

bool demoLoops(const std::string& name) {
  static const std::set<std::string> kRunsThatEnd = {"ballast", "pulley", "tackle",
                                                     "wheel",   "winch",  "capstan"};
  return kRunsThatEnd.count(name) > 0;
}

DemoRun startDemo(const SceneDef& scene, const std::string& name) {
  DemoRun run;
  run.loops = demoLoops(name);
  if (!run.loops) return run;  // an edited scene is probed on every edit: only the demos are
  try {
    World probe(scene, name);
    run.stage = sceneBounds(probe);
    const long steps = std::lround(kStageProbeSeconds / scene.dt);
    for (long i = 0; i < steps; ++i) {
      probe.step(scene.dt, scene.substeps);
      if (i % 6 == 0) {  // ten looks a second are enough for bounds
        const WorldBounds b = sceneBounds(probe);
        run.stage.include(b.lo);
        run.stage.include(b.hi);
      }
    }
  } catch (const std::exception&) {  // the window reports a failing run when it happens
  }
  if (!run.stage.empty()) {
    const double margin = demo_loop::kStageMargin * (run.stage.hi - run.stage.lo).maxCoeff();
    run.stage.include(run.stage.lo, margin);
    run.stage.include(run.stage.hi, margin);
  }
  return run;
}

bool runEnded(DemoRun& run, const World& world, double dt) {
  using namespace demo_loop;
  const double v = fastest(world);
  if (v > kMoving) run.moved = true;
  const bool ended = (run.moved && v < kAtRest) || offStage(run.stage, world);
  run.endedFor = ended ? run.endedFor + dt : 0;
  return run.endedFor >= kRunEndSeconds - 1e-9;
}

}  // namespace cablelab::ui
