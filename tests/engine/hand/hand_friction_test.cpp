// The hand with friction between membranes and box (scene parameter `mu`,
// docs/control.md#membrane-friction): the scene it builds, and simulated runs of a turning box to
// held-out (x, y, theta) targets.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/core/error.h"
#include "engine/dynamics/world.h"
#include "engine/hand/hand_tracking.h"
#include "engine/scenes/scene_hand.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {
namespace hand_friction_test {  // named: unity batches join test files

/// Of ten held-out targets, how many are reached within 5 mm and 0.02 rad at 15 s. Issue 41's goal
/// is at least 9; measured 10 (within 3.7 mm and 7e-5 rad, every grasp held). Without the
/// controller's friction offset (hand_controller.h) (0.367, 0.334, 0.219) ended 187 mm off, the
/// box creeping behind its reference; without the statics' rounding-aware line search
/// (box_pose.h) (0.161, 0.222, 0.141) also ended 16 mm off.
constexpr int kHeldOutReached = 10;

HandModel frictionHand(double mu) {
  return handModelWithSettings({{"mu", mu}, {"turn", 1}});
}

TEST(HandFriction, MuGripsTheBoxCornersAndZeroIsTheThesisScene) {
  EXPECT_EQ(handModelWithSettings({}).friction, 0.0);
  for (const double mu : {0.0, 0.5}) {
    const SceneDef s = buildHandScene(frictionHand(mu));
    for (const CableDef& c : s.cables) {
      ASSERT_EQ(c.pulleys.size(), 1u);
      EXPECT_EQ(c.pulleys[0].grip, mu > 0 ? Grip::Capstan : Grip::Frictionless);
      EXPECT_EQ(c.pulleys[0].mu, mu);
    }
  }
  EXPECT_THROW(makeScene("hand", {{"mu", -0.1}}), InputError);
}

// The grasp closes and both membranes wrap two corners each, split in two spans; each holds
// within its capstan ratio e^(mu theta), and they differ (friction carries a tension difference).
TEST(HandFriction, MembranesHoldWithinTheirCapstanRatio) {
  const SceneDef scene = makeScene("hand", {{"mu", 0.5}, {"turn", 1}});
  World w(scene, "hand");
  const int box = w.findBody(kHandBoxName);
  // The top finger slides right and the bottom one left: a shear that turns the box.
  w.setServoTarget(w.findJoint("top_slide"), 0.05);
  w.setServoTarget(w.findJoint("bottom_slide"), -0.05);
  for (int i = 0; i < 240; ++i) w.step(scene.dt, scene.substeps);
  for (int f = 0; f < 2; ++f) {
    const Cable& c = w.cable(w.findCable(kHandCableNames[f]));
    ASSERT_EQ(c.spanCount(), 2) << f;
    const double a = c.spanTension(0), b = c.spanTension(1);
    ASSERT_GT(std::min(a, b), 0) << f;
    EXPECT_LE(std::max(a, b), std::exp(0.5 * c.link(0).wrapAngle) * std::min(a, b) * 1.001) << f;
  }
  EXPECT_GT(std::abs(w.body(box).angle), 0.01);
}

TEST(HandFrictionTracking, SeededHeldOutTargetsInXYThetaAreReached) {
  // Issue 41's goal with mu = 0.5, turn = 1: targets (x, y, theta), |theta| <= 0.3 rad, inside
  // the reach set (|x|, |y| <= 0.4 m), reached within 5 mm and 0.02 rad with the grasp held.
  // Drawn from a seed, not used to tune anything.
  std::mt19937 rng(20261205);
  std::uniform_real_distribution<double> xy(-0.4, 0.4), theta(-0.3, 0.3);
  int reached = 0, held = 0;
  for (int i = 0; i < 10; ++i) {
    TrackOptions o;
    o.target = Vec2(xy(rng), xy(rng));
    o.targetAngle = theta(rng);
    o.pid = true;
    const TrackResult r = runTracking(o, frictionHand(0.5));
    held += r.graspHeld;
    const bool ok = r.graspHeld && r.finalError < 0.005 && r.finalAngleError < 0.02;
    reached += ok;
    std::printf("target %+.3f %+.3f %+.3f: error %.2e m %.2e rad held %d\n", o.target.x(),
                o.target.y(), o.targetAngle, r.finalError, r.finalAngleError, int(r.graspHeld));
  }
  EXPECT_EQ(held, 10);
  EXPECT_GE(reached, kHeldOutReached);
}

}  // namespace hand_friction_test
}  // namespace cablelab
