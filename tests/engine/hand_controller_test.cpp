#include "engine/hand_controller.h"

#include <gtest/gtest.h>

namespace cablelab {
namespace {

constexpr double kFdStep = 1e-6;
constexpr double kSensitivityTolerance = 1e-5;

TEST(PointEquilibrium, SensitivityMatchesCentralDifferences) {
  std::vector<SpringCable> cables = {{Vec2(-1, 0.3), Vec2(1.2, 0.2), 150, 1.5}, {Vec2(-0.9, -0.4), Vec2(1, -0.2), 100, 1.4}};
  const PointEquilibrium eq = solvePointEquilibrium(cables, Vec2::Zero());
  ASSERT_TRUE(eq.converged);
  for (int c = 0; c < 8; ++c) {
    auto shifted = [&](double h) {
      auto copy = cables;
      Vec2& end = c % 4 < 2 ? copy[c / 4].a : copy[c / 4].b;
      end[c % 2] += h;
      return solvePointEquilibrium(copy, eq.p).p;
    };
    const Vec2 fd = (shifted(kFdStep) - shifted(-kFdStep)) / (2 * kFdStep);
    EXPECT_NEAR(eq.sensitivity(0, c), fd.x(), kSensitivityTolerance) << "column " << c;
    EXPECT_NEAR(eq.sensitivity(1, c), fd.y(), kSensitivityTolerance) << "column " << c;
  }
}

TEST(HandController, BoxJacobianMatchesFiniteDifferencesThroughKinematics) {
  HandController controller{HandModel{}};
  HandJoints q;
  q << 0.1, 0.2, -0.08, 0.05, 0.1, -0.03;
  const BoxPrediction p = controller.predict(q, Vec2::Zero());
  ASSERT_TRUE(p.valid);
  for (int j = 0; j < 6; ++j) {
    HandJoints a = q, b = q;
    a[j] += kFdStep, b[j] -= kFdStep;
    const Vec2 fd = (controller.predict(a, p.box).box - controller.predict(b, p.box).box) / (2 * kFdStep);
    EXPECT_NEAR(p.jacobian(0, j), fd.x(), kSensitivityTolerance) << "joint " << j;
    EXPECT_NEAR(p.jacobian(1, j), fd.y(), kSensitivityTolerance) << "joint " << j;
  }
}

TEST(HandController, UpdateMovesTheBoxTowardsTheTarget) {
  HandModel m;
  HandController controller(m);
  HandJoints q = HandJoints::Zero();
  const Vec2 target(0.1, 0.2);
  Vec2 box = controller.predict(q, Vec2::Zero()).box;
  for (int u = 0; u < 200; ++u) {
    q = m.clamp(q + controller.update(q, box, Vec2::Zero(), target, q));
    box = controller.predict(q, box).box;
  }
  EXPECT_LT((box - target).norm(), 1e-3);
}

}  // namespace
}  // namespace cablelab
