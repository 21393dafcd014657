// A World restored from its state (world_state.h) steps bit for bit as the original under the same
// time-varying inputs: servo targets, forces, a teleport, live cable edits, gravity.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "engine/core/error.h"
#include "engine/dynamics/world_state.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {
namespace {

/// The same input to both worlds at step k (time-varying).
void drive(World& w, int k) {
  for (int j = 0; j < w.jointCount(); ++j) w.setServoTarget(j, 0.05 * std::sin(0.1 * k + j));
  if (w.bodyCount() > 0 && k % 7 == 0)
    w.applyForce(w.bodyCount() - 1, Vec2(0.3 * std::cos(0.2 * k), 0.1), w.body(0).position);
  w.step(w.scene().dt, w.scene().substeps);
}

/// Every bit of the state a user reads.
bool sameBits(const World& a, const World& b) {
  if (a.time() != b.time() || a.stepCount() != b.stepCount()) return false;
  for (int i = 0; i < a.bodyCount(); ++i) {
    const BodyState &p = a.body(i), &q = b.body(i);
    const double u[6] = {p.position.x(), p.position.y(), p.angle,
                         p.velocity.x(), p.velocity.y(), p.angularVelocity};
    const double v[6] = {q.position.x(), q.position.y(), q.angle,
                         q.velocity.x(), q.velocity.y(), q.angularVelocity};
    if (std::memcmp(u, v, sizeof u) != 0) return false;
  }
  for (int i = 0; i < a.cableCount(); ++i)
    if (a.cable(i).length() != b.cable(i).length() || a.cable(i).tension() != b.cable(i).tension())
      return false;
  for (int i = 0; i < a.jointCount(); ++i)
    if (a.joint(i).value != b.joint(i).value) return false;
  return true;
}

TEST(WorldState, AForkStepsBitForBitAsTheOriginal) {
  for (const char* name : {"hand", "pulley", "hexagon", "capstan", "wheel"}) {
    SCOPED_TRACE(name);
    World world(makeScene(name, {}), name);
    for (int k = 0; k < 40; ++k) drive(world, k);
    world.setBodyTransform(0, world.body(0).position + Vec2(1e-3, 0), world.body(0).angle);
    if (world.cableCount() > 0) {
      const CableParameters& p = world.cable(0).parameters();
      world.setCableParameters(0, p.restLength * 1.001, p.stiffness, p.preload, p.damping);
    }
    world.setGravity(Vec2(0.1, -9.7));
    const WorldState state = captureState(world, name);
    EXPECT_EQ(state.time, world.time());
    std::unique_ptr<World> fork = restoreWorld(state);
    ASSERT_TRUE(sameBits(world, *fork));
    EXPECT_EQ(fork->history().inputs().size(), world.history().inputs().size());
    int diverged = -1;
    for (int k = 40; k < 100 && diverged < 0; ++k) {
      drive(world, k);
      drive(*fork, k);
      if (!sameBits(world, *fork)) diverged = k;
    }
    EXPECT_EQ(diverged, -1);
  }
}

// A pose made while paused (World::poseBody, the sandbox's drag) moves bodies outside step():
// the fork must replay it, or it starts from the unposed bodies.
TEST(WorldState, AForkAfterAPoseStepsBitForBitAsTheOriginal) {
  for (const char* name : {"hexagon", "pulley", "hand"}) {
    SCOPED_TRACE(name);
    World world(makeScene(name, {}), name);
    for (int k = 0; k < 20; ++k) drive(world, k);
    const int body = world.bodyCount() - 1;
    const Vec2 start = world.body(body).position;
    world.poseBody(body, Vec2::Zero(), start + Vec2(0.3, -0.4));
    world.poseBody(body, Vec2::Zero(), start + Vec2(-0.2, 0.1), true);
    world.settlePose();
    ASSERT_NE(world.body(body).position, start);  // the pose moved it: the check below can fail
    std::unique_ptr<World> fork = restoreWorld(captureState(world, name));
    ASSERT_TRUE(sameBits(world, *fork));
    int diverged = -1;
    for (int k = 20; k < 80 && diverged < 0; ++k) {
      drive(world, k);
      drive(*fork, k);
      if (!sameBits(world, *fork)) diverged = k;
    }
    EXPECT_EQ(diverged, -1);
  }
}

TEST(WorldState, AStateNamingNoBodyOfTheSceneIsBadInput) {
  World world(makeScene("pulley", {}), "pulley");
  WorldState state = captureState(world, "pulley");
  state.inputs.push_back({WorldInput::Kind::BodyVelocity, 99});
  EXPECT_THROW(restoreWorld(state), InputError);
}

TEST(WorldState, StepsInARowAreKeptAsOneInput) {
  World world(makeScene("pulley", {}), "pulley");
  for (int k = 0; k < 50; ++k) world.step(1.0 / 60, 2);
  world.step(1.0 / 120, 2);
  ASSERT_EQ(world.history().inputs().size(), 2u);
  EXPECT_EQ(world.history().inputs()[0].count, 50);
}

}  // namespace
}  // namespace cablelab
