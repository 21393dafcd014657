// The hand with a box that turns (scene parameter `turn`, docs/hand.md): the face-on conditions
// of a turned box and the controller's (x, y, theta) model, against finite differences.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "engine/core/error.h"
#include "engine/hand/hand_controller.h"
#include "engine/hand/hand_io.h"
#include "engine/hand/hand_kinematics.h"
#include "engine/hand/hand_reach.h"
#include "engine/hand/hand_tracking.h"
#include "engine/scenes/scene_hand.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/finite_differences.h"

namespace cablelab {
namespace hand_turn_test {  // named: unity batches join test files

using test::kFdStep;
/// Of the ten held-out targets, how many are reached within 5 mm and 0.02 rad at 15 s.
constexpr int kHeldOutReached = 10;  // measured: all ten, within 0.6 mm and 0.0001 rad

HandModel turningHand() {
  HandModel m;
  m.turn = true;
  return m;
}

/// A grasp away from the pinch with both paddles tilted: the box turns and moves.
HandJoints tiltedGrasp() {
  HandJoints q;
  q << 0.1, 0.2, 0.05, 0.05, 0.1, 0.12;
  return q;
}

TEST(HandTurn, TurnedFaceOnTermsMatchFiniteDifferences) {
  const HandModel m;
  const FingertipPoints tips = fingertipPoints(m, tiltedGrasp());
  const Vec2 p(0.03, -0.02);
  const double angle = 0.2;
  const FaceOnTerms t = faceOnTerms(m, tips, p, angle);
  for (int i = 0; i < 8; ++i) {
    FingertipPoints a = tips, b = tips;
    a[i] += kFdStep, b[i] -= kFdStep;
    const Eigen::Matrix<double, 12, 1> fd =
        (faceOnTerms(m, a, p, angle).value - faceOnTerms(m, b, p, angle).value) / (2 * kFdStep);
    EXPECT_LT((t.dTips.col(i) - fd).norm(), 1e-7) << "tip coordinate " << i;
  }
  for (int i = 0; i < 2; ++i) {
    Vec2 a = p, b = p;
    a[i] += kFdStep, b[i] -= kFdStep;
    const Eigen::Matrix<double, 12, 1> fd =
        (faceOnTerms(m, tips, a, angle).value - faceOnTerms(m, tips, b, angle).value) /
        (2 * kFdStep);
    EXPECT_LT((t.dBox.col(i) - fd).norm(), 1e-7) << "box coordinate " << i;
  }
  const Eigen::Matrix<double, 12, 1> fd = (faceOnTerms(m, tips, p, angle + kFdStep).value -
                                           faceOnTerms(m, tips, p, angle - kFdStep).value) /
                                          (2 * kFdStep);
  EXPECT_LT((t.dAngle - fd).norm(), 1e-7);
  // Unturned, the conditions are the fixed box's.
  EXPECT_LT((faceOnTerms(m, tips, p, 0.0).value - faceOnTerms(m, tips, p).value).norm(), 1e-14);
}

TEST(HandTurn, PredictionInXYThetaMatchesReSolvedFiniteDifferences) {
  // d(x, y, theta)/dq of the controller's model against the statics re-solved at q +/- h e_j.
  const HandController controller(turningHand());
  const HandJoints q = tiltedGrasp();
  const BoxPrediction p = controller.predict(q, Vec2::Zero(), 0);
  ASSERT_TRUE(p.valid);
  // The tilted paddles turn the box (a fixed box would keep angle 0).
  EXPECT_GT(std::abs(p.angle), 0.02);
  for (int j = 0; j < 6; ++j) {
    HandJoints a = q, b = q;
    a[j] += kFdStep, b[j] -= kFdStep;
    const BoxPrediction pa = controller.predict(a, p.box, p.angle);
    const BoxPrediction pb = controller.predict(b, p.box, p.angle);
    const Vec2 fdBox = (pa.box - pb.box) / (2 * kFdStep);
    const double fdAngle = (pa.angle - pb.angle) / (2 * kFdStep);
    EXPECT_NEAR(p.jacobian(0, j), fdBox.x(), 1e-5) << "joint " << j;
    EXPECT_NEAR(p.jacobian(1, j), fdBox.y(), 1e-5) << "joint " << j;
    EXPECT_NEAR(p.angleJacobian(0, j), fdAngle, 1e-5) << "joint " << j;
  }
}

TEST(HandTurn, FaceOnJacobianOfATurningBoxMatchesFiniteDifferences) {
  // d(face-on conditions)/dq: fingertips with q, the box's centre and angle through the statics.
  const HandModel m = turningHand();
  const HandController controller(m);
  const HandJoints q = tiltedGrasp();
  const BoxPrediction p = controller.predict(q, Vec2::Zero(), 0);
  ASSERT_TRUE(p.valid);
  const Eigen::Matrix<double, 12, 6> J = controller.faceOnJacobian(q, p);
  for (int j = 0; j < 6; ++j) {
    HandJoints a = q, b = q;
    a[j] += kFdStep, b[j] -= kFdStep;
    const BoxPrediction pa = controller.predict(a, p.box, p.angle);
    const BoxPrediction pb = controller.predict(b, p.box, p.angle);
    const Eigen::Matrix<double, 12, 1> fd =
        (controller.faceOn(a, pa).value - controller.faceOn(b, pb).value) / (2 * kFdStep);
    EXPECT_LT((J.col(j) - fd).norm(), 1e-5) << "joint " << j;
  }
}

TEST(HandTurn, TheCentresStiffnessLetsTheAngleSettle) {
  // K = d(net force)/d(centre) with the angle re-settled: the inverse of the compliance's
  // centre block, (H^-1)_xy^-1, is what the Schur complement gives.
  const HandModel m = turningHand();
  const HandController controller(m);
  const HandJoints q = tiltedGrasp();
  const BoxPrediction p = controller.predict(q, Vec2::Zero(), 0);
  ASSERT_TRUE(p.smooth);
  Eigen::Matrix3d H;
  boxPoseEnergy(controller.boxCables(q), BoxPose(p.box.x(), p.box.y(), p.angle), nullptr, &H);
  const Eigen::Matrix2d expected = H.inverse().topLeftCorner<2, 2>().inverse();
  EXPECT_LT((p.stiffness - expected).norm(), 1e-9 * expected.norm());
  // Softer than with the angle held (the turning gives way).
  const double heldTrace = H.topLeftCorner<2, 2>().trace();
  EXPECT_LE(p.stiffness.trace(), heldTrace + 1e-9);
}

TEST(HandTurn, SceneParameterTurnFreesTheBoxsRotation) {
  auto boxOf = [](const SceneDef& s) {
    for (const BodyDef& b : s.bodies)
      if (b.name == kHandBoxName) return b;
    return BodyDef{};
  };
  EXPECT_TRUE(boxOf(makeScene("hand")).fixedRotation);
  const BodyDef turning = boxOf(makeScene("hand", {{"turn", 1}}));
  EXPECT_FALSE(turning.fixedRotation);
  EXPECT_GT(turning.angularDamping, 0);
  EXPECT_TRUE(handModelWithSettings({{"turn", 1}}).turn);
  EXPECT_FALSE(handModelWithSettings({}).turn);
  try {
    makeScene("hand", {{"turn", 0.5}});
    FAIL() << "turn=0.5 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "command line: --set turn: must be 0 or 1 (got 0.5)");
  }
}

TEST(HandTurn, AngleTargetsAreCheckedWithTheClisMessages) {
  auto message = [](auto f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(
      message([] { targetNumbers("1,2,3,4", kCommandLine, "--target"); }),
      "command line: --target: must be X,Y or X,Y,THETA, 2 or 3 finite numbers (got \"1,2,3,4\")");
  EXPECT_EQ(message([] { targetNumbers("0.1,0.2,nan", kCommandLine, "--target"); }),
            "command line: --target: must be X,Y,THETA, 3 finite numbers (got \"0.1,0.2,nan\")");
  TrackRequest request;
  setTarget(request, targetNumbers("0.1,0.2,0.3", kCommandLine, "--target"), kCommandLine,
            "--target");
  EXPECT_EQ(request.targetAngle, 0.3);
  EXPECT_EQ(
      message([&] { trackOptions(request, HandModel{}); }),
      "command line: --target: THETA needs a box that may turn (scene parameter turn=1) (got 0.3)");
  EXPECT_EQ(trackOptions(request, turningHand()).targetAngle, 0.3);
  request.targetAngle = 4;
  EXPECT_EQ(message([&] { trackOptions(request, turningHand()); }),
            "command line: --target: THETA must be in [-pi, pi] rad (got 4)");
}

TEST(HandTurnTracking, HeldOutTargetsInXYThetaAreReached) {
  // Issue 41's goal: targets (x, y, theta), |theta| <= 0.3 rad, inside the reach set, reached
  // within 5 mm and 0.02 rad with the grasp held. These ten were not used to tune anything.
  const double targets[10][3] = {{0.3, 0.2, 0.15},   {-0.2, 0.3, -0.3}, {0.0, -0.3, 0.25},
                                 {0.35, -0.2, -0.2}, {-0.3, -0.2, 0.3}, {0.15, 0.35, -0.1},
                                 {-0.35, 0.1, 0.2},  {0.25, 0.0, -0.3}, {-0.1, -0.4, -0.15},
                                 {0.05, 0.15, 0.3}};
  int reached = 0, held = 0;
  for (const auto& t : targets) {
    TrackOptions o;
    o.target = Vec2(t[0], t[1]);
    o.targetAngle = t[2];
    o.pid = true;
    const TrackResult r = runTracking(o, turningHand());
    held += r.graspHeld;
    const bool ok = r.graspHeld && r.finalError < 0.005 && r.finalAngleError < 0.02;
    reached += ok;
    EXPECT_LT(r.finalAngleError, 0.02) << t[0] << "," << t[1] << "," << t[2];
    EXPECT_LT(r.finalError, 0.01) << t[0] << "," << t[1] << "," << t[2];
  }
  EXPECT_EQ(held, 10);
  EXPECT_GE(reached, kHeldOutReached);
}

// The quasi-static sweep's statics solves, one per update from the last pose, converge all the way
// to the target: the Newton solve of the box's pose judges a step by the gradient it leaves once
// the energy's decrease falls below the energy's rounding (on the energy alone it stalled just
// above its tolerance after seven updates, and the sweep reached no target at all).
TEST(HandTurnReach, QuasiStaticSweepFollowsTheStaticsToTheTarget) {
  ReachOptions o;
  o.model = ReachModel::QuasiStatic;
  EXPECT_TRUE(quasiStaticReach(turningHand(), Vec2(0.3, 0.2), o));
  o.angle = 0.2;
  EXPECT_TRUE(quasiStaticReach(turningHand(), Vec2(-0.2, 0.1), o));
  EXPECT_FALSE(quasiStaticReach(turningHand(), Vec2(1.2, 1.95), o));  // beyond the hand's reach
}

// On a small grid the statics model's reach with a box that turns is the simulated one, target by
// target (4 x 4: the four central targets reached, the twelve outer ones not).
TEST(HandTurnReach, QuasiStaticSetIsTheSimulatedOneOnASmallGrid) {
  ReachOptions o;
  o.grid = 4;
  o.threads = 2;
  const ReachResult r = runReach(o, turningHand());
  int simulated = 0;
  for (const ReachTarget& t : r.targets) {
    simulated += t.simulated;
    EXPECT_EQ(t.quasiStatic, t.simulated) << t.point.transpose();
  }
  EXPECT_EQ(simulated, 4);
}

}  // namespace hand_turn_test
}  // namespace cablelab
