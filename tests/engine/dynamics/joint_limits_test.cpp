// Joint limits in the cable solve (joint_limits.h): a rope from an arm or a carriage that reaches
// its stop keeps its length, and the stop holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/dynamics/world.h"
#include "tests/support/engine_test_support.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace {

// `ropes` rigid ropes, each holding a 5 kg weight 1 m below the tip of a 1 m arm pivoted on the
// world (revolute, stopped at -0.5 rad), or below a 1 kg carriage on a rail down and to the right
// (prismatic, stopped 0.3 m along). Let go level, the arm swings down and hits its stop within
// 0.3 s; the carriage slides into its stop. Over 32 ropes the island takes the sparse path.
SceneDef limitedScene(JointDef::Kind kind, int ropes) {
  SceneDef s;
  s.name = "limited";
  BodyDef driver;
  driver.name = "driver";
  driver.mass = 1;
  driver.inertia = 1.0 / 12;
  driver.position = kind == JointDef::Kind::Revolute ? Vec2(0.5, 0) : Vec2::Zero();
  driver.shapes = {test::sensorBox(0.5, 0.03)};
  s.bodies = {driver};
  JointDef joint = test::worldPivot("driver", Vec2::Zero());
  joint.kind = kind;
  joint.axis = Vec2(0.6, -0.8);
  joint.enableLimit = true;
  joint.lower = kind == JointDef::Kind::Revolute ? -0.5 : -0.3;
  joint.upper = kind == JointDef::Kind::Revolute ? 0.5 : 0.3;
  s.joints = {joint};
  const Vec2 tip = kind == JointDef::Kind::Revolute ? Vec2(0.5, 0) : Vec2::Zero();
  for (int r = 0; r < ropes; ++r) {
    BodyDef weight;
    weight.name = "weight" + std::to_string(r);
    weight.mass = 5.0 / ropes;
    weight.fixedRotation = true;
    weight.position = driver.position + tip + Vec2(0.01 * r, -1);
    weight.shapes = {test::sensorBox(0.05, 0.05)};
    s.bodies.push_back(weight);
    CableDef rope;
    rope.name = "rope" + std::to_string(r);
    rope.start = {"driver", tip + Vec2(0.01 * r, 0)};
    rope.end = {weight.name, Vec2::Zero()};
    s.cables.push_back(rope);
  }
  return s;
}

struct LimitRun {
  double stretch = 0;   // the largest length - rest length of any rope (m; the arm falls ahead
                        // of its weight, and its rope goes slack)
  double furthest = 0;  // the joint's coordinate furthest from 0 (rad or m)
  int sparseSolves = 0;
};

LimitRun runLimited(JointDef::Kind kind, int ropes, int substeps) {
  World world(limitedScene(kind, ropes));
  LimitRun r;
  for (int step = 0; step < 300; ++step) {
    world.step(test::kDt, substeps);
    r.sparseSolves += world.lastStepStats().sparseIslands;
    for (int c = 0; c < world.cableCount(); ++c)
      r.stretch = std::max(r.stretch, world.cable(c).stretch());
    r.furthest = std::max(r.furthest, std::abs(world.joint(0).value));
  }
  return r;
}

TEST(JointLimits, RopesFromAnArmOrACarriageAtItsStopHoldTheirLength) {
  // With the limits free in the cable solve, the ropes stretched 323 / 61 mm (arm, 1 / 4
  // sub-steps; 496 / 62 mm with 40 ropes) and 84 / 16 mm (carriage), and the arm went 2% past its
  // stop. With locks: at most 2.2e-6 m, and the stops hold.
  for (const JointDef::Kind kind : {JointDef::Kind::Revolute, JointDef::Kind::Prismatic})
    for (const int ropes : {1, 40})
      for (const int substeps : {1, 4}) {
        const LimitRun r = runLimited(kind, ropes, substeps);
        const std::string what = std::string(kind == JointDef::Kind::Revolute ? "arm" : "rail") +
                                 ", " + std::to_string(ropes) + " ropes, " +
                                 std::to_string(substeps) + " sub-steps";
        EXPECT_LT(r.stretch, 1e-4) << what;
        const double stop = kind == JointDef::Kind::Revolute ? 0.5 : 0.3;
        EXPECT_NEAR(r.furthest, stop, 0.01 * stop) << what;  // it reaches its stop, no further
        if (ropes > 32) {
          EXPECT_GT(r.sparseSolves, 0) << what;
        }
      }
}

}  // namespace
}  // namespace cablelab
