// Driven bodies (issue 11, item 4): kinematic bodies move with their prescribed velocity during
// the step, and the cable solve must see that motion, or a rope lifted at v stretches by about
// v h / Baumgarte share every step.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/dynamics/world.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

using test::kDt;
constexpr double kLift = 5.0;      // m/s
constexpr double kStretch = 1e-4;  // m: the goal bound

BodyDef weight(const Vec2& position) {
  BodyDef b;
  b.name = "weight";
  b.mass = 10;
  b.position = position;
  b.velocity = Vec2(0, kLift);  // already lifting: the test is the steady lift, not the jerk
  ShapeDef s;
  s.radius = 0.2;
  s.sensor = true;
  b.shapes = {s};
  return b;
}

BodyDef crane(BodyType type) {
  BodyDef b;
  b.name = "crane";
  b.type = type;
  b.position = Vec2(0, 0);
  b.velocity = Vec2(0, type == BodyType::Kinematic ? kLift : 0);
  ShapeDef s;
  s.radius = 0.1;
  s.sensor = true;
  b.shapes = {s};
  return b;
}

CableDef rope(const std::string& from) {
  CableDef c;
  c.name = "rope";
  c.start = {from, Vec2(0, 0)};
  c.end = {"weight", Vec2(0, 0)};
  return c;
}

double maxStretch(World& world, int steps, int substeps = 1) {
  double worst = 0;
  for (int s = 0; s < steps; ++s) {
    world.step(kDt, substeps);
    worst = std::max(worst, world.cable(0).stretch());  // a rope may go slack, never longer
  }
  return worst;
}

TEST(DrivenBodies, AKinematicCraneLiftsWithoutStretchingTheRope) {
  for (int substeps : {1, 4}) {
    SceneDef s;
    s.bodies = {crane(BodyType::Kinematic), weight(Vec2(0, -3))};
    s.cables = {rope("crane")};
    World world(s);
    EXPECT_LT(maxStretch(world, 120, substeps), kStretch) << substeps << " sub-steps";
    EXPECT_NEAR(world.body(1).velocity.y(), kLift, 1e-3);
    EXPECT_NEAR(world.body(0).position.y() - world.body(1).position.y(), 3, kStretch);
  }
}

TEST(DrivenBodies, AHookPinnedToAKinematicTrolleyLiftsWithoutStretchingTheRope) {
  // The rope hangs from a dynamic hook pinned (revolute) to the kinematic trolley: the joint rows
  // carry the trolley's prescribed velocity into the solve.
  SceneDef s;
  BodyDef hook;
  hook.name = "hook";
  hook.mass = 0.5;
  hook.position = Vec2(0, -0.5);
  hook.velocity = Vec2(0, kLift);
  ShapeDef shape;
  shape.radius = 0.1;
  shape.sensor = true;
  hook.shapes = {shape};
  s.bodies = {crane(BodyType::Kinematic), hook, weight(Vec2(0, -3.5))};
  JointDef pin;
  pin.name = "pin";
  pin.bodyA = "crane";
  pin.bodyB = "hook";
  pin.anchor = Vec2(0, 0);
  s.joints = {pin};
  s.cables = {rope("hook")};
  World world(s);
  EXPECT_LT(maxStretch(world, 120), kStretch);
  EXPECT_NEAR(world.body(2).velocity.y(), kLift, 1e-2);
}

TEST(DrivenBodies, AServoDrivenCarriageLiftsWithoutStretchingTheRope) {
  // A prismatic carriage on a vertical rail whose servo target climbs at 5 m/s: the servo's
  // force is a load the solve sees, so the rope follows the carriage exactly. (The servo is an
  // explicit PD force: gains with kd h / m = 0.5 keep it stable.)
  SceneDef s;
  BodyDef carriage = crane(BodyType::Dynamic);
  carriage.mass = 20;
  carriage.velocity = Vec2(0, kLift);
  s.bodies = {carriage, weight(Vec2(0, -3))};
  JointDef rail;
  rail.kind = JointDef::Kind::Prismatic;
  rail.name = "rail";
  rail.bodyB = "crane";
  rail.axis = Vec2(0, 1);
  rail.servo.enabled = true;
  rail.servo.kp = 4000;
  rail.servo.kd = 600;
  rail.servo.maxForce = 1e5;
  s.joints = {rail};
  s.cables = {rope("crane")};
  World world(s);
  double worst = 0;
  for (int i = 0; i < 120; ++i) {
    world.setServoTarget(0, kLift * (i + 1) * kDt);
    world.step(kDt);
    worst = std::max(worst, world.cable(0).stretch());
  }
  EXPECT_LT(worst, kStretch);
  EXPECT_GT(world.cable(0).tension(), 0);  // taut at the end: lifting, not just released
  EXPECT_NEAR(world.body(1).velocity.y(), world.body(0).velocity.y(), 1e-2);
}

}  // namespace
}  // namespace cablelab
