// Controller update and hand-scene step (with and without the membranes).
#include <benchmark/benchmark.h>

#include "engine/dynamics/world.h"
#include "engine/hand/hand_controller.h"

namespace cablelab {
namespace {

void BM_HandControllerUpdate(benchmark::State& state) {
  HandController controller{HandModel{}};
  const HandJoints q = HandJoints::Zero();
  const Vec2 box = controller.predict(q, Vec2::Zero()).box;
  for (auto _ : state) benchmark::DoNotOptimize(controller.update(q, box, Vec2(0.01, 0), q));
}
BENCHMARK(BM_HandControllerUpdate);

void BM_HandStep(benchmark::State& state) {
  SceneDef scene = buildHandScene(HandModel{});
  if (state.range(0) == 0) scene.cables.clear();
  World world(scene, "hand");
  world.setWrapSkipping(state.range(0) != 2);
  double events = 0, iterations = 0, kept = 0, unsearched = 0;
  for (auto _ : state) {
    world.step(scene.dt, scene.substeps);
    events += world.lastStepStats().events;
    iterations += world.lastStepStats().solverIterations;
    kept += world.lastStepStats().selectionSkips;
    unsearched += world.lastStepStats().searchSkips;
  }
  // Sub-steps cut at a wrap event (each costs a second cable solve) and LCP pivots, per step.
  state.counters["cuts"] = benchmark::Counter(events, benchmark::Counter::kAvgIterations);
  state.counters["pivots"] = benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
  // Cable updates that kept the wrap set and event searches skipped (wrap_skip.cpp), per step.
  state.counters["kept"] = benchmark::Counter(kept, benchmark::Counter::kAvgIterations);
  state.counters["unsearched"] = benchmark::Counter(unsearched, benchmark::Counter::kAvgIterations);
}
// cables: 1 with the cables, 0 Box2D alone, 2 with the cables and wrap-set skipping off.
BENCHMARK(BM_HandStep)->Arg(1)->Arg(0)->Arg(2)->ArgNames({"cables"});

}  // namespace
}  // namespace cablelab
