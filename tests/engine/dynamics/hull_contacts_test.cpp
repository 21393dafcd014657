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

}  // namespace hull_contacts_test
}  // namespace cablelab
