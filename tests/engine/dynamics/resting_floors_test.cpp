// A body resting at its pulley keeps the last sub-step's impulses (docs/floors.md, "Resting at a
// pulley"): its floors warm-start Newton, and a redundant island whose warm start already meets
// every row skips the LCPs. It must follow Newton's motion (setKeptImpulses(false): the solve
// before), and it must actually be taken where a tackle's block rests at its top sheave.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/dynamics/cable_solver.h"
#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/body_states.h"

namespace cablelab {
namespace resting_floors_test {  // named: unity batches join test files

constexpr double kGravity = 9.81;

struct Tackle {
  double mLoad = 0.8, mEffort = 1.2, r = 0.15, dt = 1.0 / 60;
  int substeps = 1;
  double pullAt = -1;  // s: the block pulled down at 3 m_load g for 0.5 s from then, < 0: never
};

struct Motion {
  std::vector<double> poses, tensions;  // every body's (x, y, theta) and the rope's, per step
  int kept = 0;                         // islands that kept their impulses, all sub-steps
  int steps = 0;
};

Motion runTackle(const Tackle& t, double seconds, bool kept) {
  setKeptImpulses(kept);
  World world(makeScene("tackle", {{"m_load", t.mLoad}, {"m_effort", t.mEffort}, {"r", t.r}}));
  Motion run;
  run.steps = static_cast<int>(std::lround(seconds / t.dt));
  for (int i = 0; i < run.steps; ++i) {
    const double time = i * t.dt;
    if (t.pullAt >= 0 && time >= t.pullAt && time < t.pullAt + 0.5)
      world.applyForce(0, Vec2(0, -3 * t.mLoad * kGravity), world.body(0).position);
    world.step(t.dt, t.substeps);
    run.kept += world.lastStepStats().keptImpulses;
    for (int b = 0; b < world.bodyCount(); ++b) {
      const BodyState& s = world.body(b);
      run.poses.insert(run.poses.end(), {s.position.x(), s.position.y(), s.angle});
    }
    run.tensions.push_back(world.cable(0).tension());
  }
  setKeptImpulses(true);
  return run;
}

// Random tackles whose block rises to its top sheave and rests there (the load under four times
// the effort), at 30, 60 and 120 Hz, 1 and 2 sub-steps, half of them pulled off the sheave at
// 3 s and rising back. Measured over 6 s: poses within 2.4e-8 m of Newton's, tensions within
// 5.1e-9 of their scale, the impulses kept in 8 of the 10 (on 1 to 36% of their sub-steps; the
// other two had not come to rest). The poses differ by where Newton stops at rest: each of its
// answers is within its tolerance of the root, and below the length slop nothing takes a drift
// of that size back (in one tackle Newton's block sank 1.7e-9 m/s where the kept one stood).
TEST(RestingAtAPulley, RandomTacklesFollowNewtonsMotion) {
  std::mt19937 rng(36);
  std::uniform_real_distribution<double> unit(0, 1);
  const double rates[] = {30, 60, 120};
  int keptCases = 0;
  for (int k = 0; k < 10; ++k) {
    Tackle t;
    t.mEffort = 0.3 + 2.7 * unit(rng);
    t.mLoad = t.mEffort * (0.2 + 3.3 * unit(rng));
    t.r = 0.08 + 0.17 * unit(rng);
    t.dt = 1 / rates[rng() % 3];
    t.substeps = 1 + static_cast<int>(rng() % 2);
    t.pullAt = k % 2 ? 3.0 : -1.0;
    SCOPED_TRACE("m_load " + std::to_string(t.mLoad) + " m_effort " + std::to_string(t.mEffort) +
                 " r " + std::to_string(t.r) + " dt " + std::to_string(t.dt) + " x" +
                 std::to_string(t.substeps) + (t.pullAt > 0 ? " pulled" : ""));
    const Motion kept = runTackle(t, 6.0, true), newton = runTackle(t, 6.0, false);
    ASSERT_EQ(kept.poses.size(), newton.poses.size());
    EXPECT_LT(test::largestDifference(kept.poses, newton.poses), 2e-7);
    EXPECT_LT(test::largestDifference(kept.tensions, newton.tensions),
              2e-8 * test::largestMagnitude(newton.tensions, 1e-9));
    EXPECT_EQ(newton.kept, 0);
    keptCases += kept.kept > 0;
  }
  EXPECT_GE(keptCases, 7);
}

// The built-in tackle with a light load (`cablelab run tackle --set m_load=0.8`) rests at its
// top sheave from 1.5 s on. Over 3 to 10 s: the impulses kept on most steps (measured 285 of
// 420), where Newton ran three chord iterations on each, every kept step with no LCP at all; the
// rope holds the effort (m_effort g, to 1e-7) and the bodies stay where they were (measured:
// within 1.2e-9 m, Newton's within 9.9e-10 m).
TEST(RestingAtAPulley, TheTacklesBlockKeepsItsImpulsesAtItsTopSheave) {
  for (const bool kept : {true, false}) {
    SCOPED_TRACE(kept ? "kept" : "Newton");
    setKeptImpulses(kept);
    World world(makeScene("tackle", {{"m_load", 0.8}}));
    const double dt = world.scene().dt;
    for (int i = 0; i * dt < 3.0; ++i) world.step(dt);
    const Vec2 block = world.body(0).position, effort = world.body(1).position;
    int keptSteps = 0, steps = 0;
    double lcpWork = 0;  // iterations of the main solve a kept step took (the midpoint's: 1)
    for (int i = 0; i * dt < 7.0; ++i, ++steps) {
      world.step(dt);
      const StepStats& s = world.lastStepStats();
      keptSteps += s.keptImpulses;
      if (s.keptImpulses) lcpWork += s.solverIterations - s.midpointFallbacks;
      EXPECT_NEAR(world.cable(0).tension(), 1.2 * kGravity, 1e-7 * 1.2 * kGravity);
    }
    EXPECT_LT((world.body(0).position - block).norm(), 1e-8);
    EXPECT_LT((world.body(1).position - effort).norm(), 1e-8);
    if (kept) {
      EXPECT_GE(keptSteps, steps / 2);
      EXPECT_EQ(lcpWork, 0);
    } else {
      EXPECT_EQ(keptSteps, 0);
    }
  }
  setKeptImpulses(true);
}

}  // namespace resting_floors_test
}  // namespace cablelab
