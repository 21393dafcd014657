// Dynamics agree with statics: fingers held by their servos at fixed targets, the simulated box
// settles where the statics model (box-to-point reduction + equilibrium) puts it.
#include <gtest/gtest.h>

#include <cstdio>

#include "engine/dynamics/world.h"
#include "engine/hand/hand_controller.h"
#include "engine/hand/hand_tracking.h"

namespace cablelab {
namespace {

constexpr double kSettleTolerance = 1e-3;  // m
constexpr double kSettleTime = 12.0;       // s

TEST(HandScene, BoxSettlesAtTheStaticsPrediction) {
  HandModel m;
  HandController controller(m);
  const double poses[10][6] = {{0, 0, 0, 0, 0, 0},
                               {0.1, 0, -0.1, 0.1, 0, -0.1},
                               {-0.1, 0.1, 0.1, -0.1, 0.1, 0.1},
                               {0.2, 0.3, -0.2, 0.2, 0.3, -0.2},
                               {0.05, 0, 0, 0, 0, 0.05},
                               {0, 0.2, 0, 0, 0.2, 0},
                               {0, 0.1, 0, 0, -0.1, 0},
                               {0.15, -0.2, -0.15, 0.15, -0.2, -0.15},
                               {0.02, 0.05, 0.03, -0.02, 0.0, 0.0},
                               {-0.2, 0.4, 0.2, -0.2, 0.4, 0.2}};
  for (const auto& pose : poses) {
    const HandJoints targets = Eigen::Map<const HandJoints>(pose);
    World world(buildHandScene(m), "hand");
    placeHand(world, m, targets);
    const int box = world.findBody(kHandBoxName);
    const BoxPrediction guess = controller.predict(targets, Vec2::Zero());
    world.setBodyTransform(box, guess.box, 0);
    for (int s = 0; s < kSettleTime * 60; ++s) world.step(1.0 / 60, world.scene().substeps);
    // Statics at the joints the servos actually hold (they yield a little under the membranes).
    const BoxPrediction p = controller.predict(readHandJoints(world), world.body(box).position);
    std::printf("settle error %.3g mm\n", 1e3 * (world.body(box).position - p.box).norm());
    ASSERT_TRUE(p.valid) << "pose " << targets.transpose();
    EXPECT_LT((world.body(box).position - p.box).norm(), kSettleTolerance)
        << "pose " << targets.transpose() << " sim " << world.body(box).position.transpose()
        << " statics " << p.box.transpose();
  }
}

}  // namespace
}  // namespace cablelab
