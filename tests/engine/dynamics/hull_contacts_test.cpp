// Which pairs keep a point out of a polygon pulley's hull (engine/dynamics/hull_contacts.h;
// docs/cables.md, "Points inside a hull"), and that their fixtures leave the bodies as the scene
// made them.
#include "engine/dynamics/hull_contacts.h"

#include <gtest/gtest.h>

#include <string>

#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/engine_test_support.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace hull_contacts_test {

SceneDef polygons(const std::string& name) {
  return loadSceneFile(test::dataPath("polygons/" + name + ".json"));
}

int polygonPairs(const std::vector<HullContact>& pairs) {
  int n = 0;
  for (const HullContact& c : pairs) n += !c.otherPolygon.empty();
  return n;
}

// Each square of the loops touches the rope's three world points and the other square (they
// become neighbours on the path once the middle point leaves it); each pair once.
TEST(HullContacts, EverySquareOfTheLoopsTouchesTheWorldPointsAndTheOtherSquare) {
  const std::vector<HullContact> pairs = hullContacts(polygons("polygons_in_rope_loops"));
  ASSERT_EQ(pairs.size(), 7u);
  EXPECT_EQ(polygonPairs(pairs), 1);
  for (const HullContact& c : pairs)
    if (c.otherPolygon.empty()) {
      EXPECT_EQ(c.otherBody, -1);
      EXPECT_DOUBLE_EQ(c.point.y(), 1.0);
      EXPECT_EQ(c.polygon.size(), 4u);
    }
}

// Hexagons placed overlapping (0.5 m apart, 0.52 m across their flats) do not touch: the scene
// put them so. Just clear of each other (0.57 m: a corner 1 cm from the facing flat) they do.
TEST(HullContacts, PolygonsPlacedOverlappingDoNotTouch) {
  SceneDef scene = polygons("two_polygons_spinning");
  EXPECT_EQ(polygonPairs(hullContacts(scene)), 1);
  scene.bodies[0].position.x() = -0.25;
  scene.bodies[1].position.x() = 0.25;
  EXPECT_EQ(polygonPairs(hullContacts(scene)), 0);
}

// A shapeless body is a point mass whose pulley only guides the rope (the hooked square), and
// the hand's box and fingers are sensors that pass through each other: no pairs.
TEST(HullContacts, ShapelessBodiesAndTheHandTouchNothing) {
  EXPECT_TRUE(hullContacts(polygons("hooked_polygon")).empty());
  EXPECT_TRUE(hullContacts(makeScene("hand")).empty());
}

// The fixtures have no mass: each hexagon keeps the mass and inertia it has without the rope.
TEST(HullContacts, TheTouchingFixturesLeaveMassAndInertiaAlone) {
  const SceneDef scene = polygons("two_polygons_spinning");
  SceneDef bare = scene;
  bare.cables.clear();
  const World with(scene), without(bare);
  for (int b = 0; b < 2; ++b) {
    EXPECT_EQ(with.body(b).invMass, without.body(b).invMass);
    EXPECT_EQ(with.body(b).invInertia, without.body(b).invInertia);
    EXPECT_DOUBLE_EQ(with.body(b).invMass, 0.5);
  }
}

// A hexagon spool on a pivot winding a rope whose other end hangs a weight (its anchor at the
// weight's centre) over a point pulley on a free block; the rope is tied to the spool itself.
SceneDef spoolAndWeight(const Vec2& weightAt) {
  SceneDef s;
  BodyDef spool;
  spool.name = "spool";
  spool.position = Vec2(0, 3);
  spool.mass = 2;
  spool.shapes = {test::sensorPolygon(6, 0.2)};
  BodyDef block = test::hangingMass("block", Vec2(1, 3), 1);
  s.bodies = {spool, test::hangingMass("weight", weightAt, 1), block};
  s.joints = {test::worldPivot("spool", Vec2(0, 3))};
  CableDef rope;
  rope.name = "rope";
  rope.start.body = "weight";
  rope.end.body = "spool";
  rope.end.point = Vec2(0.2, 0);
  PulleyDef point;
  point.body = "block";
  PulleyDef polygon;
  polygon.kind = PulleyDef::Kind::Polygon;
  polygon.body = "spool";
  polygon.side = WrapSide::Right;
  rope.pulleys = {point, polygon};
  s.cables = {rope};
  return s;
}

// The weight's anchor and the block's point pulley touch the spool (each once, in its body's
// frame); the rope's end tied on the spool itself does not.
TEST(HullContacts, PointsOnOtherMovingBodiesTouchThePolygon) {
  const std::vector<HullContact> pairs = hullContacts(spoolAndWeight(Vec2(0.2, -1)));
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(polygonPairs(pairs), 0);
  EXPECT_EQ(pairs[0].body, 0);
  EXPECT_EQ(pairs[0].otherBody, 1);
  EXPECT_EQ(pairs[0].point, Vec2::Zero());
  EXPECT_EQ(pairs[1].otherBody, 2);
}

// A weight placed with its shape meeting the spool's hull (its anchor 5 cm outside it) passes
// through it by design, as the hand's box and fingers do: no pair. Nor for a shapeless weight.
TEST(HullContacts, APointWhoseBodyIsPlacedInTheHullOrHasNoShapeDoesNotTouchIt) {
  const std::vector<HullContact> overlapping = hullContacts(spoolAndWeight(Vec2(0, 2.78)));
  ASSERT_EQ(overlapping.size(), 1u);
  EXPECT_EQ(overlapping[0].otherBody, 2);
  SceneDef shapeless = spoolAndWeight(Vec2(0.2, -1));
  shapeless.bodies[1].shapes.clear();
  ASSERT_EQ(hullContacts(shapeless).size(), 1u);
  // A disc weight just clear of the hull (1 mm) touches it; one that reaches 1 mm in does not.
  for (const double gap : {1e-3, -1e-3}) {
    SceneDef disc = spoolAndWeight(Vec2(0, 3 - 0.2 * std::sqrt(3) / 2 - 0.1 - gap));
    disc.bodies[1].shapes = {test::sensorDisc(0.1)};
    EXPECT_EQ(hullContacts(disc).size(), gap > 0 ? 2u : 1u) << gap;
  }
}

}  // namespace hull_contacts_test
}  // namespace cablelab
