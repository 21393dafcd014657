// The sparse path for big islands (engine/dynamics/sparse_island.h): it solves the dense path's
// problem, so both give the same tensions and trajectories; a hanging chain carries the weight
// below each link; a slack row in the middle of the island pulls with zero tension.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/dynamics/sparse_island.h"
#include "engine/dynamics/world.h"
#include "engine/scenes/scale_scenes.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {
namespace {

constexpr double kIslandG = 9.81;
constexpr int kAlwaysDense = 1 << 30;  // threshold that keeps every island dense

// Restores the default threshold whatever a test does.
struct ThresholdGuard {
  explicit ThresholdGuard(int rows) { setSparseIslandThreshold(rows); }
  ~ThresholdGuard() { setSparseIslandThreshold(-1); }
};

// A chain just above the default threshold, masses 1 + 0.05 k kg (a wrong mass or a row
// swapped gives a wrong tension), at rest or swinging.
SceneDef islandChain(int n, double swing) {
  SceneDef s = makeHangingChain(n);
  for (size_t k = 0; k < s.bodies.size(); ++k) {
    BodyDef& b = s.bodies[k];
    b.mass = 1 + 0.05 * static_cast<double>(k);
    b.inertia *= b.mass;
    b.velocity = Vec2(swing * std::sin(0.3 * static_cast<double>(k)), 0);
  }
  return s;
}

struct IslandRun {
  std::vector<std::vector<double>> tensions;  // per step, per cable
  std::vector<BodyState> final;
  long sparseSolves = 0;
};

IslandRun runIsland(const SceneDef& scene, int threshold, int steps, int substeps = 1) {
  ThresholdGuard guard(threshold);
  World world(scene, "test");
  IslandRun r;
  for (int i = 0; i < steps; ++i) {
    world.step(scene.dt, substeps);
    r.sparseSolves += world.lastStepStats().sparseIslands;
    std::vector<double> t;
    for (int c = 0; c < world.cableCount(); ++c) t.push_back(world.cable(c).tension());
    r.tensions.push_back(t);
  }
  for (int b = 0; b < world.bodyCount(); ++b) r.final.push_back(world.body(b));
  return r;
}

// Same tensions every step and the same final state, relative to their scales.
void expectSameIsland(const IslandRun& sparse, const IslandRun& dense, double tolerance) {
  ASSERT_GT(sparse.sparseSolves, 0);
  ASSERT_EQ(dense.sparseSolves, 0);
  for (size_t i = 0; i < dense.tensions.size(); ++i) {
    const double scale = *std::max_element(dense.tensions[i].begin(), dense.tensions[i].end());
    for (size_t c = 0; c < dense.tensions[i].size(); ++c)
      ASSERT_NEAR(sparse.tensions[i][c], dense.tensions[i][c], tolerance * scale)
          << "step " << i << " cable " << c;
  }
  for (size_t b = 0; b < dense.final.size(); ++b) {
    const BodyState &s = sparse.final[b], &d = dense.final[b];
    EXPECT_NEAR((s.position - d.position).norm(), 0, tolerance * (1 + d.position.norm())) << b;
    EXPECT_NEAR((s.velocity - d.velocity).norm(), 0, tolerance * (1 + d.velocity.norm())) << b;
  }
}

TEST(SparseIsland, SwingingChainMatchesTheDensePath) {
  const SceneDef s = islandChain(sparseIslandThreshold() + 2, 0.5);
  expectSameIsland(runIsland(s, 0, 120), runIsland(s, kAlwaysDense, 120), 1e-9);
}

// Stiff elastic links (omega h > 1: the main solve, with compliance rows) and sub-steps.
TEST(SparseIsland, ElasticLinksMatchTheDensePath) {
  SceneDef s = islandChain(sparseIslandThreshold() + 2, 0.3);
  for (size_t k = 0; k < s.cables.size(); k += 3) {
    s.cables[k].stiffness = 2e6;
    s.cables[k].damping = 50;
  }
  expectSameIsland(runIsland(s, 0, 60, 2), runIsland(s, kAlwaysDense, 60, 2), 1e-9);
}

// A curtain of cables (a 2-D mesh: horizontal links carry no load, they sit at the edge of
// complementarity).
TEST(SparseIsland, NetMatchesTheDensePath) {
  const SceneDef s = makeCableNet(6, 6);
  ASSERT_GT(static_cast<int>(s.cables.size()), sparseIslandThreshold());
  expectSameIsland(runIsland(s, 0, 60), runIsland(s, kAlwaysDense, 60), 1e-9);
}

// Link k of a hanging chain of n carries the weight of the discs below it.
void expectEachLinkCarriesTheWeightBelow(const World& world, const SceneDef& s, int n) {
  double below = 0;
  for (int k = n - 1; k >= 0; --k) {
    below += s.bodies[k].mass * kIslandG;
    EXPECT_NEAR(world.cable(k).tension(), below, 1e-6 * below) << "link " << k;
  }
}
// At rest the link above body k carries the weight of bodies k..n-1; lengths stay put.
TEST(SparseIsland, HangingChainCarriesTheWeightBelow) {
  const int n = sparseIslandThreshold() + 2;
  const SceneDef s = islandChain(n, 0);
  ThresholdGuard guard(-1);
  World world(s, "chain");
  std::vector<double> rest;
  for (int c = 0; c < n; ++c) rest.push_back(world.cable(c).length());
  double worst = 0;
  for (int i = 0; i < 600; ++i) {  // 10 s
    world.step(s.dt, 1);
    ASSERT_EQ(world.lastStepStats().sparseIslands, 1);
    for (int c = 0; c < n; ++c)
      worst = std::max(worst, std::abs(world.cable(c).length() - rest[c]));
  }
  EXPECT_LT(worst, 1e-6);
  expectEachLinkCarriesTheWeightBelow(world, s, n);
}

// Swinging, the lengths stay within the rigid targets' slop (kLengthSlop, 1e-5 m, plus float
// rounding of Box2D's poses 24 m down: 1.5e-5 m measured, both paths) over 10 s, and the
// energy within 0.01% (0.18 J of 4830 J measured).
TEST(SparseIsland, SwingingChainHoldsItsLengthsForTenSeconds) {
  ThresholdGuard guard(-1);
  const SceneDef s = makeHangingChain(40);
  World world(s, "chain");
  std::vector<double> rest;
  for (int c = 0; c < world.cableCount(); ++c) rest.push_back(world.cable(c).length());
  const double e0 = world.energy();
  double worst = 0, drift = 0;
  for (int i = 0; i < 600; ++i) {
    world.step(s.dt, 1);
    ASSERT_EQ(world.lastStepStats().sparseIslands, 1);
    for (int c = 0; c < world.cableCount(); ++c)
      worst = std::max(worst, std::abs(world.cable(c).length() - rest[c]));
    drift = std::max(drift, std::abs(world.energy() - e0));
  }
  EXPECT_LT(worst, 2e-5);
  EXPECT_LT(drift, 1e-4 * std::abs(e0));
}

// Slack rows in the middle of the island: extra cables from the side of body k to the other side
// of body k + 2 (off the chain's line, so not redundant), 5 cm longer than the gap, pull with zero
// tension (complementarity) and leave the chain's tensions as without them. They start active (the
// LCP's warm start), so the pivoting must drop them.
TEST(SparseIsland, SlackRowsInTheMiddleCarryNothing) {
  const int n = sparseIslandThreshold();
  SceneDef s = islandChain(n, 0);
  for (int k = 10; k + 2 < n; k += 7) {
    CableDef c;
    c.name = "slack" + std::to_string(k);
    c.start = {s.bodies[k].name, Vec2(0.1, 0)};
    c.end = {s.bodies[k + 2].name, Vec2(-0.1, 0)};
    c.restLength = std::hypot(s.bodies[k].position.y() - s.bodies[k + 2].position.y(), 0.2) + 0.05;
    s.cables.push_back(c);
  }
  ThresholdGuard guard(-1);
  World world(s, "slack");
  for (int i = 0; i < 120; ++i) {
    world.step(s.dt, 1);
    ASSERT_EQ(world.lastStepStats().sparseIslands, 1);
    for (int c = n; c < world.cableCount(); ++c) ASSERT_EQ(world.cable(c).tension(), 0) << c;
  }
  expectEachLinkCarriesTheWeightBelow(world, s, n);
}

// Islands of up to the threshold's rows keep the dense path; one more row takes the sparse one.
TEST(SparseIsland, SmallIslandsKeepTheDensePath) {
  ThresholdGuard guard(-1);
  const SceneDef small = islandChain(sparseIslandThreshold(), 0.3);
  World world(small, "small");
  world.step(small.dt, 1);
  EXPECT_EQ(world.lastStepStats().sparseIslands, 0);
  const SceneDef big = islandChain(sparseIslandThreshold() + 1, 0.3);
  World bigWorld(big, "big");
  bigWorld.step(big.dt, 1);
  EXPECT_EQ(bigWorld.lastStepStats().sparseIslands, 1);
}

// Every built-in scene (the hand: its fingers' cables and joints) keeps the dense path.
TEST(SparseIsland, BuiltInScenesKeepTheDensePath) {
  ThresholdGuard guard(-1);
  for (const SceneInfo& info : builtinScenes()) {
    const SceneDef s = makeScene(info.name);
    World world(s, info.name);
    for (int i = 0; i < 30; ++i) {
      world.step(s.dt, s.substeps);
      ASSERT_EQ(world.lastStepStats().sparseIslands, 0) << info.name;
    }
  }
}

// A chain with jointed bodies: every fifth disc carries a 0.5 kg bob on a revolute joint 0.15 m
// to its side (a body only a joint moves, a dof of the island all the same). The joints enter
// the KKT system as equality rows; the dense path projects onto them.
SceneDef jointedChain(int n) {
  SceneDef s = islandChain(n, 0.4);
  for (int k = 0; k < n; k += 5) {
    BodyDef bob = s.bodies[k];
    bob.name = "bob" + std::to_string(k);
    bob.position += Vec2(0.3, 0);
    bob.mass = 0.5;
    s.bodies.push_back(bob);
    JointDef j;
    j.name = "hinge" + std::to_string(k);
    j.bodyA = s.bodies[k].name;
    j.bodyB = bob.name;
    j.anchor = s.bodies[k].position + Vec2(0.15, 0);
    s.joints.push_back(j);
  }
  return s;
}

// The largest cable length error and hinge gap error (|bob - disc| - 0.3) over 10 s.
std::pair<double, double> jointedErrors(const SceneDef& s, int threshold) {
  ThresholdGuard guard(threshold);
  World world(s, "jointed");
  const int n = world.cableCount();
  std::vector<double> rest;
  for (int c = 0; c < n; ++c) rest.push_back(world.cable(c).length());
  double length = 0, hinge = 0;
  for (int i = 0; i < 600; ++i) {
    world.step(s.dt, 1);
    for (int c = 0; c < n; ++c)
      length = std::max(length, std::abs(world.cable(c).length() - rest[c]));
    for (int k = 0, bob = n; k < n; k += 5, ++bob)
      hinge = std::max(hinge,
                       std::abs((world.body(bob).position - world.body(k).position).norm() - 0.3));
  }
  return {length, hinge};
}

// Same to 1e-9 over the first 15 steps (4e-11 measured). Later the two drift apart (5e-8 of the
// largest tension by step 35, 6e-5 at 36, where one path's warm start settles and the other's
// starts again from zero: the paths regularise the LCP by 1e-12 (1 + K_ii) with K_ii measured
// through M^-1 here, M'^-1 projected there), so over 10 s they must hold the lengths and the
// hinges as well as each other (both: 2.7 mm, 2.5e-6 m measured: Box2D's joints act after the
// cable forces).
TEST(SparseIsland, JointedChainMatchesTheDensePath) {
  const SceneDef s = jointedChain(sparseIslandThreshold() + 2);
  expectSameIsland(runIsland(s, 0, 15), runIsland(s, kAlwaysDense, 15), 1e-9);
  const auto [sparseLength, sparseHinge] = jointedErrors(s, 0);
  const auto [denseLength, denseHinge] = jointedErrors(s, kAlwaysDense);
  EXPECT_LT(sparseLength, 1.1 * denseLength + 1e-6);
  EXPECT_LT(sparseHinge, 1.1 * denseHinge + 1e-7);
}

}  // namespace
}  // namespace cablelab
