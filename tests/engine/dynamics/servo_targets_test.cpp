// Targets set between steps are reached over the step (docs/servos.md, "Targets set between
// steps"): the servo sees a target the user sets move on linearly across the step's sub-steps, so
// a ramp the user drives (set_servo_target each step) lifts a winch's weight the same at 1, 2, 4
// and 7 sub-steps. Set in one jump at the first sub-step, a servo stiff enough to follow it within
// that sub-step whipped a light drum through the whole jump and threw the weight (to the drum, at
// 8 m/s, at 20 Hz x 7, where the ramp asked 1.35 m/s of the rope).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {
namespace servo_targets_test {

constexpr double kG = 9.81;
constexpr double kEndTolerance = 0.01;   // m: where the weight ends, against the target's place
constexpr double kRiseTolerance = 0.01;  // m: past the target and a free flight at the rope's speed

struct RampCase {
  double drumInertia, weight, r, kp, critical;  // kd = critical x 2 sqrt(kp (I + m r^2))
  double hz, rimSpeed;                          // the ramp, at the rope (m/s)
  double lift = 1.0;                            // m
};

struct Lift {
  double highest, end;  // the weight's rise over its start (m): the most, and at the end
};

Lift rampedLift(const RampCase& k, int substeps) {
  SceneDef s = makeScene("winch", {{"r", k.r}, {"omega", 0.0}, {"mass", k.weight}});
  s.bodies[0].inertia = k.drumInertia;
  ServoDef& servo = s.joints[0].servo;
  servo.kp = k.kp;
  servo.kd = k.critical * 2 * std::sqrt(k.kp * (k.drumInertia + k.weight * k.r * k.r));
  World w(s, "winch");
  const double dt = 1 / k.hz, y0 = w.body(1).position.y(), q0 = w.joint(0).value;
  const double turn = k.lift / k.r, rate = k.rimSpeed / k.r;
  Lift lift{0, 0};
  for (int n = 0; n * dt < turn / rate + 2.5; ++n) {
    w.setServoTarget(0, q0 + std::min(turn, rate * (n + 1) * dt));
    w.step(dt, substeps);
    lift.highest = std::max(lift.highest, w.body(1).position.y() - y0);
  }
  lift.end = w.body(1).position.y() - y0;
  return lift;
}

TEST(ServoTargets, ARampedWinchLiftsTheSameAtAnySubstepCount) {
  // Light and heavy drums, light and heavy weights, stiff servos at 0.5 to 2 times critical
  // damping, 20 to 120 Hz, the rope wound at 0.5 to 1.5 m/s; the first is the audit's.
  const RampCase cases[] = {
      {1.89e-3, 1.574, 0.179, 25962, 0.61, 20, 1.35},
      {1e-4, 0.5, 0.1, 1e5, 1.0, 30, 1.0},
      {1e-3, 2.0, 0.05, 2e4, 0.5, 60, 0.8},
      {0.01, 1.0, 0.15, 5e3, 1.0, 20, 1.2},
      {3e-4, 5.0, 0.1, 5e4, 0.7, 45, 1.5},
      {0.1, 1.0, 0.2, 1e4, 1.0, 30, 1.0},
      {1e-4, 0.2, 0.08, 2000, 1.0, 120, 0.5},
      {2e-3, 3.0, 0.12, 1e5, 2.0, 20, 1.3},
  };
  for (const RampCase& k : cases) {
    SCOPED_TRACE("I " + std::to_string(k.drumInertia) + " m " + std::to_string(k.weight) + " kp " +
                 std::to_string(k.kp) + " at " + std::to_string(k.hz) + " Hz");
    // At rest the servo gives way under the weight by m g r / kp of turn: m g r^2 / kp of rope.
    const double target = k.lift - k.weight * kG * k.r * k.r / k.kp;
    // Once the drum stops, the weight may fly on at the rope's speed (the rope only pulls).
    const double flight = k.rimSpeed * k.rimSpeed / (2 * kG);
    const Lift one = rampedLift(k, 1);
    for (int substeps : {1, 2, 4, 7}) {
      SCOPED_TRACE(std::to_string(substeps) + " sub-steps");
      const Lift l = substeps == 1 ? one : rampedLift(k, substeps);
      EXPECT_LE(l.highest, target + flight + kRiseTolerance);
      EXPECT_NEAR(l.end, target, kEndTolerance);
      EXPECT_NEAR(l.end, one.end, kEndTolerance);
    }
  }
}

// A target written in the scene file that differs from where its joint starts is a step at t = 0,
// reached over the first step as one set before it: to the bit the run of the same scene whose
// target the user sets before its first step. In one jump at the first sub-step, a stiff servo
// reached it within that sub-step, n sub-steps throwing the weight about n times as fast as one.
std::unique_ptr<World> steppedWinch(const RampCase& k, bool inSceneFile) {
  SceneDef s = makeScene("winch", {{"r", k.r}, {"omega", 0.0}, {"mass", k.weight}});
  s.bodies[0].inertia = k.drumInertia;
  ServoDef& servo = s.joints[0].servo;
  servo.kp = k.kp;
  servo.kd = k.critical * 2 * std::sqrt(k.kp * (k.drumInertia + k.weight * k.r * k.r));
  servo.maxForce = k.rimSpeed * k.weight * kG * k.r;  // here: max_force in m g r
  if (inSceneFile) servo.target = k.lift / k.r;
  auto w = std::make_unique<World>(s, "winch");
  if (!inSceneFile) w->setServoTarget(0, k.lift / k.r);
  return w;
}

TEST(ServoTargets, AStepInTheSceneFileIsReachedOverTheFirstStep) {
  // Stiff and soft servos, max_force from 1.5 m g r to far above (the default's 1e4 N m), kd 0
  // to 2 times critical, 20 to 240 Hz, light and heavy drums; the lift 0.3 to 0.8 m.
  const RampCase cases[] = {
      {1e-4, 0.5, 0.1, 1e5, 1.0, 30, 1e4, 0.5},   {1e-3, 2.0, 0.05, 2e4, 0.5, 60, 3.0, 0.6},
      {0.01, 1.0, 0.15, 5e3, 1.0, 20, 1e4, 0.3},  {3e-4, 5.0, 0.1, 5e4, 0.0, 45, 2.0, 0.4},
      {0.1, 1.0, 0.2, 1e4, 2.0, 30, 1.5, 0.8},    {1e-4, 0.2, 0.08, 2000, 1.0, 120, 1e4, 0.5},
      {2e-3, 3.0, 0.12, 1e5, 0.5, 240, 5.0, 0.7}, {6.8e-3, 2.1, 0.059, 404, 2.0, 20, 2.6, 0.78},
  };
  for (const RampCase& k : cases)
    for (int substeps : {2, 4, 7}) {
      SCOPED_TRACE("I " + std::to_string(k.drumInertia) + " kp " + std::to_string(k.kp) + " at " +
                   std::to_string(k.hz) + " Hz x " + std::to_string(substeps));
      const auto file = steppedWinch(k, true), set = steppedWinch(k, false);
      double worst = 0;
      for (int n = 0; n / k.hz < 1.5; ++n) {
        file->step(1 / k.hz, substeps);
        set->step(1 / k.hz, substeps);
        worst = std::max(worst, std::abs(file->body(1).position.y() - set->body(1).position.y()));
        worst = std::max(worst, std::abs(file->joint(0).value - set->joint(0).value));
      }
      EXPECT_EQ(worst, 0.0);
    }
}

}  // namespace servo_targets_test
}  // namespace cablelab
