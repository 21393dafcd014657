// A winch's rope pulls at most (max_force + I |alpha|) / r (docs/servos.md, "Tension and the drum's
// inertia"): the drum's own inertia I adds to its servo's torque wherever the rope slows it or
// turns it back, as a light drum does when its rope catches a weight the servo threw up. Each step
// keeps the drum's balance, I dw/dt = f - T r, so a step's tension passes max_force / r exactly by
// the drum's I |dw/dt| / r, and by nothing more (the audit's 19.84 N = 1.16 max_force / r at 480
// Hz).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {
namespace winch_catch_tension_test {

constexpr double kG = 9.81;
// Of max_force (N m): Box2D keeps the drum's rate in single precision, so I dw/dt carries ~1e-7.
constexpr double kBalanceTolerance = 1e-5;
constexpr double kBoundTolerance = 1e-5;

struct ThrowCase {
  double drumInertia, weight, r, kp, hz;
  int substeps;
  double maxForce;  // in m g r
  double rimSpeed;  // the ramp, at the rope (m/s)
};

struct Catch {
  double worstBalance = 0;  // |I dw/dt - (f - T r)| / max_force, the largest
  double worstBound = 0;    // (T r - max_force - I |dw/dt|) / max_force, the largest
  double peak = 0;          // the largest T r / max_force
};

Catch throwAndCatch(const ThrowCase& k) {
  SceneDef s = makeScene("winch", {{"r", k.r}, {"omega", 0.0}, {"mass", k.weight}});
  s.bodies[0].inertia = k.drumInertia;
  ServoDef& servo = s.joints[0].servo;
  servo.kp = k.kp;
  servo.kd = 2 * std::sqrt(k.kp * (k.drumInertia + k.weight * k.r * k.r));
  servo.maxForce = k.maxForce * k.weight * kG * k.r;
  World w(s, "winch");
  const double dt = 1 / k.hz, lift = 0.4 / k.r, rate = k.rimSpeed / k.r;
  Catch c;
  double rate0 = w.joint(0).speed;
  for (int n = 0; n * dt < lift / rate + 2.0; ++n) {
    w.setServoTarget(0, std::min(lift, rate * (n + 1) * dt));
    w.step(dt, k.substeps);
    const double f = w.joint(0).force, tr = w.cable(0).tension() * k.r;
    const double inertial = k.drumInertia * (w.joint(0).speed - rate0) / dt;
    rate0 = w.joint(0).speed;
    c.worstBalance = std::max(c.worstBalance, std::abs(inertial - (f - tr)) / servo.maxForce);
    c.worstBound =
        std::max(c.worstBound, (tr - servo.maxForce - std::abs(inertial)) / servo.maxForce);
    c.peak = std::max(c.peak, tr / servo.maxForce);
  }
  return c;
}

TEST(WinchCatchTension, TheRopePassesMaxForceOverROnlyByTheDrumsInertia) {
  // Light drums (I from 0.004 to 0.2 m r^2) whose servo, at 1.5 to 6 m g r, throws the weight up
  // on a fast ramp and catches it; 60 to 480 Hz, 1 and 4 sub-steps. The first is the audit's.
  const ThrowCase cases[] = {
      {7.09e-5, 0.239, 0.0836, 7201, 480, 1, 6.2, 0.83},
      {1e-4, 0.5, 0.1, 2e4, 240, 1, 3.0, 1.2},
      {1e-4, 0.5, 0.1, 2e4, 60, 4, 3.0, 1.2},
      {4e-4, 2.0, 0.05, 5e4, 120, 1, 2.0, 1.0},
      {4e-4, 2.0, 0.05, 5e4, 120, 4, 2.0, 1.0},
      {2e-3, 1.0, 0.15, 1e4, 480, 1, 4.0, 1.4},
      {1e-3, 4.0, 0.12, 3e4, 240, 4, 1.5, 0.8},
      {5e-5, 0.3, 0.08, 5e3, 90, 1, 6.0, 1.5},
  };
  int caught = 0;  // cases whose catch passed max_force / r
  for (const ThrowCase& k : cases) {
    SCOPED_TRACE("I " + std::to_string(k.drumInertia) + " m " + std::to_string(k.weight) + " at " +
                 std::to_string(k.hz) + " Hz x " + std::to_string(k.substeps));
    const Catch c = throwAndCatch(k);
    EXPECT_LE(c.worstBalance, kBalanceTolerance);
    EXPECT_LE(c.worstBound, kBoundTolerance);
    caught += c.peak > 1 + kBoundTolerance;
  }
  // The bound is met with the drum's inertia, not because no catch pulled harder than max_force.
  EXPECT_GE(caught, 1);
}

}  // namespace winch_catch_tension_test
}  // namespace cablelab
