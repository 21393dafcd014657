// A puck thrown at a rope whose far end hangs on an arm pivoted at (or beside) the rope's pulley:
// the arm is jointed, so the main solve takes the catch. At the join the puck has no share of
// the rope's J (theorem 1) and the pivot takes the arm's, so pulling along the start-of-step J
// needed unbounded impulses (1.4e24 N, the puck thrown back at 120 m/s from 20) or spun the arm
// up (236 rad/s, 13.5 kJ from a 200 J throw). Such a row pulls along J at the pose the free
// motion reaches, or gives a fast-joining point half its share there (cable_solver.cpp, stage
// 4b).
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "engine/dynamics/world.h"
#include "tests/support/engine_test_support.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace {

SceneDef pivotedArmCatch(double speed, double pivotOffset) {
  SceneDef s;
  s.name = "jointed catch";
  s.gravity = Vec2::Zero();
  BodyDef puck;
  puck.name = "puck";
  puck.mass = 1;
  puck.position = Vec2(0, -0.2);
  puck.velocity = Vec2(0, speed);
  puck.fixedRotation = true;
  puck.shapes = {test::sensorDisc(0.03)};
  BodyDef arm;
  arm.name = "arm";
  arm.mass = 1;
  arm.inertia = 1.0 / 12;
  arm.position = Vec2(1 + pivotOffset, -0.5);  // off the pulley's vertical: it can give rope
  arm.shapes = {test::sensorBox(0.03, 0.5)};
  s.bodies = {puck, arm};
  s.joints = {test::worldPivot("arm", Vec2(1 + pivotOffset, 0))};
  CableDef rope;
  rope.name = "rope";
  rope.start = {"world", Vec2(-1, 0)};
  PulleyDef onPuck;
  onPuck.body = "puck";
  onPuck.side = WrapSide::Left;
  PulleyDef fixed;
  fixed.point = Vec2(1, 0);
  fixed.side = WrapSide::Threaded;
  rope.pulleys = {onPuck, fixed};
  rope.end = {"arm", Vec2(0, -0.5)};
  s.cables = {rope};
  return s;
}

TEST(JointedCatch, APuckCaughtByARopeOnAPivotedArmGainsNoEnergy) {
  // Slow catches too where the arm has next to no say (1 m/s, pivot within 1 cm of the pulley:
  // 7.2 kJ and 4.6 J from 0.5 J before); 1 m/s with the pivot 10 cm away keeps J0 and gains 1.1%.
  std::vector<std::pair<double, double>> cases = {{0.0, 1.0}, {0.001, 1.0}, {0.01, 1.0}};
  for (const double offset : {0.0, 0.001, 0.01, 0.1, 0.3})
    for (const double speed : {5.0, 20.0, 50.0}) cases.push_back({offset, speed});
  for (const auto& [offset, speed] : cases) {
    SCOPED_TRACE("pivot " + std::to_string(offset) + " m beside the pulley, " +
                 std::to_string(speed) + " m/s");
    World world(pivotedArmCatch(speed, offset));
    const double thrown = world.energy();
    const double rest = world.cable(0).restLength();
    double highest = thrown, stretch = 0;
    bool engaged = false;
    for (int step = 0; step < 120; ++step) {
      world.step(test::kDt, 1);
      highest = std::max(highest, world.energy());
      stretch = std::max(stretch, world.cable(0).length() - rest);
      engaged |= world.cable(0).wraps() > 1;
    }
    EXPECT_TRUE(engaged);
    EXPECT_LE(highest, 1.01 * thrown) << highest / thrown;
    EXPECT_LT(stretch, 1e-2);
  }
}

}  // namespace
}  // namespace cablelab
