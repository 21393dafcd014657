#include "engine/hand/hand_controller.h"

#include <gtest/gtest.h>

#include "engine/hand/hand_kinematics.h"

namespace cablelab {
namespace {

constexpr double kFdStep = 1e-6;
constexpr double kSensitivityTolerance = 1e-5;

TEST(HandController, StaticsMatchesTheBoxCableEnergy) {
  // The box-to-point reduction: at the predicted centre, the two membranes wrapped round the box
  // (fingertip -> corner -> corner -> fingertip) exert no net force on it.
  HandModel m;
  HandController controller(m);
  HandJoints q;
  q << 0.1, 0.2, -0.08, 0.05, 0.1, -0.03;
  const BoxPrediction p = controller.predict(q, Vec2::Zero());
  ASSERT_TRUE(p.valid);
  const FingertipPoints tips = fingertipPoints(m, q);
  const double h = m.boxHalfSize;
  Vec2 force = Vec2::Zero();
  for (int f = 0; f < 2; ++f) {
    const double face = HandModel::side(f) * h;
    const Vec2 a = tips.segment<2>(4 * f), b = tips.segment<2>(4 * f + 2);
    const Vec2 ca = p.box + Vec2(-h, face), cb = p.box + Vec2(h, face);
    const double length = (ca - a).norm() + 2 * h + (b - cb).norm();
    const double tension = m.stiffness * (length - m.restLength() + m.preload);
    ASSERT_GT(tension, 0);
    force += tension * ((a - ca).normalized() + (b - cb).normalized());
  }
  EXPECT_LT(force.norm(), 1e-8);
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
    const Vec2 fd =
        (controller.predict(a, p.box).box - controller.predict(b, p.box).box) / (2 * kFdStep);
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
    q = m.clamp(q + controller.update(q, box, target, q));
    box = controller.predict(q, box).box;
  }
  EXPECT_LT((box - target).norm(), 1e-3);
}

}  // namespace
}  // namespace cablelab
