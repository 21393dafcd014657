#include "engine/scenes/scale_scenes.h"

#include <algorithm>

namespace cablelab {

namespace {

constexpr double kDiscRadius = 0.1;
constexpr double kDiscMass = 1.0;

BodyDef disc(const std::string& name, const Vec2& position, const Vec2& velocity) {
  BodyDef b;
  b.name = name;
  b.position = position;
  b.velocity = velocity;
  b.mass = kDiscMass;
  b.inertia = 0.5 * kDiscMass * kDiscRadius * kDiscRadius;  // explicit: MuJoCo gets the same
  ShapeDef s;
  s.kind = ShapeDef::Kind::Circle;
  s.radius = kDiscRadius;
  b.shapes = {s};
  return b;
}

PulleyDef threaded(const std::string& body, const Vec2& point) {
  PulleyDef p;
  p.body = body;
  p.point = point;
  p.side = WrapSide::Threaded;
  return p;
}

}  // namespace

SceneDef makeAtwoodMachines(int n) {
  SceneDef s;
  s.name = "atwood_" + std::to_string(n);
  s.description = std::to_string(n) + " independent Atwood machines (equal masses, swinging)";
  s.view = {Vec2(std::min(n, 4) - 1.0, 1.0), 4.0};
  const Vec2 swing(0.2, 0);
  for (int k = 0; k < n; ++k) {
    const double x = 2.0 * k;
    const std::string id = std::to_string(k);
    s.bodies.push_back(disc("left" + id, Vec2(x - 0.25, 0), swing));
    s.bodies.push_back(disc("right" + id, Vec2(x + 0.25, 0), swing));
    CableDef c;
    c.name = "cable" + id;
    c.start = {"left" + id, Vec2(0, kDiscRadius)};
    c.pulleys = {threaded("world", Vec2(x - 0.25, 2)), threaded("world", Vec2(x + 0.25, 2))};
    c.end = {"right" + id, Vec2(0, kDiscRadius)};
    s.cables.push_back(c);
  }
  return s;
}

SceneDef makePulleyChain(int pulleys) {
  const int discs = pulleys / 2;
  SceneDef s;
  s.name = "pulleys_" + std::to_string(pulleys);
  s.description = "one cable over " + std::to_string(pulleys) + " point pulleys, " +
                  std::to_string(discs) + " hanging discs";
  s.view = {Vec2(0.5 * discs, 1.0), 0.6 * discs + 2};
  CableDef c;
  c.name = "cable";
  c.start = {"world", Vec2(0, 2.5)};
  for (int i = 0; i < discs; ++i) {
    const std::string name = "disc" + std::to_string(i);
    s.bodies.push_back(disc(name, Vec2(i + 0.5, 0), Vec2(0, i % 2 ? -0.1 : 0.1)));
    c.pulleys.push_back(threaded("world", Vec2(i, 2)));
    c.pulleys.push_back(threaded(name, Vec2(0, kDiscRadius)));
  }
  c.end = {"world", Vec2(discs, 2)};
  s.cables.push_back(c);
  return s;
}

namespace {

constexpr double kLinkLength = 0.6;  // m: above kFloorWatch (engine/dynamics/floors.h)

CableDef cableLink(const std::string& name, const std::string& from, const std::string& to,
                   const Vec2& fromPoint = Vec2::Zero()) {
  CableDef c;
  c.name = name;
  c.start = {from, fromPoint};
  c.end = {to, Vec2::Zero()};
  return c;
}

}  // namespace

SceneDef makeHangingChain(int n) {
  SceneDef s;
  s.name = "chain_" + std::to_string(n);
  s.description = "a rope of " + std::to_string(n) + " discs linked by rigid cables";
  s.view = {Vec2(0, -0.5 * kLinkLength * n), kLinkLength * n + 1};
  for (int k = 0; k < n; ++k) {
    const std::string name = "disc" + std::to_string(k);
    s.bodies.push_back(disc(name, Vec2(0, -kLinkLength * (k + 1)), Vec2(0.2, 0)));
    s.cables.push_back(k == 0 ? cableLink("link0", "world", name, Vec2::Zero())
                              : cableLink("link" + std::to_string(k), s.bodies[k - 1].name, name));
  }
  return s;
}

SceneDef makeCableNet(int rows, int cols) {
  SceneDef s;
  s.name = "net_" + std::to_string(rows) + "x" + std::to_string(cols);
  s.description = "a " + std::to_string(rows) + " x " + std::to_string(cols) +
                  " curtain of discs and rigid cables";
  s.view = {Vec2(0.5 * kLinkLength * cols, -0.5 * kLinkLength * rows),
            kLinkLength * std::max(rows, cols) + 1};
  auto name = [](int r, int c) { return "disc" + std::to_string(r) + "_" + std::to_string(c); };
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      s.bodies.push_back(
          disc(name(r, c), Vec2(kLinkLength * c, -kLinkLength * (r + 1)), Vec2(0.2, 0)));
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const std::string id = std::to_string(r) + "_" + std::to_string(c);
      s.cables.push_back(r == 0
                             ? cableLink("up" + id, "world", name(r, c), Vec2(kLinkLength * c, 0))
                             : cableLink("up" + id, name(r - 1, c), name(r, c)));
      if (c + 1 < cols) s.cables.push_back(cableLink("right" + id, name(r, c + 1), name(r, c)));
    }
  return s;
}

std::vector<ScaleCase> bigIslandCases() {
  std::vector<ScaleCase> cases;
  for (int n : {16, 64, 256, 1024})
    cases.push_back({"chain_" + std::to_string(n), makeHangingChain(n)});
  for (int n : {4, 8, 16, 32}) {
    SceneDef net = makeCableNet(n, n);
    cases.push_back({net.name, std::move(net)});
  }
  return cases;
}

std::vector<ScaleCase> scaleCases() {
  std::vector<ScaleCase> cases;
  for (int n : {1, 16, 256, 1024})
    cases.push_back({"atwood_" + std::to_string(n), makeAtwoodMachines(n)});
  cases.push_back({"pulleys_64", makePulleyChain(64)});
  return cases;
}

}  // namespace cablelab
