// The grasp sequence under the controller (hand_tracking.h, hand_grasp.h): target jumps, a target
// far outside the reachable set, and the offset from the default start.
#include "engine/hand/hand_tracking.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/hand/hand_kinematics.h"

namespace cablelab {
namespace {

constexpr double kReachTolerance = 0.005;  // m, as `reach` counts a target reached
constexpr double kPidTolerance = 0.001;    // m at 15 s (issue acceptance)
constexpr double kTensionFactor = 3.0;     // the tension may not exceed 3x its steady value

bool finite(const TrackResult& r) {
  for (const TrackSample& s : r.samples)
    if (!s.box.allFinite() || !std::isfinite(s.tension)) return false;
  return r.finalJoints.allFinite();
}

TEST(HandTracking, TargetJumpsAcrossTheWorkspaceKeepTheGrasp) {
  // (0.5, 0.5) to (0, 0) at 8 s: the jump that used to ring the grasp loose; then across the
  // workspace to (-0.4, -0.6).
  TrackOptions o;
  o.target = Vec2(0.5, 0.5);
  o.pid = true;
  o.time = 22;
  o.changes = {{8.0, Vec2(0, 0)}, {13.0, Vec2(-0.4, -0.6)}};
  const TrackResult r = runTracking(o);
  ASSERT_TRUE(finite(r));
  EXPECT_TRUE(r.graspHeld);
  EXPECT_EQ(r.losses, 0);
  ASSERT_GT(r.startTension, 0);
  EXPECT_LT(r.maxTension, kTensionFactor * r.startTension)
      << "max " << r.maxTension << " N, steady " << r.startTension << " N";
  EXPECT_LT(r.finalError, kReachTolerance);
}

TEST(HandTracking, FarTargetLeavesTheBoxHeldAtTheBoundary) {
  TrackOptions o;
  o.target = Vec2(5, 5);
  o.pid = true;
  const TrackResult r = runTracking(o);
  ASSERT_TRUE(finite(r));
  EXPECT_TRUE(r.graspHeld);
  const HandModel m;
  int atLimit = 0;
  for (int j = 0; j < 6; ++j)
    atLimit += r.finalJoints[j] > m.upper[j] - 0.01 || r.finalJoints[j] < m.lower[j] + 0.01;
  EXPECT_GE(atLimit, 1) << "no joint at its limit";
  // The box went as far towards the target as the hand allows: beyond the fingertips' own reach
  // on the way, and not back.
  const Vec2 box = r.samples.back().box;
  EXPECT_LT((box - o.target).norm(), (r.start - o.target).norm() - 1.0);
}

TEST(HandTracking, DefaultStartIsOffTheTargetAndPidRemovesTheOffset) {
  TrackOptions o;
  o.target = Vec2::Zero();
  o.pid = true;
  const TrackResult pid = runTracking(o);
  EXPECT_GE(pid.startError, 0.05);
  EXPECT_TRUE(pid.graspHeld);
  EXPECT_LT(pid.finalError, kPidTolerance);
  o.pid = false;
  const TrackResult pd = runTracking(o);
  EXPECT_TRUE(pd.graspHeld);
  EXPECT_DOUBLE_EQ(pd.startError, pid.startError);  // the same start, the same grasp
}

TEST(HandTracking, NearestPinchIsInsideTheFingertipsReach) {
  const HandModel m;
  for (const Vec2& g : {Vec2(5, 5), Vec2(-3, 0), Vec2(0.5, -4), Vec2(0.1, 0.1)}) {
    const Vec2 p = nearestPinch(m, g);
    EXPECT_TRUE(pinchWithinLimits(m, p)) << g.transpose();
    if (pinchWithinLimits(m, g)) {
      EXPECT_LT((p - g).norm(), 1e-6);
    }
  }
}

}  // namespace
}  // namespace cablelab
