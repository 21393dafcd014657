// Cable kinematics per wrap point, the joint tension solve (LCP), and a whole step of every
// built-in scene with its cables and with them removed (Box2D alone, sleeping off in World).
// `cablelab bench` reports the same step figures through engine/scenes/bench_scenes.h.
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <random>

#include "engine/cable/cable.h"
#include "engine/dynamics/tension_solver.h"
#include "engine/dynamics/world.h"
#include "engine/scenes/bench_scenes.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {
namespace {

// A zig-zag path of `points` wrap points spread over 4 moving bodies (plus the two anchors).
void BM_CableKinematics(benchmark::State& state) {
  const int points = static_cast<int>(state.range(0));
  std::vector<BodyState> bodies(4);
  for (int b = 0; b < 4; ++b) {
    bodies[b].position = Vec2(b, 0.1 * b);
    bodies[b].angle = 0.2 * b;
    bodies[b].velocity = Vec2(0.1, -0.2);
    bodies[b].angularVelocity = 0.5;
    bodies[b].invMass = 1;
    bodies[b].invInertia = 10;
  }
  std::vector<WrapPoint> path;
  path.push_back({WrapPoint::Kind::Anchor, -1, Vec2(-1, 1), Vec2::Zero(), -1, -1});
  for (int i = 0; i < points; ++i)
    path.push_back(
        {WrapPoint::Kind::Point, i % 4, Vec2(0.05 * i, (i % 2) ? 0.3 : -0.3), Vec2::Zero(), i, -1});
  path.push_back({WrapPoint::Kind::Anchor, -1, Vec2(5, 1), Vec2::Zero(), -1, -1});
  for (auto _ : state) {
    CableKinematics k = cableKinematics(path, bodies);
    benchmark::DoNotOptimize(k.length);
  }
  state.SetItemsProcessed(state.iterations() * points);  // items/s = wrap points/s
}
BENCHMARK(BM_CableKinematics)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Arg(16)->Arg(32);

// The LCP all cables are solved in together (m cables), K = J W + compliance: SPD, random.
void BM_TensionSolve(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  Eigen::MatrixXd J(m, 3 * m);
  for (int i = 0; i < J.size(); ++i) J.data()[i] = g(rng);
  const Eigen::MatrixXd K = J * J.transpose() + 1e-3 * Eigen::MatrixXd::Identity(m, m);
  Eigen::VectorXd b(m);
  for (int i = 0; i < m; ++i) b[i] = g(rng);  // about half the cables go slack
  long iterations = 0;
  for (auto _ : state) {
    LcpSolution s = solveLcp(K, b);
    iterations += s.iterations;
    benchmark::DoNotOptimize(s.x.data());
  }
  state.counters["pivots"] = double(iterations) / double(state.iterations());
}
BENCHMARK(BM_TensionSolve)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Arg(16);

// One World::step of a built-in scene (its dt and sub-steps), with or without its cables.
void BM_SceneStep(benchmark::State& state, const std::string& name) {
  SceneDef scene = makeScene(name);
  if (state.range(0) == 0) scene.cables.clear();
  World world(scene, name);
  for (int i = 0; i < 30; ++i) world.step(scene.dt, scene.substeps);
  long wraps = 0;
  for (auto _ : state) {
    world.step(scene.dt, scene.substeps);
    wraps += world.lastStepStats().wrapPoints;
  }
  state.counters["wraps"] = double(wraps) / double(state.iterations());
  state.counters["substeps"] = scene.substeps;
}
BENCHMARK_CAPTURE(BM_SceneStep, ballast, std::string("ballast"))
    ->Arg(1)
    ->Arg(0)
    ->ArgNames({"cables"});
BENCHMARK_CAPTURE(BM_SceneStep, hand, std::string("hand"))->Arg(1)->Arg(0)->ArgNames({"cables"});
BENCHMARK_CAPTURE(BM_SceneStep, hexagon, std::string("hexagon"))
    ->Arg(1)
    ->Arg(0)
    ->ArgNames({"cables"});
BENCHMARK_CAPTURE(BM_SceneStep, membrane, std::string("membrane"))
    ->Arg(1)
    ->Arg(0)
    ->ArgNames({"cables"});
BENCHMARK_CAPTURE(BM_SceneStep, pulley, std::string("pulley"))
    ->Arg(1)
    ->Arg(0)
    ->ArgNames({"cables"});

// The medians `cablelab bench` reports for the hand (measureScene), as counters.
void BM_HandMedians(benchmark::State& state) {
  SceneTiming t;
  for (auto _ : state) t = measureScene(makeScene("hand"), 60, 5000, 5);
  state.counters["box2d_step_us"] = t.withoutCables.stepMicros;
  state.counters["cable_step_us"] = t.withCables.stepMicros;
  state.counters["cable_overhead"] = t.overhead;
  state.counters["wrap_point_ns"] = t.withCables.wrapPointNanos;
}
BENCHMARK(BM_HandMedians)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace cablelab
