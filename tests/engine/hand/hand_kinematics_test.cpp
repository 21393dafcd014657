#include "engine/hand/hand_kinematics.h"
#include "tests/support/finite_differences.h"

#include <gtest/gtest.h>

namespace cablelab {
namespace {

using test::kFdStep;
constexpr double kJacobianTolerance = 1e-7;

TEST(HandKinematics, JacobianMatchesCentralDifferences) {
  HandModel m;
  HandJoints q;
  q << 0.3, -0.2, -0.4, -0.25, 0.5, 0.1;
  const FingertipJacobian J = fingertipJacobian(m, q);
  for (int j = 0; j < 6; ++j) {
    HandJoints a = q, b = q;
    a[j] += kFdStep, b[j] -= kFdStep;
    const FingertipPoints fd = (fingertipPoints(m, a) - fingertipPoints(m, b)) / (2 * kFdStep);
    for (int r = 0; r < 8; ++r)
      EXPECT_NEAR(J(r, j), fd[r], kJacobianTolerance) << "row " << r << " joint " << j;
  }
}

TEST(HandKinematics, PinchPoseCorners) {
  HandModel m;
  const FingertipPoints tips = fingertipPoints(m, HandJoints::Zero());
  EXPECT_NEAR(tips[0], -m.paddleHalfWidth, 1e-12);
  EXPECT_NEAR(tips[1], m.baseY - m.paddleOffset, 1e-12);
  EXPECT_TRUE(wrapsFaceOn(m, tips, Vec2::Zero()));
  EXPECT_FALSE(wrapsFaceOn(m, fingertipPoints(m, m.openPose()), Vec2::Zero()));
}

}  // namespace
}  // namespace cablelab
