// Controller update and hand-scene step (with and without the membranes).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "engine/dynamics/world.h"
#include "engine/hand/hand_controller.h"
#include "engine/hand/hand_mpc.h"

namespace cablelab {
namespace {

void BM_HandControllerUpdate(benchmark::State& state) {
  HandController controller{HandModel{}};
  const HandJoints q = HandJoints::Zero();
  const Vec2 box = controller.predict(q, Vec2::Zero()).box;
  for (auto _ : state) benchmark::DoNotOptimize(controller.update(q, box, Vec2(0.01, 0), q));
}
BENCHMARK(BM_HandControllerUpdate);

// One MPC update from the pinch towards a target 10 cm off, planned afresh (no warm start: the
// costliest kind), horizon N. vs_jacobian: its time over one Jacobian controller update's.
void BM_HandMpcUpdate(benchmark::State& state) {
  HandMpcParams params;
  params.horizon = static_cast<int>(state.range(0));
  HandMpc mpc{HandModel{}, params};
  const HandJoints q = HandJoints::Zero();
  const Vec2 box = HandController{HandModel{}}.predict(q, Vec2::Zero()).box;
  double seconds = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    mpc.reset();
    benchmark::DoNotOptimize(
        mpc.update(q, BoxPose(box.x(), box.y(), 0), Vec2::Zero(), BoxPose(0.1, 0.05, 0), q));
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  const double micros = 1e6 * seconds / static_cast<double>(state.iterations());
  state.counters["vs_jacobian"] = micros / measureControllerUpdateMicros(2000);
  state.counters["period_share"] = micros / 53000;  // of the 0.053 s outer-loop period
}
BENCHMARK(BM_HandMpcUpdate)->Arg(6)->Arg(12)->ArgNames({"horizon"})->Unit(benchmark::kMicrosecond);

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

// The hand with its fingers moving: BM_HandStep's hand comes to rest bit for bit after some 5 s,
// and work that depends only on the pose is then not done again (wrap_skip.cpp). Here every
// servo target is swept at 1 Hz (0.02 rad, 2 mm on the slides), and the fingers carry the box up
// and down by 3 cm: no body ever rests, the cost of a hand at work. cables: 1 with them, 0 Box2D
// alone.
void BM_HandMovingStep(benchmark::State& state) {
  SceneDef scene = buildHandScene(HandModel{});
  if (state.range(0) == 0) scene.cables.clear();
  World world(scene, "hand");
  long step = 0;
  for (auto _ : state) {
    const double sweep = std::sin(2 * std::numbers::pi * scene.dt * static_cast<double>(step++));
    for (int j = 0; j < world.jointCount(); ++j)
      world.setServoTarget(j, (j % 3 == kSlide ? 0.002 : 0.02) * sweep);
    world.step(scene.dt, scene.substeps);
  }
}
BENCHMARK(BM_HandMovingStep)->Arg(1)->Arg(0)->ArgNames({"cables"});

}  // namespace
}  // namespace cablelab
