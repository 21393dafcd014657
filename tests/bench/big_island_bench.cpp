// One big island (engine/scenes/scale_scenes.h, bigIslandCases): a rope of N discs linked by
// rigid cables and an n x n curtain of discs and cables, every cable in one island. Time per
// World::step; the growth exponent over N is the log-log slope of these times (docs/model.md,
// "Big islands"; `cablelab bench --json` reports it as big_island_exponent).
#include <benchmark/benchmark.h>

#include "engine/dynamics/sparse_island.h"
#include "engine/dynamics/world.h"
#include "engine/scenes/scale_scenes.h"

namespace cablelab {
namespace {

void BM_BigIsland(benchmark::State& state) {
  const ScaleCase c = bigIslandCases().at(static_cast<size_t>(state.range(0)));
  World world(c.scene, c.scene.name);
  for (int i = 0; i < 5; ++i) world.step(c.scene.dt, c.scene.substeps);
  double cableMicros = 0, pivots = 0;
  for (auto _ : state) {
    world.step(c.scene.dt, c.scene.substeps);
    cableMicros += world.lastStepStats().cableMicros;
    pivots += world.lastStepStats().solverIterations;
  }
  state.counters["pivots"] = pivots / static_cast<double>(state.iterations());
  state.SetLabel(c.name);
  state.counters["bodies"] = static_cast<double>(c.scene.bodies.size());
  state.counters["cables"] = static_cast<double>(c.scene.cables.size());
  state.counters["cable_us"] = cableMicros / static_cast<double>(state.iterations());
}
BENCHMARK(BM_BigIsland)->DenseRange(0, 7)->Unit(benchmark::kMicrosecond);

// The threshold: a swinging chain of n links on either path (path 0: dense, 1: sparse), where
// the two cost the same is where the sparse path starts (sparseIslandThreshold()).
void BM_ChainPath(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  setSparseIslandThreshold(state.range(1) ? 0 : 1 << 30);
  const SceneDef scene = makeHangingChain(n);
  World world(scene, scene.name);
  for (int i = 0; i < 5; ++i) world.step(scene.dt, scene.substeps);
  for (auto _ : state) world.step(scene.dt, scene.substeps);
  setSparseIslandThreshold(-1);
  state.SetLabel(state.range(1) ? "sparse" : "dense");
}
BENCHMARK(BM_ChainPath)
    ->ArgsProduct({{8, 16, 24, 32, 48, 64, 96, 256}, {0, 1}})
    ->ArgNames({"links", "sparse"})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace cablelab
