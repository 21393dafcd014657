// Newton's shortcut (cable_solver.h, stage 6): one LCP on the start-of-step linearisation where
// its remainder bound shows it exact to 1e-12 m. It must give Newton's trajectory, and it must
// actually be taken where bodies sit still.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/dynamics/cable_solver.h"
#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/body_states.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

struct Trajectory {
  std::vector<double> poses, tensions;
  int linearSolves = 0;
};

// Steps a world for `steps` (the hand: servos moved at step 10 and back at step 60, then held),
// recording every body's pose and every cable's tension.
Trajectory runScene(const std::string& name, bool shortcut, int steps) {
  setLinearShortcut(shortcut);
  World world(makeScene(name));
  Trajectory run;
  for (int step = 0; step < steps; ++step) {
    if (name == "hand" && (step == 10 || step == 60))
      for (int j = 0; j < 6; ++j)
        world.setServoTarget(j, step == 10 ? 0.15 * (j % 3 == 1 ? 1 : -1) : 0);
    world.step(world.scene().dt, world.scene().substeps);
    run.linearSolves += world.lastStepStats().linearSolves;
    for (int b = 0; b < world.bodyCount(); ++b) {
      const BodyState& s = world.body(b);
      run.poses.insert(run.poses.end(), {s.position.x(), s.position.y(), s.angle});
    }
    for (int c = 0; c < world.cableCount(); ++c) run.tensions.push_back(world.cable(c).tension());
  }
  setLinearShortcut(true);
  return run;
}

TEST(LinearShortcut, EveryBuiltinSceneFollowsNewtonsTrajectory) {
  for (const SceneInfo& info : builtinScenes()) {
    SCOPED_TRACE(info.name);
    const Trajectory fast = runScene(info.name, true, 180),
                     newton = runScene(info.name, false, 180);
    ASSERT_EQ(fast.poses.size(), newton.poses.size());
    EXPECT_LT(test::largestDifference(fast.poses, newton.poses), 1e-8);
    EXPECT_LT(test::largestDifference(fast.tensions, newton.tensions),
              1e-7 * test::largestMagnitude(newton.tensions, 1));
    EXPECT_EQ(newton.linearSolves, 0);
  }
}

// The hand holding its box still: after 3 s of settling every sub-step's island takes the
// shortcut (measured: 240 of 240 in each second up to 11 s; 50 of 240 in the third second, when
// the fingers still creep by more than 1e-4 m/s), where Newton linearised again at the predicted
// pose.
TEST(LinearShortcut, TheHandHoldingItsBoxTakesItAtRest) {
  setLinearShortcut(true);
  World world(makeScene("hand"));
  for (int step = 0; step < 180; ++step) world.step(world.scene().dt, world.scene().substeps);
  int taken = 0;
  for (int step = 0; step < 60; ++step) {
    world.step(world.scene().dt, world.scene().substeps);
    taken += world.lastStepStats().linearSolves;
  }
  EXPECT_GE(taken, 0.9 * 60 * world.scene().substeps);
}

}  // namespace
}  // namespace cablelab
