// The cost of wrap-event cuts (docs/cables.md, "Events"): a square spinning in an elastic sling
// at 0, 6 and 24 rad/s (4 sub-steps). At rest no event cuts a step; spinning, the vertices in
// the sling change and each change cuts Box2D's step and solves the cable again. The counters
// give the cuts per step: the time per cut is the slope of the step time against them.
//   build/bin/cablelab_bench --benchmark_filter=EventCuts
#include <benchmark/benchmark.h>

#include "engine/dynamics/world.h"
#include "tests/support/sling_scene.h"

namespace cablelab {
namespace {

void BM_EventCuts(benchmark::State& state) {
  const SceneDef scene = test::sling(4, 1, static_cast<double>(state.range(0)), 400, 4);
  World world(scene, "sling");
  const double dt = 1.0 / 60;
  for (int i = 0; i < 60; ++i) world.step(dt, scene.substeps);  // settled in the sling
  double events = 0, solves = 0;
  for (auto _ : state) {
    world.step(dt, scene.substeps);
    events += world.lastStepStats().events;
    solves += world.lastStepStats().midpointSolves;
  }
  state.counters["cuts_per_step"] = benchmark::Counter(events, benchmark::Counter::kAvgIterations);
  state.counters["solves_per_step"] =
      benchmark::Counter(solves, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_EventCuts)->Arg(0)->Arg(6)->Arg(24)->ArgNames({"spin"});

}  // namespace
}  // namespace cablelab
