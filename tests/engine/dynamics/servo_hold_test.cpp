// Held joints (engine/dynamics/servo_drive.cpp, docs/servos.md "Held joints"): a servo whose joint
// a load its prediction does not see (here a contact) has stopped predicts the joint held, one
// way, and so pushes with its PD law, kp (target - q), where before it pushed with
// kp (target - q) / (1 + h c / m); a held servo the hold no longer pushes against lets go at once.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/dynamics/world.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace servo_hold_test {

constexpr double kLawTolerance = 1e-6;  // of kp (target - q): what the hold's rounding leaves

ShapeDef solidBox(double hx, double hy) {
  ShapeDef box = test::sensorBox(hx, hy);
  box.sensor = false;
  return box;
}

// A 1 m rod pinned at the origin along +x, no gravity unless asked, and a static block at 0.55 rad
// 0.8 m out: the rod turns into it at about 0.42 rad and stops there.
SceneDef pressScene(double mass, double kp, double kd, double target, const Vec2& gravity) {
  SceneDef s;
  s.gravity = gravity;
  BodyDef rod;
  rod.name = "rod";
  rod.position = Vec2(0.5, 0);
  rod.mass = mass;
  rod.inertia = mass / 12;
  rod.shapes = {solidBox(0.5, 0.02)};
  BodyDef block;
  block.name = "block";
  block.type = BodyType::Static;
  block.position = 0.8 * Vec2(std::cos(0.55), std::sin(0.55));
  block.shapes = {solidBox(0.05, 0.05)};
  s.bodies = {rod, block};
  JointDef pin;
  pin.name = "pin";
  pin.bodyB = "rod";
  pin.servo.enabled = true;
  pin.servo.kp = kp;
  pin.servo.kd = kd;
  pin.servo.target = target;
  s.joints = {pin};
  return s;
}

struct PressCase {
  double mass, kp, kd, hz;
  int substeps;
};

TEST(ServoHold, ARodPressedAgainstABlockPushesWithItsPdLaw) {
  // h c / m from 0.4 to 6.7 (m the rod's inertia at the pin): before the hold the force at rest
  // was kp (target - q) / (1 + h c / m).
  const PressCase cases[] = {{1.0, 500, 44.72, 60, 1},
                             {0.1, 2e3, 10, 30, 4},
                             {3.0, 100, 300, 240, 1},
                             {0.3, 1e4, 0, 120, 4}};
  for (const PressCase& k : cases) {
    World w(pressScene(k.mass, k.kp, k.kd, 1.0, Vec2::Zero()));
    for (int i = 0; i < 3 * k.hz; ++i) w.step(1 / k.hz, k.substeps);
    const JointState pin = w.joint(0);
    SCOPED_TRACE("mass " + std::to_string(k.mass) + " kp " + std::to_string(k.kp) + " at " +
                 std::to_string(k.hz) + " Hz x " + std::to_string(k.substeps));
    ASSERT_LT(pin.value, 0.5);  // the block stopped it
    ASSERT_LT(std::abs(pin.speed), 1e-3);
    const double law = k.kp * (1.0 - pin.value) - k.kd * pin.speed;
    EXPECT_NEAR(pin.force, law, kLawTolerance * law);
    EXPECT_TRUE(w.warnings().empty());
  }
}

// The force of the step after `change` on a world held against the block, and on the same world
// moved to where it already is (which forgets the hold): a released hold leaves nothing behind.
void expectReleasedLikeUnheld(const Vec2& gravity, double mass, double newTarget) {
  const double hz = 60;
  World held(pressScene(mass, 500, 44.72, 1.0, gravity));
  for (int i = 0; i < 3 * hz; ++i) held.step(1 / hz);
  ASSERT_LT(std::abs(held.joint(0).speed), 1e-3);
  World twin(pressScene(mass, 500, 44.72, 1.0, gravity));
  for (int i = 0; i < 3 * hz; ++i) twin.step(1 / hz);
  const BodyState rod = twin.body(0);
  twin.setBodyTransform(0, rod.position, rod.angle);  // no motion: the hold is forgotten
  for (World* w : {&held, &twin}) {
    w->setServoTarget(0, newTarget);
    w->step(1 / hz);
  }
  EXPECT_NE(held.joint(0).force, 0.0);
  EXPECT_EQ(held.joint(0).force, twin.joint(0).force);
  EXPECT_EQ(held.joint(0).value, twin.joint(0).value);
}

TEST(ServoHold, AHeldServoWhoseTargetMovesBehindItLetsGo) {
  // The held prediction's force would pull away from the block: the servo's force is the one of
  // a servo never held, to the bit.
  expectReleasedLikeUnheld(Vec2::Zero(), 1.0, 0.2);
  expectReleasedLikeUnheld(Vec2::Zero(), 0.2, -1.0);
}

TEST(ServoHold, AHeldServoThatGravityOutweighsLetsGo) {
  // Gravity along -y pulls the rod off the block with 0.5 m g cos(q) = 2.2 N m; the servo still
  // pushes into it, with 500 (0.43 - q) < 2.2 N m: the hold's row would have to pull.
  expectReleasedLikeUnheld(Vec2(0, -9.81), 0.5, 0.425);
}

}  // namespace servo_hold_test
}  // namespace cablelab
