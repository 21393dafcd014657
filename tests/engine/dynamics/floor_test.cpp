// A body that reaches a pulley stops there (docs/cables.md, "Floors").
#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace cablelab
