// A polygon swung round past a cable's end anchor stays wrapped (issue 11, item 5): the cable
// winds round it for turn after turn, no guard acts (no warning, so no length jump above 1 mm),
// and with nothing damped the energy is kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/hook_scene.h"

namespace cablelab {
namespace {

TEST(Hooks, ASquareWhirledRoundTheEndAnchorWindsTheCableOnAndKeepsItsEnergy) {
  for (const int substeps : {1, 4}) {
    SCOPED_TRACE("substeps " + std::to_string(substeps));
    World world(test::whirl(6, 0.5, 0.5, substeps));
    const Cable& rope = world.cable(1);
    const double e0 = world.energy();
    double worst = 0, scale = 0, orbit = 0;
    size_t mostWraps = 0;
    bool joined = false, stayed = true;
    Vec2 last = world.body(0).position;
    for (int s = 0; s < 300; ++s) {  // 5 s
      world.step(1.0 / 60, substeps);
      const BodyState& b = world.body(0);
      worst = std::max(worst, std::abs(world.energy() - e0));
      scale = std::max(scale, 0.5 * b.velocity.squaredNorm() / b.invMass +
                                  0.5 * b.angularVelocity * b.angularVelocity / b.invInertia);
      orbit += std::atan2(cross(b.position, last), last.dot(b.position));  // clockwise: +
      last = b.position;
      joined |= rope.engaged(0);
      if (joined) stayed &= rope.engaged(0);
      mostWraps = std::max(mostWraps, static_cast<size_t>(rope.wraps()));
    }
    EXPECT_TRUE(joined && stayed);
    EXPECT_GT(orbit / (2 * M_PI), 3.0);  // round B three times and more
    EXPECT_GT(mostWraps, 12u);           // the chain holds three whole turns of the square
    EXPECT_TRUE(world.warnings().empty()) << world.warnings().front();
    EXPECT_LT(worst, 0.02 * scale) << worst / scale;
  }
}

}  // namespace
}  // namespace cablelab

namespace cablelab {
namespace {

TEST(Hooks, APointThatHooksTheCableBeyondItsEndPulleyStaysOnIt) {
  // The ballast scene thrown sideways: the point carries its cable past the end pulley, the
  // ballast is stopped at that pulley (its floor), and the point, on the cable doubled back round
  // it past half a turn, swings round on it. The cable keeps the point (Cable::leaveRound); the
  // solve's prediction of the path dropped it once the turn passed half a turn, saw a slack
  // cable, and let the point fly off: the rigid cable grew to 63 m in 60 s.
  for (const double vx : {1.64, 3.0}) {
    World world(makeScene("ballast", {{"v0x", vx}, {"m_point", 4.0}, {"m_ballast", 0.16}}));
    double longest = 0;
    for (int step = 0; step < 3600; ++step) {
      world.step(1.0 / 60, 2);
      longest = std::max(longest, world.cable(0).stretch());
    }
    EXPECT_LT(longest, 1e-4) << vx;
    EXPECT_EQ(world.cable(0).path().size(), 4u) << vx;  // anchor, point, pulley, ballast
    EXPECT_TRUE(world.warnings().empty()) << vx;
  }
}

}  // namespace
}  // namespace cablelab
