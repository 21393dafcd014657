// cablelab against MuJoCo 2.2.2 on the same worlds (issue 11, scale): N independent Atwood
// machines and one cable over 64 point pulleys, read from the same scene files
// (tests/data/bench/, written from engine/scenes/scale_scenes.h). Both step the scene's dt,
// one step per iteration. Counters: cable_us is cablelab's cable update + solve per step.
//   build/bin/cablelab_bench --benchmark_filter=Scale
#include <benchmark/benchmark.h>

#include <string>

#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"

#ifdef CABLELAB_HAVE_MUJOCO
#include "engine/mujoco/mujoco_world.h"
#endif

namespace cablelab {
namespace {

SceneDef scaleScene(const std::string& name) {
  return makeScene(std::string(CABLELAB_SOURCE_DIR) + "/tests/data/bench/" + name + ".json");
}

void BM_ScaleCablelab(benchmark::State& state, const std::string& name) {
  const SceneDef scene = scaleScene(name);
  World world(scene, name);
  for (int i = 0; i < 10; ++i) world.step(scene.dt, scene.substeps);
  double cable = 0;
  for (auto _ : state) {
    world.step(scene.dt, scene.substeps);
    cable += world.lastStepStats().cableMicros;
  }
  state.counters["cable_us"] = cable / double(state.iterations());
  state.counters["cables"] = world.cableCount();
}

#ifdef CABLELAB_HAVE_MUJOCO
void BM_ScaleMujoco(benchmark::State& state, const std::string& name) {
  const SceneDef scene = scaleScene(name);
  MujocoWorld world(scene);
  for (int i = 0; i < 10; ++i) world.step();
  for (auto _ : state) world.step();
  state.counters["dofs"] = world.dofs();
}
#endif

// Registered side by side, case by case, so the two figures of a row come from the same minute.
const bool registered = [] {
  for (const char* name : {"atwood_1", "atwood_16", "atwood_256", "atwood_1024", "pulleys_64"}) {
    benchmark::RegisterBenchmark(("BM_Scale/cablelab/" + std::string(name)).c_str(),
                                 BM_ScaleCablelab, std::string(name))
        ->Unit(benchmark::kMicrosecond);
#ifdef CABLELAB_HAVE_MUJOCO
    benchmark::RegisterBenchmark(("BM_Scale/mujoco/" + std::string(name)).c_str(), BM_ScaleMujoco,
                                 std::string(name))
        ->Unit(benchmark::kMicrosecond);
#endif
  }
  return true;
}();

}  // namespace
}  // namespace cablelab
