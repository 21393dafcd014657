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

// Steps of one world, timed one by one into `out`.
void record(World& world, int steps, Samples& out) {
  const double dt = world.scene().dt;
  const int substeps = std::max(1, world.scene().substeps);
  out.substeps = substeps;
  for (int i = 0; i < steps; ++i) {
    world.step(dt, substeps);
    const StepStats& s = world.lastStepStats();
    out.step.push_back(s.stepMicros);
    out.cable.push_back(s.cableMicros);
    out.wraps += s.wrapPoints;
    if (s.wrapPoints > 0) out.perWrap.push_back(1e3 * s.cableMicros / s.wrapPoints);
  }
}

void recordSpanTensions(const World& world, Samples& out) {
  out.spanTensions.clear();
  for (int c = 0; c < world.cableCount(); ++c) {
    const Cable& cable = world.cable(c);
    std::vector<double> tensions;
    for (int k = 0; k < cable.spanCount(); ++k) tensions.push_back(cable.spanTension(k));
    out.spanTensions.emplace_back(cable.name(), std::move(tensions));
  }
}

SceneDef withoutCables(SceneDef scene) {
  scene.cables.clear();
  return scene;
}

void warmUp(World& world, int warmup) {
  for (int i = 0; i < warmup; ++i) world.step(world.scene().dt, world.scene().substeps);
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
  World world(withCables ? std::move(scene) : withoutCables(std::move(scene)), "bench");
  warmUp(world, warmup);
  Samples s;
  record(world, steps, s);
  recordSpanTensions(world, s);
  return summarise(s);
}

SceneTiming measureScene(const SceneDef& scene, int warmup, int steps, int rounds) {
  // A shared machine's speed drifts within a second (the VM this was written on: a step's
  // median moved by 1.5x between runs a few seconds apart), so the two worlds step side by side
  // in batches of kBatch steps: both medians sample the same moments.
  constexpr int kBatch = 10;
  rounds = std::max(1, rounds);
  Samples with, without;
  for (int r = 0; r < rounds; ++r) {
    const int n = steps / rounds + (r < steps % rounds ? 1 : 0);
    World a(scene, "bench"), b(withoutCables(scene), "bench");
    warmUp(a, warmup);
    warmUp(b, warmup);
    for (int done = 0; done < n; done += kBatch) {
      const int batch = std::min(kBatch, n - done);
      record(a, batch, with);
      record(b, batch, without);
    }
    recordSpanTensions(a, with);
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
