// The energy-consistent solve chosen per cable island (docs/cables.md, "When it applies"): the
// partition, undamped parts that keep their energy beside jointed and touching ones, and the
// trajectories of worlds where every island gets the same solve as the whole-world choice gave.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/dynamics/cable_islands.h"
#include "engine/dynamics/world.h"
#include "tests/support/busy_scene.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

using test::kDt;

// Largest |E - E0| of each undamped part of the busy world over `seconds`, over its largest
// kinetic energy.
struct PartDrift {
  double sling = 0, band = 0;
  int stepsWithBothSolves = 0, steps = 0;
};

PartDrift runBusy(bool perIsland, double seconds) {
  World world(test::busy(true));
  world.setMidpointPerIsland(perIsland);
  const std::string parts[2] = {"sling.", "band."};
  double e0[2], worst[2] = {0, 0}, scale[2] = {0, 0}, kinetic = 0;
  for (int p = 0; p < 2; ++p) e0[p] = test::partEnergy(world, parts[p], kinetic);
  PartDrift r;
  r.steps = static_cast<int>(std::lround(seconds / kDt));
  for (int s = 0; s < r.steps; ++s) {
    world.step(kDt, world.scene().substeps);
    for (int p = 0; p < 2; ++p) {
      worst[p] = std::max(worst[p], std::abs(test::partEnergy(world, parts[p], kinetic) - e0[p]));
      scale[p] = std::max(scale[p], kinetic);
    }
    // Some island went to the midpoint solve while the world has joints and contacts (the main
    // solve ran too: the hexagon's and the hand's cables have tensions).
    const int hexCable = world.findCable("hex.cable");
    r.stepsWithBothSolves += world.lastStepStats().midpointSolves > 0 && hexCable >= 0 &&
                             world.cable(hexCable).tension() > 0;
  }
  r.sling = worst[0] / scale[0];
  r.band = worst[1] / scale[1];
  return r;
}

TEST(MidpointIslands, CablesSharingAMovingBodyAreOneIslandAndPrescribedBodiesJoinNone) {
  // a, b, c dynamic; k kinematic. c0 world-a and c1 a-b share a; c2 world-c and c4 k-c share c;
  // c3 k-d shares only k (kinematic) with c4: its own island; c5 world-k moves nothing: idle.
  SceneDef s;
  for (const char* name : {"a", "b", "c", "d", "k"}) {
    BodyDef b;
    b.name = name;
    b.position = Vec2(2.0 * s.bodies.size(), 0);
    if (name[0] == 'k') b.type = BodyType::Kinematic;
    s.bodies.push_back(b);
  }
  auto cable = [&](const std::string& from, const std::string& to) {
    CableDef c;
    c.name = "c" + std::to_string(s.cables.size());
    c.start = {from, from == "world" ? Vec2(1, 5) : Vec2::Zero()};
    c.end = {to, Vec2::Zero()};
    c.restLength = 10;
    s.cables.push_back(c);
  };
  cable("world", "a");
  cable("a", "b");
  cable("world", "c");
  cable("k", "d");
  cable("k", "c");
  cable("world", "k");
  World world(s);
  std::vector<BodyState> bodies;
  std::vector<Cable> cables;
  for (int b = 0; b < 5; ++b) bodies.push_back(world.body(b));
  for (int c = 0; c < world.cableCount(); ++c) cables.push_back(world.cable(c));
  CableIslands islands;
  islands.build(bodies, cables, false);
  ASSERT_EQ(islands.count(), 3);
  auto list = [](std::span<const int> v) { return std::vector<int>(v.begin(), v.end()); };
  EXPECT_EQ(list(islands.cables(0)), (std::vector<int>{0, 1}));
  EXPECT_EQ(list(islands.cables(1)), (std::vector<int>{2, 4}));
  EXPECT_EQ(list(islands.cables(2)), (std::vector<int>{3}));
  EXPECT_EQ(list(islands.idle()), (std::vector<int>{5}));
  islands.build(bodies, cables, true);  // the whole-world choice: one island
  ASSERT_EQ(islands.count(), 1);
  EXPECT_EQ(list(islands.cables(0)), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(list(islands.idle()), (std::vector<int>{5}));
}

TEST(MidpointIslands, UndampedPartsOfTheBusySceneKeepTheirEnergyBesideJointsAndContacts) {
  // The sling and the band share the world with the hexagon on its pivot, the Atwood machine
  // landing on the ground and the hand (joints, servos, contacts). Each part's energy is its own
  // (no cable or contact between parts). With the whole-world choice every cable goes to the
  // main solve, whose implicit springs damp the unresolved ones.
  const double seconds = 12;
  const PartDrift perIsland = runBusy(true, seconds);
  EXPECT_LT(perIsland.sling, 0.02);
  EXPECT_LT(perIsland.band, 0.02);
  EXPECT_GT(perIsland.stepsWithBothSolves, perIsland.steps * 9 / 10);
  const PartDrift whole = runBusy(false, seconds);
  // No step takes both solves there. Both parts take the main solve's own midpoint rule
  // (cable_solver.cpp, stage 5a), which since it balances each row's work (stage 6a) keeps the
  // band's energy (0.1%; 10% and more before), and since its elastic rows pull along J at the
  // midpoint pose (stage 6e) the sling's, a square spinning in it whose corners join and leave
  // the cable (measured 3e-6; a fifth of its energy scale, 0.22, along J0).
  EXPECT_LT(whole.sling, 0.02);
  EXPECT_LT(whole.band, 0.02);
  EXPECT_EQ(whole.stepsWithBothSolves, 0);
  std::printf("per island: sling %.2e band %.2e; whole world: sling %.3f band %.3f\n",
              perIsland.sling, perIsland.band, whole.sling, whole.band);
}

// Largest difference in pose and velocity between two worlds of the same scene over `steps`,
// one choosing per island, the other for the whole world; `midpointSteps` counts the steps with
// a midpoint solve in the first.
struct Gap {
  double largest = 0;
  int midpointSteps = 0;                   // steps with a midpoint solve (per island)
  long islandSolves = 0, wholeSolves = 0;  // midpoint solves of each world
};

Gap trajectoryGap(const SceneDef& scene, int steps) {
  World islands(scene), whole(scene);
  whole.setMidpointPerIsland(false);
  Gap r;
  double& gap = r.largest;
  for (int s = 0; s < steps; ++s) {
    islands.step(kDt, scene.substeps);
    whole.step(kDt, scene.substeps);
    r.midpointSteps += islands.lastStepStats().midpointSolves > 0;
    r.islandSolves += islands.lastStepStats().midpointSolves;
    r.wholeSolves += whole.lastStepStats().midpointSolves;
    for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) {
      const BodyState &x = islands.body(b), &y = whole.body(b);
      gap = std::max({gap, (x.position - y.position).norm(), std::abs(x.angle - y.angle),
                      (x.velocity - y.velocity).norm(),
                      std::abs(x.angularVelocity - y.angularVelocity)});
    }
  }
  return r;
}

TEST(MidpointIslands, OnlyMidpointIslandsFollowTheWholeWorldMidpointTrajectory) {
  // The sling and the band: two islands, each solved on its own, against one solve of both.
  const Gap g = trajectoryGap(test::undampedParts(), 600);
  EXPECT_EQ(g.midpointSteps, 600);
  EXPECT_EQ(g.islandSolves, 2 * g.wholeSolves);  // two islands, one whole-world solve
  EXPECT_LT(g.largest, 1e-12);
}

TEST(MidpointIslands, OnlyExcludedIslandsFollowTheMainSolveTrajectory) {
  // The hexagon on its pivot and the hand (joints, servos, the grasped box touching): no island
  // is the midpoint solve's, the main solve takes every cable as before.
  SceneDef s;
  s.name = "excluded";
  test::addPart(s, makeScene("hexagon", {{"omega", 4.0}}), "hex.", Vec2(-8, 0));
  test::addPart(s, makeScene("hand"), "hand.", Vec2(0, 40));
  const Gap g = trajectoryGap(s, 600);
  EXPECT_EQ(g.midpointSteps, 0);
  EXPECT_EQ(g.wholeSolves, 0);
  EXPECT_LT(g.largest, 1e-12);
}

TEST(MidpointIslands, AMidpointIslandBesideAMainOneMovesAsItDoesAlone) {
  // The undamped band beside a pendulum on a pivot that a rigid cable tethers (jointed: the main
  // solve's). Neither has wrap events, and the band's own modes set the refinement, so the band
  // takes the same steps as alone and, solved on its own, moves exactly as alone. With the
  // whole-world choice the pendulum's joint sent the band to the main solve too.
  const SceneDef alone = test::undampedBand();
  SceneDef mixed = alone;
  BodyDef bob;
  bob.name = "bob";
  bob.position = Vec2(5, -1);
  bob.velocity = Vec2(2, 0);
  mixed.bodies.push_back(bob);
  JointDef pivot;
  pivot.name = "pivot";
  pivot.bodyB = "bob";
  pivot.anchor = Vec2(5, 0);
  mixed.joints.push_back(pivot);
  CableDef tether;
  tether.name = "tether";
  tether.start = {"world", Vec2(7, -1)};
  tether.end = {"bob", Vec2::Zero()};
  tether.restLength = 1.9;
  mixed.cables.push_back(tether);
  for (const bool perIsland : {true, false}) {
    SCOPED_TRACE(perIsland ? "per island" : "whole world");
    World one(alone), two(mixed);
    two.setMidpointPerIsland(perIsland);
    double gap = 0, pulled = 0;
    int midpointSteps = 0;
    for (int s = 0; s < 600; ++s) {
      one.step(kDt, alone.substeps);
      two.step(kDt, mixed.substeps);
      const BodyState &x = one.body(0), &y = two.body(0);
      gap = std::max({gap, (x.position - y.position).norm(), (x.velocity - y.velocity).norm()});
      pulled = std::max(pulled, two.cable(two.findCable("tether")).tension());
      midpointSteps += two.lastStepStats().midpointSolves > 0;
    }
    EXPECT_GT(pulled, 0.5);  // the tether held the pendulum (N; measured 0.99)
    if (perIsland) {
      EXPECT_EQ(midpointSteps, 600);
      EXPECT_LT(gap, 1e-12);
    } else {
      EXPECT_EQ(midpointSteps, 0);
      // The main solve's rule moves the band otherwise (measured 4.2e-6: both pull along the
      // discrete gradient, but the two solves settle and stop apart).
      EXPECT_GT(gap, 1e-6);
    }
  }
}

}  // namespace
}  // namespace cablelab
