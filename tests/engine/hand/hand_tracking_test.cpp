// The grasp sequence under the controller (hand_tracking.h, hand_grasp.h): target jumps, a target
// far outside the reachable set, and the offset from the default start.
#include "engine/hand/hand_tracking.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>
#include <vector>

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

/// Whether `reach` counts `target` reached: the run, stopped early as the sweep stops it, ends
/// within the tolerance with the grasp held.
bool reachedAsTheSweepCountsIt(const Vec2& target) {
  TrackOptions o;
  o.target = target;
  o.pid = true;
  o.stop.enabled = true;
  o.stop.tolerance = kReachTolerance;
  const TrackResult r = runTracking(o);
  return r.graspHeld && r.finalError < kReachTolerance;
}

TEST(HandTracking, FarTargetsEndAtTheReachableSetsNearestPoint) {
  // Targets far outside the reachable set, in five directions: the box ends held, with joints at
  // their limits, and no target of a fine grid round where it ended that the hand reaches (as
  // `reach` counts it) is nearer the far target by more than the reach tolerance. A controller
  // that stops short of the boundary (5 cm, say) has reached targets of the grid well nearer.
  constexpr double kFarTime = 30;    // s: a target on the hand's axis starts its slide slowly
  constexpr double kSpacing = 0.03;  // m: grid round the end point, 5 x 5 (+/- 6 cm)
  const HandModel m;
  for (const Vec2& far : {Vec2(5, 5), Vec2(-5, 5), Vec2(0, -5), Vec2(5, 0), Vec2(-5, 0)}) {
    TrackOptions o;
    o.target = far;
    o.pid = true;
    o.time = kFarTime;
    const TrackResult r = runTracking(o);
    ASSERT_TRUE(finite(r)) << far.transpose();
    EXPECT_TRUE(r.graspHeld) << far.transpose();
    int atLimit = 0;
    for (int j = 0; j < 6; ++j)
      atLimit += r.finalJoints[j] > m.upper[j] - 0.01 || r.finalJoints[j] < m.lower[j] + 0.01;
    EXPECT_GE(atLimit, 1) << far.transpose() << ": no joint at its limit";
    const Vec2 end = r.samples.back().box;
    const double distance = (end - far).norm();

    std::vector<Vec2> grid;
    for (int i = -2; i <= 2; ++i)
      for (int k = -2; k <= 2; ++k) grid.push_back(end + kSpacing * Vec2(i, k));
    std::vector<char> reached(grid.size(), 0);
    std::atomic<size_t> next{0};
    auto worker = [&] {
      for (size_t g = next++; g < grid.size(); g = next++)
        reached[g] = reachedAsTheSweepCountsIt(grid[g]);
    };
    std::thread helper(worker);
    worker();
    helper.join();
    double best = 1e300;
    int count = 0;
    for (size_t g = 0; g < grid.size(); ++g)
      if (reached[g]) best = std::min(best, (grid[g] - far).norm()), ++count;
    ASSERT_GT(count, 0) << far.transpose() << ": no grid target round the end is reached";
    EXPECT_LE(distance, best + kReachTolerance)
        << far.transpose() << ": the box ended " << distance << " m off, a reached target is "
        << best << " m off";
  }
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
