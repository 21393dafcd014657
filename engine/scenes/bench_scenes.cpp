#include "engine/scenes/bench_scenes.h"

#include <algorithm>
#include <vector>

#include "engine/dynamics/world.h"

namespace cablelab {

namespace {

double medianOf(std::vector<double> v) {
  if (v.empty()) return 0;
  auto mid = v.begin() + v.size() / 2;
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

struct Samples {
  std::vector<double> step, cable, perWrap;
  double wraps = 0;
  int substeps = 1;
  std::vector<std::pair<std::string, std::vector<double>>> spanTensions;  // the last run's
};

void sample(SceneDef scene, bool withCables, int warmup, int steps, Samples& out) {
  if (!withCables) scene.cables.clear();
  World world(std::move(scene), "bench");
  const double dt = world.scene().dt;
  const int substeps = std::max(1, world.scene().substeps);
  out.substeps = substeps;
  for (int i = 0; i < warmup; ++i) world.step(dt, substeps);
  for (int i = 0; i < steps; ++i) {
    world.step(dt, substeps);
    const StepStats& s = world.lastStepStats();
    out.step.push_back(s.stepMicros);
    out.cable.push_back(s.cableMicros);
    out.wraps += s.wrapPoints;
    if (s.wrapPoints > 0) out.perWrap.push_back(1e3 * s.cableMicros / s.wrapPoints);
  }
  out.spanTensions.clear();
  for (int c = 0; c < world.cableCount(); ++c) {
    const Cable& cable = world.cable(c);
    std::vector<double> tensions;
    for (int k = 0; k < cable.spanCount(); ++k) tensions.push_back(cable.spanTension(k));
    out.spanTensions.emplace_back(cable.name(), std::move(tensions));
  }
}

StepTiming summarise(const Samples& s) {
  StepTiming t;
  t.steps = static_cast<int>(s.step.size());
  t.stepMicros = medianOf(s.step);
  t.cableMicros = medianOf(s.cable);
  t.meanWrapPoints = t.steps > 0 ? s.wraps / t.steps : 0;
  t.wrapPointNanos = medianOf(s.perWrap);
  t.substepWrapPointNanos = t.wrapPointNanos / s.substeps;
  t.spanTensions = s.spanTensions;
  return t;
}

}  // namespace

StepTiming measureSceneSteps(SceneDef scene, bool withCables, int warmup, int steps) {
  Samples s;
  sample(std::move(scene), withCables, warmup, steps, s);
  return summarise(s);
}

SceneTiming measureScene(const SceneDef& scene, int warmup, int steps, int rounds) {
  rounds = std::max(1, rounds);
  Samples with, without;
  for (int r = 0; r < rounds; ++r) {
    const int n = steps / rounds + (r < steps % rounds ? 1 : 0);
    sample(scene, true, warmup, n, with);
    sample(scene, false, warmup, n, without);
  }
  SceneTiming t;
  t.scene = scene.name;
  t.withCables = summarise(with);
  t.withoutCables = summarise(without);
  t.overhead =
      t.withoutCables.stepMicros > 0 ? t.withCables.stepMicros / t.withoutCables.stepMicros - 1 : 0;
  return t;
}

}  // namespace cablelab
