// Wrap-point selection plus kinematics (Cable::update) per wrap point: a cable zig-zagging over
// 16 pulleys on moving bodies, all squares (polygon vertices) or all circles. The bound:
// a circle wrap point costs no more than 2x a polygon vertex (compare the ns per item).
#include <benchmark/benchmark.h>

#include "engine/cable/cable.h"

namespace cablelab {
namespace {

SceneDef zigZag(bool circles, int count) {
  SceneDef s;
  for (int i = 0; i < count; ++i) {
    BodyDef b;
    b.name = "b" + std::to_string(i);
    b.position = Vec2(0.5 * i, (i % 2) ? 0.05 : -0.05);  // the straight cable cuts them all
    ShapeDef box;
    box.kind = ShapeDef::Kind::Polygon;
    box.vertices = {Vec2(-0.1, -0.1), Vec2(0.1, -0.1), Vec2(0.1, 0.1), Vec2(-0.1, 0.1)};
    b.shapes = {box};
    s.bodies.push_back(b);
  }
  CableDef c;
  c.name = "c";
  c.start = {"world", Vec2(-1, 0)};
  c.end = {"world", Vec2(0.5 * count, 0)};
  for (int i = 0; i < count; ++i) {
    PulleyDef p;
    p.body = "b" + std::to_string(i);
    // Over the top of the low bodies, under the high ones: every pulley bends the cable.
    p.side = (i % 2) ? WrapSide::Right : WrapSide::Left;
    if (circles) {
      p.kind = PulleyDef::Kind::Circle;
      p.radius = 0.1;
    } else {
      p.kind = PulleyDef::Kind::Polygon;
    }
    c.pulleys.push_back(p);
  }
  s.cables = {c};
  return s;
}

void BM_CableUpdate(benchmark::State& state) {
  const bool circles = state.range(0) == 1;
  const int count = 16;
  const SceneDef scene = zigZag(circles, count);
  std::vector<BodyState> bodies(count);
  for (int i = 0; i < count; ++i) {
    bodies[i].position = scene.bodies[i].position;
    bodies[i].angularVelocity = 0.3;
    bodies[i].velocity = Vec2(0, 0.01);
  }
  Cable cable(scene, 0, "bench");
  cable.update(bodies);
  long points = 0;
  double t = 0;
  for (auto _ : state) {
    t += 1e-3;
    for (int i = 0; i < count; ++i) bodies[i].angle = 0.3 * t;  // the pulleys turn
    cable.update(bodies);
    points += cable.wraps();
    benchmark::DoNotOptimize(cable.length());
  }
  state.SetItemsProcessed(points);  // items/s = wrap points/s
  state.counters["wraps"] = double(points) / double(state.iterations());
  state.SetLabel(circles ? "circles" : "squares (vertices)");
}
BENCHMARK(BM_CableUpdate)->Arg(0)->Arg(1);

}  // namespace
}  // namespace cablelab
