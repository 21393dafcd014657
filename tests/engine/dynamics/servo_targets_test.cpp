// Targets set between steps are reached over the step (docs/servos.md, "Targets set between
// steps"): the servo sees a target the user sets move on linearly across the step's sub-steps, so
// a ramp the user drives (set_servo_target each step) lifts a winch's weight the same at 1, 2, 4
// and 7 sub-steps. Set in one jump at the first sub-step, a servo stiff enough to follow it within
// that sub-step whipped a light drum through the whole jump and threw the weight (to the drum, at
// 8 m/s, at 20 Hz x 7, where the ramp asked 1.35 m/s of the rope).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

}  // namespace servo_targets_test
}  // namespace cablelab
