// Redundant rigid cables (issue 11, item 3): more taut cables than the body has freedoms. The
// tensions are then not unique; the solver picks the minimum-norm distribution (tension_solver.h)
// and never answers conflicting targets with an unbounded impulse.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "tests/support/engine_test_support.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace {

using test::kDt;
constexpr double kRingMass = 5.0, kRingRadius = 0.5, kAnchorRadius = 1.5;

// A 5 kg ring at the origin held by `cables` radial rigid spokes to anchors 1 m further out,
// evenly spread from 30 degrees (so 3 spokes are two upper ones and one below).
SceneDef ring(int cables, double restLength = -1) {
  SceneDef s;
  s.name = "ring";
  BodyDef b;
  b.name = "ring";
  b.mass = kRingMass;
  b.inertia = kRingMass * kRingRadius * kRingRadius;
  b.shapes = {test::sensorDisc(kRingRadius)};
  s.bodies = {b};
  for (int k = 0; k < cables; ++k) {
    const double angle = std::numbers::pi / 6 + 2 * std::numbers::pi * k / cables;
    const Vec2 u(std::cos(angle), std::sin(angle));
    CableDef c;
    c.name = "spoke" + std::to_string(k);
    c.start = {"ring", kRingRadius * u};
    c.end = {"world", kAnchorRadius * u};
    c.restLength = restLength;
    s.cables.push_back(c);
  }
  return s;
}

Vec2 spokeDirection(const World& world, int k) {
  const Vec2 a = world.cable(k).path().front().world, b = world.cable(k).path().back().world;
  return (b - a).normalized();
}

// The minimum-norm tensions that hold the weight: T_k = max(0, u_k . lambda), lambda solving
// sum over the taut spokes of u_k u_k^T lambda = m g (found by a small active-set loop).
std::vector<double> minimumNormTensions(const World& world) {
  const int n = world.cableCount();
  std::vector<bool> taut(n, true);
  Vec2 lambda = Vec2::Zero();
  for (int pass = 0; pass < n; ++pass) {
    Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
    for (int k = 0; k < n; ++k)
      if (taut[k]) A += spokeDirection(world, k) * spokeDirection(world, k).transpose();
    lambda = A.ldlt().solve(-kRingMass * world.gravity());
    bool changed = false;
    for (int k = 0; k < n; ++k)
      if (taut[k] && spokeDirection(world, k).dot(lambda) < 0) taut[k] = false, changed = true;
    if (!changed) break;
  }
  std::vector<double> t(n);
  for (int k = 0; k < n; ++k)
    t[k] = taut[k] ? std::max(0.0, spokeDirection(world, k).dot(lambda)) : 0;
  return t;
}

TEST(RedundantCables, ARingOnManyRigidCablesStaysStillWithMinimumNormTensions) {
  for (int cables : {3, 28, 40, 100}) {
    World world(ring(cables));
    double drift = 0, turn = 0;
    for (int s = 0; s < 600; ++s) {  // 10 s
      world.step(kDt);
      drift = std::max(drift, world.body(0).position.norm());
      turn = std::max(turn, std::abs(world.body(0).angle));
    }
    EXPECT_LT(drift, 1e-3) << cables << " cables";
    EXPECT_LT(turn, 1e-3) << cables << " cables";
    // The tensions hold the weight (force balance)...
    Vec2 pull = Vec2::Zero();
    double largest = 0;
    for (int k = 0; k < cables; ++k) {
      pull += world.cable(k).tension() * spokeDirection(world, k);
      largest = std::max(largest, world.cable(k).tension());
    }
    const Vec2 weight = kRingMass * world.gravity();
    EXPECT_LT((pull + weight).norm(), 0.01 * weight.norm()) << cables << " cables";
    // ... and are the minimum-norm ones.
    const std::vector<double> expected = minimumNormTensions(world);
    for (int k = 0; k < cables; ++k)
      EXPECT_NEAR(world.cable(k).tension(), expected[k], 0.01 * largest)
          << cables << " cables, spoke " << k;
  }
}

TEST(RedundantCables, IdenticalCablesShareTheLoadEqually) {
  // A 2 kg weight hung by 1..6 identical cables from one point: K has rank 1.
  for (int cables = 1; cables <= 6; ++cables) {
    SceneDef s;
    BodyDef b;
    b.name = "weight";
    b.mass = 2;
    b.position = Vec2(0, -1);
    b.shapes = {ShapeDef{}};
    s.bodies = {b};
    for (int k = 0; k < cables; ++k) {
      CableDef c;
      c.name = "c" + std::to_string(k);
      c.start = {"world", Vec2(0, 0)};
      c.end = {"weight", Vec2(0, 0)};
      s.cables.push_back(c);
    }
    World world(s);
    for (int i = 0; i < 120; ++i) world.step(kDt);
    EXPECT_NEAR(world.body(0).position.y(), -1, 1e-4);
    for (int k = 0; k < cables; ++k)
      EXPECT_NEAR(world.cable(k).tension(), 2 * 9.81 / cables, 0.01 * 9.81) << cables;
  }
}

// A 2 kg ring on N spokes whose anchors are turned 0.8 rad from their attachments: it swings on
// two or three taut spokes while the others hang slack. The slack spokes' targets (centimetres
// short of taut) were projected with the taut ones' (tension_solver.cpp, projectTargets) and held
// the taut spokes 8 to 17 mm long for the whole 10 s (N = 5..20; 3 and 4 spokes are not
// redundant). Every spoke now keeps its length to 1 mm at every step.
TEST(RedundantCables, SlackSpokesLeaveTheTautOnesAtTheirLength) {
  for (int cables : {5, 6, 8, 12, 20}) {
    SCOPED_TRACE(std::to_string(cables) + " spokes");
    SceneDef s;
    BodyDef b;
    b.name = "ring";
    b.mass = 2;
    b.inertia = 0.18;
    b.shapes = {test::sensorDisc(0.3)};
    s.bodies = {b};
    for (int k = 0; k < cables; ++k) {
      const double angle = 0.1 + 2 * std::numbers::pi * k / cables;
      CableDef c;
      c.name = "spoke" + std::to_string(k);
      c.start = {"world", Vec2(std::cos(angle + 0.8), std::sin(angle + 0.8))};
      c.end = {"ring", 0.3 * Vec2(std::cos(angle), std::sin(angle))};
      s.cables.push_back(c);
    }
    World world(s);
    double stretch = 0, lowest = 0;
    for (int step = 0; step < 600; ++step) {
      world.step(kDt);
      for (int k = 0; k < cables; ++k) {
        stretch = std::max(stretch, world.cable(k).stretch());
        lowest = std::min(lowest, world.cable(k).tension());
      }
    }
    EXPECT_LT(stretch, 1e-3);
    EXPECT_GE(lowest, 0);
    EXPECT_GT(world.body(0).position.norm(), 0.01);  // it did swing: the spokes were tested
  }
}

TEST(RedundantCables, ConflictingTargetsNeverThrowTheBody) {
  // Every spoke 1 mm too short for the pose: no pose satisfies all of them (the ring cannot move
  // towards every anchor at once), so the targets conflict on a rank-2 K. The least-squares
  // answer leaves the ring where it is, at bounded tension.
  for (int cables : {28, 40}) {
    World world(ring(cables, kAnchorRadius - kRingRadius - 1e-3));
    double drift = 0, largest = 0;
    for (int s = 0; s < 600; ++s) {
      world.step(kDt);
      drift = std::max(drift, world.body(0).position.norm());
      for (int k = 0; k < cables; ++k) largest = std::max(largest, world.cable(k).tension());
    }
    EXPECT_LT(drift, 1e-3) << cables << " cables";
    EXPECT_LT(std::abs(world.body(0).angle), 1e-2) << cables << " cables";
    EXPECT_LT(largest, 10 * kRingMass * 9.81) << cables << " cables";
  }
}

// What a rigid ring on spokes tells of a run: how far it drifted and turned, how fast it spun, its
// largest tension, and how far the tensions at the end are from balancing its weight (N).
struct RingRun {
  double drift = 0, turn = 0, spin = 0, largest = 0, imbalance = 0;
  bool held = false;  // World said it held rows no pose meets
};

RingRun runRing(const SceneDef& scene, double seconds, int substeps) {
  World world(scene);
  RingRun run;
  const int steps = static_cast<int>(std::lround(seconds / kDt));
  for (int s = 0; s < steps; ++s) {
    world.step(kDt, substeps);
    const BodyState& b = world.body(0);
    run.drift = std::max(run.drift, b.position.norm());
    run.turn = std::max(run.turn, std::abs(b.angle));
    run.spin = std::max(run.spin, std::abs(b.angularVelocity));
    for (int k = 0; k < world.cableCount(); ++k)
      run.largest = std::max(run.largest, world.cable(k).tension());
  }
  Vec2 net = world.gravity() / world.body(0).invMass;
  for (int k = 0; k < world.cableCount(); ++k) {
    const auto& path = world.cable(k).path();
    const bool fromRing = path.front().body == 0;  // the pull on the ring points to the anchor
    net += world.cable(k).tension() * (fromRing ? 1 : -1) * spokeDirection(world, k);
  }
  run.imbalance = net.norm();
  for (const std::string& w : world.warnings())
    run.held |= w.find("none meets") != std::string::npos;
  return run;
}

TEST(RedundantCables, SpokesWhoseRestLengthsNoPoseMeetsHoldTheRingStill) {
  // Every third spoke 1 cm short, the next 2 cm: no pose meets them, and the correction that
  // shortens a too-long rigid cable asks for a velocity no motion has. The start-of-step solve
  // answered with impulses up to 1e14 N s, the rings spun at 270..6600 rad/s and drifted
  // 0.1..1.3 m; the solve holds such rows at their lengths instead (and World says so), and the
  // ring hangs still on tensions that carry its weight.
  const double weight = kRingMass * 9.81;
  const SceneDef file = loadSceneFile(test::dataPath("redundant/overconstrained_ring.json"));
  std::vector<std::pair<std::string, SceneDef>> scenes = {{"the file's 40 spokes", file}};
  for (const int cables : {28, 40, 100}) {
    SceneDef s = ring(cables);
    for (int k = 0; k < cables; ++k)
      s.cables[k].restLength = kAnchorRadius - kRingRadius - 0.01 * (k % 3);
    scenes.emplace_back(std::to_string(cables) + " spokes", s);
  }
  for (const auto& [name, scene] : scenes)
    for (const int substeps : {1, 4}) {
      const RingRun run = runRing(scene, 10, substeps);
      const std::string what = name + ", " + std::to_string(substeps) + " sub-steps";
      EXPECT_LT(run.drift, 1e-3) << what;
      EXPECT_LT(run.turn, 1e-2) << what;
      EXPECT_LT(run.spin, 0.1) << what;
      EXPECT_LT(run.largest, 10 * weight) << what;
      EXPECT_LT(run.imbalance, 0.02 * weight) << what;  // 1.1% at most (100, 4)
      EXPECT_TRUE(run.held) << what;                    // and World said so
    }
}

}  // namespace
}  // namespace cablelab
