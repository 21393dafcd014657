// How soon a winch that winds on after its weight has reached the drum stalls (docs/servos.md,
// "Stalls"): its force reaches max_force, a warning names the joint, and the rope then holds
// max_force / r. The drum is held by the cable's floor at the rim, which the servo's prediction
// does not see; two steps later the servo predicts its joint held (docs/servos.md, "Held joints"),
// so the force rises at kp |speed| as against a rigid stop and the stall comes within
// max_force / (kp |speed|) + 0.2 s of the arrival. Before the hold it rose at
// kp |speed| / (1 + h c / m): 38 s on a light drum at a coarse step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {
namespace winch_stall_time_test {

struct StallCase {
  double drumInertia, kp, kd, maxForce, hz;
  int substeps;
  double r = 0.1, weight = 1.0, omega = 5.0;
};

// The goal's margin over max_force / (kp |speed|): the two steps that find the hold, and the
// arrival's own steps (docs/servos.md, "Held joints").
constexpr double kStallMargin = 0.2;  // s

void expectStallInTime(const StallCase& k) {
  SceneDef s = makeScene("winch", {{"r", k.r}, {"omega", k.omega}, {"mass", k.weight}});
  s.bodies[0].inertia = k.drumInertia;
  s.joints[0].servo.kp = k.kp;
  s.joints[0].servo.kd = k.kd;
  s.joints[0].servo.maxForce = k.maxForce;
  World w(s, "winch");
  const double bound = k.maxForce / (k.kp * std::abs(k.omega)) + kStallMargin;
  double arrived = -1, stalledAt = -1, worstAfter = 0;
  while (w.time() < 30 && (stalledAt < 0 || w.time() < stalledAt + 1)) {
    w.step(1 / k.hz, k.substeps);
    // Arrival: the drum, winding at omega, stopped by the weight at its rim.
    if (arrived < 0 && w.time() > 1 && std::abs(w.joint(0).speed) < 0.5 * std::abs(k.omega))
      arrived = w.time();
    if (stalledAt < 0 && !w.warnings().empty() &&
        w.warnings().back().find("stalled") != std::string::npos)
      stalledAt = w.time();
    // The arrival's first steps stop the drum's turn through the rope (its momentum, not the
    // servo's force): the bound holds from 0.1 s on.
    if (arrived >= 0 && w.time() > arrived + 0.1)
      worstAfter = std::max(worstAfter, w.cable(0).tension());
    ASSERT_LE(std::abs(w.joint(0).force), k.maxForce * (1 + 1e-12));
  }
  SCOPED_TRACE("I " + std::to_string(k.drumInertia) + " kp " + std::to_string(k.kp) + " kd " +
               std::to_string(k.kd) + " max " + std::to_string(k.maxForce) + " at " +
               std::to_string(k.hz) + " Hz x " + std::to_string(k.substeps));
  ASSERT_GT(arrived, 0);
  ASSERT_GT(stalledAt, 0);
  EXPECT_LE(stalledAt - arrived, bound) << "bound " << bound << " s";
  // The weight's arrival at the drum is said first, then the stall.
  ASSERT_EQ(w.warnings().size(), 2u);
  EXPECT_EQ(w.warnings()[0].find("cable 'cable': the weight 'weight' reached the drum 'drum'"), 0u)
      << w.warnings()[0];
  EXPECT_EQ(w.warnings()[1].find("joint 'axle'"), 0u) << w.warnings()[1];
  EXPECT_NEAR(std::abs(w.joint(0).force), k.maxForce, 1e-9 * k.maxForce);
  EXPECT_LE(worstAfter, k.maxForce / k.r * (1 + 1e-6));
}

TEST(WinchStallTime, AWinchWindingOnAtItsDrumStallsWithinTheDocumentedTime) {
  // Light and heavy drums (1e-3 and 0.1 kg m^2, 1 kg at r = 0.1 m), soft and stiff servos with
  // kd near critical on drum and weight, or well below, 30 to 240 Hz at 1 and 4 sub-steps.
  const double r = 0.1, weight = 1.0;
  const StallCase cases[] = {
      {1e-3, 2e4, 2 * std::sqrt(2e4 * (1e-3 + weight * r * r)), 20, 60, 1},
      {1e-3, 500, 44.72, 20, 120, 4},
      {1e-3, 5e3, 5, 5, 240, 1},
      {0.1, 2000, 2 * std::sqrt(2000 * (0.1 + weight * r * r)), 20, 30, 4},
      {0.1, 1e4, 20, 5, 60, 4},
  };
  for (const StallCase& k : cases) expectStallInTime(k);
}

TEST(WinchStallTime, ALightDrumAtACoarseStepStallsAtOnce) {
  // h c / m = 102: the force rose at kp |speed| / 103 before the hold, and the stall came 38 s
  // after the arrival; kd |speed| = 216 N m is above max_force, so a held drum stalls at once.
  expectStallInTime({1.4e-3, 132, 53.9, 200, 30, 4, 0.05, 1.24, 4});
  // Other drums, weights, gains and steps where h c / m is large (h c / m 770 and 40).
  expectStallInTime({3e-4, 2e3, 3e3, 200, 60, 4, 0.2, 0.4, 2.5});
  expectStallInTime({1e-3, 50, 100, 30, 120, 1, 0.1, 2.0, 4});
}

}  // namespace winch_stall_time_test
}  // namespace cablelab
