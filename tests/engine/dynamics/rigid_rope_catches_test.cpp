// A weight on a rigid rope over a polygon spinning on its pivot: the corners flick the rope, the
// weight flies up off it and the rope catches it again. A rigid catch from slack is a plastic
// impact (docs/knocks.md, "Rigid tethers: whirls and catches"), and these catches are where the
// random busy scenes' rigid ropes lose their energy (docs/knocks.md, "Caught over a spinning
// hexagon"): every other step of one solve keeps it, save where the main solve takes a
// stiff island (30 Hz at -7 rad/s).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/dynamics/world.h"
#include "tests/support/energy_drift.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace {

// Seed 2 of the issue 36 sweep's hexagon part (busy_conservative.json mutated), on its own: a
// 0.5 m hexagon of 3.5 kg spinning at `spin` rad/s on its pivot, a rigid rope from a world point
// up to its left round it to a weight of `mass` hanging 1 m below its right side.
SceneDef weightOnARigidRopeOverASpinningHexagon(double mass, double spin) {
  return test::ropeOverASpinningHexagon(3.5, 5.0 / 12 * 3.5 * 0.25, spin, Vec2(-1.5, 0.8),
                                        Vec2(0.9, -1.0), mass);  // a regular hexagon's inertia
}

struct CatchRun {
  int catches = 0;        // steps that start with the rope slack by more than kSlack
  double worstHeld = 0;   // largest |E change| / scale of a step, taut at its start, of one solve
  double heldSum = 0;     // the sum of those changes / scale
  double worstGain = 0;   // largest E gain of any step / scale
  double caughtLoss = 0;  // energy lost in the steps that start slack / scale
  double totalLoss = 0;   // E0 - E at the end / scale
};

constexpr double kSlack = 1e-5;  // m: kLengthSlop (length_targets.h)

CatchRun run(double mass, double spin, int hz, double seconds) {
  World world(weightOnARigidRopeOverASpinningHexagon(mass, spin));
  const Cable& rope = world.cable(0);
  const double e0 = world.energy();
  double before = e0, scale = 0, held = 0, worstHeld = 0, worstGain = 0, caught = 0;
  int catches = 0;
  for (int s = 0; s < static_cast<int>(seconds * hz); ++s) {
    const bool slack = rope.length() < rope.restLength() - kSlack;
    world.step(1.0 / hz, 1);
    const double e = world.energy(), change = e - before;
    scale = std::max(scale, test::kineticEnergy(world));
    worstGain = std::max(worstGain, change);
    if (slack) {
      ++catches;
      caught -= change;
    } else if (world.lastStepStats().events == 0) {  // one solve, the rope taut at its start
      worstHeld = std::max(worstHeld, std::abs(change));
      held += change;
    }
    before = e;
  }
  return {catches,           worstHeld / scale, held / scale,
          worstGain / scale, caught / scale,    (e0 - before) / scale};
}

TEST(RigidRopeCatches, AWeightFlickedByASpinningHexagonLosesEnergyOnlyWhereItsRopeCatchesIt) {
  // A taut step of one solve keeps the energy to 4.3e-5 of the scale, and steps that start slack
  // never gain. Not yet held: at -7 rad/s and 30 Hz the rope's pull gives the island stage 3's
  // geometric stiffness (h^2 T / (m L) over 0.05) and the main solve takes it; a taut step that
  // goes slack there loses 0.93-2.9% of the scale (docs/knocks.md, "Caught over a spinning
  // hexagon"), so that stepping is left out.
  int runs = 0, catches = 0;
  double worstHeld = 0, worstHeldSum = 0, worstGain = 0, caught = 0;
  for (const double mass : {0.75, 1.5, 3.0})
    for (const double spin : {3.0, 5.0, -7.0})
      for (const int hz : {30, 60, 120}) {
        if (spin == -7.0 && hz == 30) continue;  // the stiff main solve's loss (above)
        SCOPED_TRACE(::testing::Message() << mass << " kg, " << spin << " rad/s, " << hz << " Hz");
        const CatchRun r = run(mass, spin, hz, 10);
        EXPECT_LT(r.worstHeld, 2e-4);
        EXPECT_LT(std::abs(r.heldSum), 1e-3);
        EXPECT_LT(r.worstGain, 2e-4);
        EXPECT_GE(r.caughtLoss, -1e-5);  // catches only lose
        EXPECT_GT(r.totalLoss, -1e-4);   // the run never ends above its start
        worstHeld = std::max(worstHeld, r.worstHeld);
        worstHeldSum = std::max(worstHeldSum, std::abs(r.heldSum));
        worstGain = std::max(worstGain, r.worstGain);
        caught += r.caughtLoss;
        catches += r.catches;
        ++runs;
      }
  std::printf(
      "24 runs: %d steps start slack (lose %.3g of the scales in all); taut one-solve "
      "steps: worst %.2g, worst sum %.2g; worst gain %.2g of the scale\n",
      catches, caught, worstHeld, worstHeldSum, worstGain);
  EXPECT_EQ(runs, 24);
  EXPECT_GT(catches, 24);  // the rope does go slack and catch: the test sees catches
}

}  // namespace
}  // namespace cablelab
