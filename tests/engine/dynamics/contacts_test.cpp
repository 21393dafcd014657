// Contacts and cables (World::expectContacts): Box2D's contact solver acts after the cable solve,
// so the cable solve expects the contact forces of the steps before. A block on a table pulled
// by a weight hanging over the table's edge pulley is the textbook case: with friction mu the
// weight falls at (m2 - mu m1) g / (m1 + m2), or the block holds if mu m1 >= m2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/dynamics/world.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

using test::kDt;
constexpr double kG = 9.81;

BodyDef box(const std::string& name, const Vec2& at, double half, double mass, double mu) {
  BodyDef b;
  b.name = name;
  b.type = mass > 0 ? BodyType::Dynamic : BodyType::Static;
  b.mass = mass;
  b.position = at;
  ShapeDef s;
  s.kind = ShapeDef::Kind::Polygon;
  s.vertices = {{-half, -half}, {half, -half}, {half, half}, {-half, half}};
  s.friction = mu;
  b.shapes = {s};
  return b;
}

// Before: the rope ran 4.2 mm long while the block slid (mu 0.3) and 6.9 mm while friction held
// it (mu 0.6), the solve having predicted a frictionless block.
TEST(Contacts, ABlockDraggedAcrossATableKeepsTheRopeAtItsLength) {
  const double m1 = 2, m2 = 1;
  for (const double mu : {0.0, 0.3, 0.6}) {
    SceneDef s;
    BodyDef table = box("table", Vec2(0, -2), 2, 0, mu);
    BodyDef block = box("block", Vec2(-1, 0.1), 0.1, m1, mu);
    BodyDef weight = box("weight", Vec2(2.2, -1), 0.1, m2, mu);
    weight.shapes[0].sensor = true;  // it hangs clear of the table
    s.bodies = {table, block, weight};
    CableDef rope;
    rope.name = "rope";
    rope.start = {"block", Vec2(0.1, 0)};
    rope.end = {"weight", Vec2::Zero()};
    PulleyDef edge;
    edge.point = Vec2(2.2, 0.1);
    edge.side = WrapSide::Threaded;
    rope.pulleys = {edge};
    s.cables = {rope};
    World w(s);
    const double a = std::max(0.0, (m2 - mu * m1) * kG / (m1 + m2));
    double worst = 0, v0 = 0;
    while (w.time() < 1.2 - 1e-9) {  // the block is still 0.6 m from the edge at mu 0
      w.step(kDt);
      if (std::abs(w.time() - 0.5) < 1e-9) v0 = w.body(2).velocity.y();
      if (w.time() > 0.5) worst = std::max(worst, std::abs(w.cable(0).stretch()));
    }
    SCOPED_TRACE(testing::Message() << "mu " << mu);
    EXPECT_LT(worst, 5e-5);  // m, from 0.5 s on (the first steps have no contact history)
    EXPECT_NEAR((v0 - w.body(2).velocity.y()) / 0.7, a, 0.01 * a + 1e-3);
    EXPECT_NEAR(w.cable(0).tension(), m2 * (kG - a), 0.005 * m2 * kG);
  }
}

}  // namespace
}  // namespace cablelab
