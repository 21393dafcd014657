// How soon a winch that winds on after its weight has reached the drum stalls (docs/servos.md,
// "Stalls"): its force reaches max_force, a warning names the joint, and the rope then holds
// max_force / r. The drum is held by the cable's floor at the rim, which the servo's prediction
// does not see, so the force rises at kp |speed| / (1 + h c / m) (m the drum's and weight's
// inertia at the axle, c = kp h + kd): the stall comes within max_force (1 + h c / m) /
// (kp |speed|) of the arrival, a few steps more.
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
};

TEST(WinchStallTime, AWinchWindingOnAtItsDrumStallsWithinTheDocumentedTime) {
  // Light and heavy drums (1e-3 and 0.1 kg m^2, 1 kg at r = 0.1 m), soft and stiff servos with
  // kd near critical on drum and weight, or well below, 30 to 240 Hz at 1 and 4 sub-steps.
  const double r = 0.1, weight = 1.0, omega = 5.0;
  const StallCase cases[] = {
      {1e-3, 2e4, 2 * std::sqrt(2e4 * (1e-3 + weight * r * r)), 20, 60, 1},
      {1e-3, 500, 44.72, 20, 120, 4},
      {1e-3, 5e3, 5, 5, 240, 1},
      {0.1, 2000, 2 * std::sqrt(2000 * (0.1 + weight * r * r)), 20, 30, 4},
      {0.1, 1e4, 20, 5, 60, 4},
  };
  for (const StallCase& k : cases) {
    SceneDef s = makeScene("winch", {{"r", r}, {"omega", omega}, {"mass", weight}});
    s.bodies[0].inertia = k.drumInertia;
    s.joints[0].servo.kp = k.kp;
    s.joints[0].servo.kd = k.kd;
    s.joints[0].servo.maxForce = k.maxForce;
    World w(s, "winch");
    const double h = 1 / (k.hz * k.substeps), c = k.kp * h + k.kd;
    const double m = k.drumInertia + weight * r * r;
    const double bound = k.maxForce * (1 + h * c / m) / (k.kp * omega);
    double arrived = -1, stalledAt = -1, worstAfter = 0;
    while (w.time() < 30 && (stalledAt < 0 || w.time() < stalledAt + 1)) {
      w.step(1 / k.hz, k.substeps);
      // Arrival: the drum, winding at omega, stopped by the weight at its rim.
      if (arrived < 0 && w.time() > 1 && std::abs(w.joint(0).speed) < 0.5 * omega)
        arrived = w.time();
      if (stalledAt < 0 && !w.warnings().empty()) stalledAt = w.time();
      // The arrival's own step stops the drum's turn through the rope (its momentum, not the
      // servo's force): the bound holds from the next step.
      if (arrived >= 0 && w.time() > arrived + 1.5 / k.hz)
        worstAfter = std::max(worstAfter, w.cable(0).tension());
      ASSERT_LE(std::abs(w.joint(0).force), k.maxForce * (1 + 1e-12));
    }
    SCOPED_TRACE("I " + std::to_string(k.drumInertia) + " kp " + std::to_string(k.kp) + " kd " +
                 std::to_string(k.kd) + " max " + std::to_string(k.maxForce) + " at " +
                 std::to_string(k.hz) + " Hz x " + std::to_string(k.substeps));
    ASSERT_GT(arrived, 0);
    ASSERT_GT(stalledAt, 0);
    EXPECT_LE(stalledAt - arrived, 1.5 * bound + 4 / k.hz) << "bound " << bound << " s";
    ASSERT_EQ(w.warnings().size(), 1u);
    EXPECT_EQ(w.warnings()[0].find("joint 'axle'"), 0u) << w.warnings()[0];
    EXPECT_NEAR(w.joint(0).force, k.maxForce, 1e-9 * k.maxForce);
    EXPECT_LE(worstAfter, k.maxForce / r * (1 + 1e-6));
  }
}

}  // namespace winch_stall_time_test
}  // namespace cablelab
