// A body that reaches a pulley stops there (docs/cables.md, "Floors").
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {
namespace {

TEST(Floors, PulleySceneNeverGainsEnergyAndKeepsItsLength) {
  // The built-in scene: the lighter box reaches its pulley after about 2.7 s and is held there.
  World world(makeScene("pulley"));
  const Cable& cable = world.cable(0);
  const double e0 = world.energy(), rest = cable.restLength();
  const int steps = static_cast<int>(std::lround(60.0 / world.scene().dt));
  double highest = e0, stretch = 0;
  for (int s = 0; s < steps; ++s) {
    world.step(world.scene().dt, world.scene().substeps);
    highest = std::max(highest, world.energy());
    stretch = std::max(stretch, std::abs(cable.length() - rest));
  }
  EXPECT_LT(highest, e0 + 0.01 * std::abs(e0));
  EXPECT_LT(stretch, 0.01);
  // Held at the pulley, at rest: the top of one box within a few cm of its pulley.
  double nearest = 1e9;
  for (int b = 0; b < 2; ++b) {
    const Vec2 top = world.body(b).position + Vec2(0, 2);
    nearest = std::min(nearest, (top - Vec2(b == 0 ? -10 : 10, 30)).norm());
  }
  EXPECT_LT(nearest, 0.05);
  EXPECT_LT(world.body(0).velocity.norm() + world.body(1).velocity.norm(), 0.05);
}

TEST(Floors, BodyThrownAtItsPulleyIsStoppedNotPassedThrough) {
  // The light box thrown up at 20 m/s: it stops at the pulley (energy goes, none comes).
  SceneDef scene = makeScene("pulley", {{"m_left", 1}, {"m_right", 3}});
  scene.bodies[0].velocity = Vec2(0, 20);
  scene.bodies[1].velocity = Vec2(0, -20);
  World world(scene);
  const double e0 = world.energy(), rest = world.cable(0).restLength();
  double highest = e0, stretch = 0, topY = -1e9;
  for (int s = 0; s < 300; ++s) {
    world.step(1.0 / 60, 1);
    highest = std::max(highest, world.energy());
    stretch = std::max(stretch, std::abs(world.cable(0).length() - rest));
    topY = std::max(topY, world.body(0).position.y() + 2);
  }
  EXPECT_LT(highest, e0 + 0.01 * std::abs(e0));
  EXPECT_LT(topY, 30.0);  // never above the pulley
  EXPECT_LT(stretch, 0.01);
}

// The same two boxes, each on a vertical rail (a prismatic joint to the world, as on a lift's
// guide): jointed bodies are moved by the main solve (the midpoint one leaves them alone), which
// then needs the floor too. Without it the light box goes through its pulley and the energy grows.
TEST(Floors, JointedBodyPulledIntoItsPulleyIsHeldThere) {
  for (const bool thrown : {false, true}) {
    SCOPED_TRACE(thrown ? "thrown up at 20 m/s" : "pulled up from rest");
    SceneDef scene = makeScene("pulley", {{"m_left", 1}, {"m_right", 3}});
    for (const BodyDef& b : std::vector<BodyDef>(scene.bodies)) {
      JointDef rail;
      rail.name = b.name + "_rail";
      rail.kind = JointDef::Kind::Prismatic;
      rail.bodyB = b.name;
      rail.anchor = b.position;
      rail.axis = Vec2(0, 1);
      scene.joints.push_back(rail);
    }
    if (thrown) {
      scene.bodies[0].velocity = Vec2(0, 20);
      scene.bodies[1].velocity = Vec2(0, -20);
    }
    World world(scene);
    const Cable& cable = world.cable(0);
    const double e0 = world.energy(), rest = cable.restLength();
    double highest = e0, stretch = 0, topY = -1e9;
    int midpointSolves = 0;
    for (int s = 0; s < 600; ++s) {
      world.step(1.0 / 60, 1);
      highest = std::max(highest, world.energy());
      stretch = std::max(stretch, std::abs(cable.length() - rest));
      topY = std::max(topY, world.body(0).position.y() + 2);
      midpointSolves += world.lastStepStats().midpointSolves;
    }
    EXPECT_EQ(midpointSolves, 0);  // the main solve took every step
    EXPECT_LT(highest, e0 + 0.01 * std::abs(e0));
    EXPECT_LT(stretch, 0.01);
    EXPECT_LT(topY, 30.0);  // never above the pulley
    // Held 1 cm under its pulley, at rest.
    EXPECT_NEAR(world.body(0).position.y() + 2, 30.0 - 0.01, 0.005);
    EXPECT_LT(world.body(0).velocity.norm() + world.body(1).velocity.norm(), 0.05);
  }
}

// The pulley scene over two round pulleys (radius 1, a quarter turn wound on each): the light box
// is hauled up along the tangent to the right wheel's rim. The floor is on the segment's length
// between its contact points (the tangent point), measured along its start direction. With no
// floor next to an arc (as before), or with one on the tangent length itself (which comes back
// up once the box is past the rim), the box reached the rim, rolled over it (the wheel left the
// path), and both boxes fell for ever. Free bodies (the midpoint solve) and bodies on rails (the
// main solve).
TEST(Floors, ABodyHauledUpToARoundPulleyIsHeldShortOfItsRim) {
  for (const bool rails : {false, true}) {
    SCOPED_TRACE(rails ? "on rails" : "free");
    SceneDef scene = makeScene("pulley");
    for (PulleyDef& p : scene.cables[0].pulleys) {
      p.kind = PulleyDef::Kind::Circle;
      p.radius = 1;
      p.side = WrapSide::Left;  // over the tops: walking from the left box the cable turns right
      p.turns = 0.25;
      p.point.x() += p.point.x() < 0 ? 1 : -1;  // the cable comes down at x = -10 and 10
    }
    if (rails)
      for (const BodyDef& b : std::vector<BodyDef>(scene.bodies)) {
        JointDef rail;
        rail.name = b.name + "_rail";
        rail.kind = JointDef::Kind::Prismatic;
        rail.bodyB = b.name;
        rail.anchor = b.position;
        rail.axis = Vec2(0, 1);
        scene.joints.push_back(rail);
      }
    World world(scene);
    const Cable& cable = world.cable(0);
    const double e0 = world.energy(), rest = cable.restLength();
    double highest = e0, stretch = 0;
    for (int s = 0; s < 1200; ++s) {  // 20 s: the box reaches the rim after about 2.7 s
      world.step(scene.dt, scene.substeps);
      highest = std::max(highest, world.energy());
      stretch = std::max(stretch, std::abs(cable.length() - rest));
    }
    EXPECT_LT(highest, e0 + 0.01 * std::abs(e0));
    EXPECT_LT(stretch, 0.01);
    ASSERT_EQ(cable.wraps(), 2);  // both wheels still in the path
    const WrapPoint& wheel = cable.path()[2];
    const WrapPoint& box = cable.path()[3];
    EXPECT_NEAR((box.world - wheel.tangentOut).norm(), 0.01, 0.005);  // the segment held at 1 cm
    EXPECT_NEAR(world.body(1).position.y() + 2, 30.0 - 0.01, 0.005);
    EXPECT_LT(world.body(0).velocity.norm() + world.body(1).velocity.norm(), 0.05);
    EXPECT_TRUE(world.warnings().empty()) << world.warnings().front();
  }
}

}  // namespace
}  // namespace cablelab
