// Cable::nextEvent against crossing times worked out by hand, and the look-ahead selection.
#include <gtest/gtest.h>

#include "engine/cable/cable.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

using test::kDt;

// A cable (-1, 0) -> pulley on body "p" -> (1, 0); the pulley is a point or a square.
SceneDef crossingScene(bool polygon) {
  SceneDef s;
  BodyDef b;
  b.name = "p";
  b.mass = 1;
  s.bodies = {b};
  CableDef c;
  c.name = "c";
  c.start = {"world", Vec2(-1, 0)};
  c.end = {"world", Vec2(1, 0)};
  PulleyDef p;
  p.body = "p";
  p.side = WrapSide::Left;
  if (polygon) {
    p.kind = PulleyDef::Kind::Polygon;
    p.vertices = {Vec2(-0.1, -0.1), Vec2(0.1, -0.1), Vec2(0.1, 0.1), Vec2(-0.1, 0.1)};
  }
  c.pulleys = {p};
  s.cables = {c};
  return s;
}

BodyState at(const Vec2& position, const Vec2& velocity, double angle = 0, double spin = 0) {
  BodyState b;
  b.position = position;
  b.velocity = velocity;
  b.angle = angle;
  b.angularVelocity = spin;
  b.invMass = 1;
  b.invInertia = 1;
  return b;
}

TEST(CableEvents, PointPulleyJoinsWhenItReachesTheSegment) {
  const SceneDef scene = crossingScene(false);
  Cable cable(scene, 0, "test");
  std::vector<BodyState> bodies{at(Vec2(0.3, -0.2), Vec2(0, 40))};
  cable.update(bodies);
  ASSERT_EQ(cable.wraps(), 0);
  const auto e = cable.nextEvent(bodies, kDt);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->kind, WrapEvent::Kind::Join);
  EXPECT_EQ(e->pulley, 0);
  EXPECT_NEAR(e->time, 0.2 / 40, 1e-9 * kDt);
  // Moved to the event, and selected a moment later: it joins with no length jump.
  const double before = cable.length();
  bodies[0].position.y() += e->time * 40;
  std::vector<BodyState> ahead = bodies;
  ahead[0].position.y() += 1e-6 * kDt * 40;
  cable.update(ahead, bodies, nullptr);
  EXPECT_EQ(cable.wraps(), 1);
  EXPECT_NEAR(cable.length(), before, 1e-12);
}

TEST(CableEvents, EngagedPointLeavesWhenTheTurnStraightens) {
  const SceneDef scene = crossingScene(false);
  Cable cable(scene, 0, "test");
  std::vector<BodyState> bodies{at(Vec2(0, -0.1), Vec2::Zero())};
  cable.update(bodies);
  bodies[0].position.y() = 0.25;  // crossed: the cable bends round it
  cable.update(bodies);
  ASSERT_EQ(cable.wraps(), 1);
  bodies[0].velocity = Vec2(0, -30);
  const auto e = cable.nextEvent(bodies, kDt);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->kind, WrapEvent::Kind::Leave);
  EXPECT_NEAR(e->time, 0.25 / 30, 1e-9 * kDt);
}

TEST(CableEvents, SquareCornerAndItsNextVertexAreLocated) {
  // A square turned 45 degrees, its top corner at y = -0.05 rising at 10 m/s: that corner
  // reaches the segment y = 0 first.
  const SceneDef scene = crossingScene(true);
  Cable cable(scene, 0, "test");
  const double r = 0.1 * std::sqrt(2.0);
  std::vector<BodyState> bodies{at(Vec2(0.2, -0.05 - r), Vec2(0, 10), M_PI / 4)};
  cable.update(bodies);
  ASSERT_EQ(cable.wraps(), 0);
  const auto join = cable.nextEvent(bodies, kDt);
  ASSERT_TRUE(join.has_value());
  EXPECT_EQ(join->kind, WrapEvent::Kind::Join);
  EXPECT_NEAR(join->time, 0.05 / 10, 1e-9 * kDt);
  // Pushed 0.05 m through, the chain is the top corner alone.
  bodies[0].position.y() = 0.05 - r;
  cable.update(bodies);
  ASSERT_EQ(cable.wraps(), 1);
  const auto vertex = cable.nextEvent(bodies, 1.0);
  ASSERT_TRUE(vertex.has_value());
  EXPECT_EQ(vertex->kind, WrapEvent::Kind::Vertex);
  // The right corner (0.2 + r, y_c) is nearer its end (1, 0): it reaches the segment top corner
  // (0.2, y_c + r) -> (1, 0) first, where the three are collinear; y_c(t) = 0.05 - r + 10 t.
  const double t = vertex->time, yc = 0.05 - r + 10 * t;
  const Vec2 top(0.2, yc + r), right(0.2 + r, yc), b(1, 0);
  EXPECT_NEAR(cross(b - top, right - top), 0, 1e-9);
  // In closed form: the edge top -> right has slope -1, so it points at (1, 0) once
  // y_c + r = 1 - 0.2.
  EXPECT_NEAR(yc, 0.8 - r, 1e-9);
}

TEST(CableEvents, AnEndAnchorGoingIntoAPassingSquareIsLocated) {
  // A square (0.2 m) beyond the end anchor (1, 0), centred 5 cm above the cable's line and moving
  // at -10 m/s along it: no vertex crosses the segment, but the anchor goes in across the left
  // edge (vertex 3 -> 0) once the centre is at x = 1.1, and out across the right one at 0.9.
  // Unlocated, a hull that takes the anchor in and out within one step leaves the next update a
  // polygon the segment cuts and that it never saw cross: it joined round it, off the old path.
  const SceneDef scene = crossingScene(true);
  Cable cable(scene, 0, "test");
  std::vector<BodyState> bodies{at(Vec2(1.3, 0.05), Vec2(-10, 0))};
  cable.update(bodies);
  ASSERT_EQ(cable.wraps(), 0);
  const auto in = cable.nextEvent(bodies, 0.05);
  ASSERT_TRUE(in.has_value());
  EXPECT_EQ(in->kind, WrapEvent::Kind::Hull);
  EXPECT_EQ(in->pulley, 0);
  EXPECT_EQ(in->vertex, 3);
  EXPECT_NEAR(in->time, 0.2 / 10, 1e-9);
  // Selected a moment after it, the anchor inside: the square does not join.
  bodies[0].position.x() = 1.1 - 1e-6;
  cable.update(bodies);
  EXPECT_EQ(cable.wraps(), 0);
  const auto out = cable.nextEvent(bodies, 0.05);
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(out->kind, WrapEvent::Kind::Hull);
  EXPECT_EQ(out->vertex, 1);
  EXPECT_NEAR(out->time, (0.2 - 1e-6) / 10, 1e-9);
}

TEST(CableEvents, NothingAheadMeansNoEvent) {
  const SceneDef scene = crossingScene(false);
  Cable cable(scene, 0, "test");
  std::vector<BodyState> bodies{at(Vec2(0.3, -0.5), Vec2(0, 1))};
  cable.update(bodies);
  EXPECT_FALSE(cable.nextEvent(bodies, kDt).has_value());
}

}  // namespace
}  // namespace cablelab
