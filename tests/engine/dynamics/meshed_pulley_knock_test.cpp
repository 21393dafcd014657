// Two polygon pulleys of one rope pinned so close that their skins mesh like gears as they spin
// (docs/knocks.md, "Two pulleys knocking"). With restitution 1 every knock between them is taken
// by pulley_knock.h, which keeps the energy; left to Box2D's time-of-impact solve, which leaves the
// pivots out, a closing threw away the linear velocity it gave the pinned bodies: hexagons 4 mm
// apart counter-spinning at 20 rad/s lost 61% of their spin energy in one step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/dynamics/world.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace meshed_pulley_knock_test {  // named: unity batches join test files

struct Meshed {
  int sides;
  double gap;   // m between the corner circles (radius 0.12 m)
  double spin;  // rad/s of A; B spins the other way
  double hz;    // steps per second
  int substeps;
  double weight;  // kg on the rope's end
};

// Polygons of corner radius 0.12 m, 1 kg, restitution 1, pinned `gap` apart (corner circles), B
// turned 0.3 rad; a rope from the world over both (left) and over a world point to a weight.
SceneDef meshedPair(const Meshed& m) {
  SceneDef s = test::pinnedPolygonPairOnOneRope(m.sides, 0.12 + m.gap / 2, m.spin, -m.spin, 0.3, 1,
                                                m.weight);
  s.dt = 1 / m.hz;
  s.substeps = m.substeps;
  return s;
}

std::string describe(const Meshed& m) {
  return std::to_string(m.sides) + "-gons " + std::to_string(m.gap * 1000) + " mm apart at " +
         std::to_string(m.spin) + " rad/s, " + std::to_string(m.hz) + " Hz x " +
         std::to_string(m.substeps) + ", weight " + std::to_string(m.weight) + " kg";
}

TEST(MeshedPulleyKnock, CounterSpinningHexagonsKeepTheirSpinEnergyAtRestitutionOne) {
  // Each lost 3.3-61% of the spin energy on main (the largest change over 8 s); now under 1%.
  const Meshed variants[] = {
      {6, 0.004, 20, 60, 1, 0.5},  {6, 0.004, 4, 60, 1, 3.0},  {6, 0.004, 4, 240, 1, 0.5},
      {6, 0.004, 20, 240, 1, 3.0}, {6, 0.004, 10, 60, 1, 0.5}, {6, 0.004, 10, 120, 1, 3.0},
      {6, 0.004, 20, 60, 4, 0.5},  {6, 0.004, 4, 60, 4, 0.5},  {6, 0.004, 20, 120, 1, 0.5},
      {6, 0.002, 20, 60, 1, 0.5},
  };
  for (const Meshed& m : variants) {
    SCOPED_TRACE(describe(m));
    World w(meshedPair(m), "meshed");
    const double e0 = w.energy();
    double spinEnergy = 0;
    for (int i = 0; i < 2; ++i) {
      const BodyState& b = w.body(i);
      spinEnergy += 0.5 * b.angularVelocity * b.angularVelocity / b.invInertia;
    }
    int knocks = 0;
    double lowest = 0, highest = 0;
    const int steps = static_cast<int>(std::lround(8 * m.hz));
    for (int k = 0; k < steps; ++k) {
      const double a = w.body(0).angularVelocity;
      w.step(1 / m.hz, m.substeps);
      if (std::abs(w.body(0).angularVelocity - a) > 0.1 * std::abs(a) + 0.05) ++knocks;
      const double change = w.energy() - e0;
      ASSERT_TRUE(std::isfinite(change)) << "step " << k;
      lowest = std::min(lowest, change);
      highest = std::max(highest, change);
    }
    ASSERT_GT(knocks, 0) << "the skins mesh";
    // Every knock is elastic: what is left is the rope's rounding and the pivots' drift.
    EXPECT_GT(lowest, -0.01 * spinEnergy);
    EXPECT_LT(highest, 0.01 * spinEnergy);
    for (int i = 0; i < 2; ++i)
      EXPECT_LT((w.body(i).position - meshedPair(m).bodies[i].position).norm(), 1e-4)
          << "body " << i << " stays on its pivot";
  }
}

}  // namespace meshed_pulley_knock_test
}  // namespace cablelab
