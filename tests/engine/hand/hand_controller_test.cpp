#include "engine/hand/hand_controller.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "engine/hand/hand_kinematics.h"
#include "tests/support/finite_differences.h"

namespace cablelab {
namespace {

using test::kFdStep;
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

namespace cablelab {
namespace {

TEST(HandController, SpeedLimitPutsTheLagOnTheMembranesRoom) {
  // At the limit the expected lag (c K^-1 + tau_s) v sits on the ellipse with half axes
  // lagShare x (room along the paddles, room across them).
  HandModel m;
  HandController controller(m);
  const BoxPrediction p = controller.predict(HandJoints::Zero(), Vec2::Zero());
  ASSERT_TRUE(p.valid);
  const double c = m.boxMass * m.boxDamping, tau = 2 / std::sqrt(m.servoKp);
  const double along = controller.params().lagShare * (m.paddleHalfWidth - m.boxHalfSize);
  const double across = controller.params().lagShare * (m.boxHalfSize - m.baseY + m.paddleOffset);
  for (double angle : {0.0, 0.4, 1.2, M_PI / 2, 2.5}) {
    const Vec2 d(std::cos(angle), std::sin(angle));
    const double v = controller.speedLimit(p.stiffness, d);
    ASSERT_GT(v, 0);
    const Vec2 lag = (c * p.stiffness.inverse() * d + tau * d) * v;
    EXPECT_NEAR(std::hypot(lag.x() / along, lag.y() / across), 1.0, 1e-12) << angle;
  }
}

TEST(HandController, JointsAtALimitDropOutAndTheOthersTakeOver) {
  // Slides at their upper limit, target further out along x: the slides are not pushed, the box
  // still moves towards the target (the proximal and distal joints do it).
  HandModel m;
  HandController controller(m);
  HandJoints q = HandJoints::Zero();
  q[kSlide] = m.upper[kSlide], q[3 + kSlide] = m.upper[3 + kSlide];
  const Vec2 box = controller.predict(q, Vec2::Zero()).box;
  const Vec2 target = box + Vec2(0.3, 0.2);
  HandJoints dq = HandJoints::Zero();
  for (int u = 0; u < 5; ++u) dq = controller.update(q, box, target, q);
  EXPECT_LE(dq[kSlide], 0);
  EXPECT_LE(dq[3 + kSlide], 0);
  EXPECT_GE(controller.status().jointsAtLimit, 2);
  const Vec2 moved = controller.predict(m.clamp(q + dq), box).box - box;
  EXPECT_GT(moved.dot(target - box), 0);
}

TEST(HandController, FaceOnJacobianMatchesFiniteDifferencesThroughTheStatics) {
  // The face-on conditions move with the fingertips and with the box's equilibrium: both parts
  // against central differences of faceOnTerms() at the re-solved equilibrium. At the pinch and
  // near the (5, 5) boundary (slides at their limit, a corner almost level with the box's face).
  HandModel m;
  HandController controller(m);
  HandJoints nearBoundary;
  nearBoundary << 0.3635, 0.9, -0.2456, 0.3411, 0.8944, -0.4333;
  for (const HandJoints& q : {HandJoints(HandJoints::Zero()), nearBoundary}) {
    const BoxPrediction p = controller.predict(q, Vec2::Zero());
    ASSERT_TRUE(p.smooth);
    const Eigen::Matrix<double, 12, 6> G = controller.faceOnJacobian(q, p);
    for (int j = 0; j < 6; ++j) {
      HandJoints a = q, b = q;
      a[j] += kFdStep, b[j] -= kFdStep;
      const Vec2 pa = controller.predict(a, p.box).box, pb = controller.predict(b, p.box).box;
      const Eigen::Matrix<double, 12, 1> fd = (faceOnTerms(m, fingertipPoints(m, a), pa).value -
                                               faceOnTerms(m, fingertipPoints(m, b), pb).value) /
                                              (2 * kFdStep);
      for (int r = 0; r < 12; ++r)
        EXPECT_NEAR(G(r, j), fd[r], kSensitivityTolerance) << "row " << r << " joint " << j;
    }
  }
}

TEST(HandController, BoundedStepKeepsTheFaceOnSlackAndTheJointLimits) {
  // Quasi-statically (box at the statics equilibrium of the commanded joints) towards a target
  // far outside the reachable set: every update's joints stay within their limits, the face-on
  // slack of the equilibrium never falls below wrapMargin once it is above it, and the box ends
  // much nearer the target than where the slides first reach their limit.
  HandModel m;
  HandControllerParams params;
  params.kd = 0;  // quasi-static: no dynamics to damp (as in the quasi-static reach)
  HandController controller(m, params);
  const Vec2 target(5, 5);
  HandJoints q = HandJoints::Zero();
  BoxPrediction p = controller.predict(q, Vec2::Zero());
  double firstAtLimit = -1;
  for (int u = 0; u < 1500; ++u) {
    q += controller.update(q, p.box, target, q);
    for (int j = 0; j < 6; ++j) {
      ASSERT_GE(q[j], m.lower[j] - 1e-9) << "update " << u;
      ASSERT_LE(q[j], m.upper[j] + 1e-9) << "update " << u;
    }
    p = controller.predict(q, p.box);
    ASSERT_TRUE(p.smooth) << "update " << u;
    EXPECT_GT(p.margin, params.wrapMargin - 1e-3) << "update " << u;
    if (firstAtLimit < 0 && q[kSlide] > m.upper[kSlide] - 1e-6)
      firstAtLimit = (p.box - target).norm();
  }
  ASSERT_GT(firstAtLimit, 0) << "the slides never reached their limit";
  EXPECT_LT((p.box - target).norm(), firstAtLimit - 0.05);
}

}  // namespace
}  // namespace cablelab
