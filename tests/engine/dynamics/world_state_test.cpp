// A World restored from its state (world_state.h) steps bit for bit as the original under the same
// time-varying inputs: servo targets, forces, a teleport, live cable edits, gravity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "engine/core/error.h"
#include "engine/dynamics/world_state.h"
#include "engine/model/scene_json.h"
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

/// The scene `world` is in now, written as scene-file text and read back (sceneNow,
/// docs/scene-format.md).
SceneDef writtenAndReadBack(const World& world) {
  return sceneFromJson(nlohmann::json::parse(sceneToJson(sceneNow(world)).dump(2)), "midrun.json");
}

// A scene written mid-run and read back, text and all, builds a World that continues bit for bit.
TEST(WorldState, ASceneWrittenMidRunContinuesBitForBit) {
  for (const char* name : {"hand", "pulley", "hexagon", "winch", "wheel"}) {
    SCOPED_TRACE(name);
    World world(makeScene(name, {}), name);
    for (int k = 0; k < 40; ++k) drive(world, k);
    World resumed(writtenAndReadBack(world), "midrun.json");
    ASSERT_TRUE(sameBits(world, resumed));
    EXPECT_EQ(resumed.stepCount(), 40);
    int diverged = -1;
    for (int k = 40; k < 100 && diverged < 0; ++k) {
      drive(world, k);
      drive(resumed, k);
      if (!sameBits(world, resumed)) diverged = k;
    }
    EXPECT_EQ(diverged, -1);
  }
}

// Without its history a mid-run scene still starts where the World was: joint coordinates (which
// servo targets and limits refer to), servo targets, time and step count.
TEST(WorldState, AMidRunSceneWithoutHistoryKeepsJointValuesTimeAndSteps) {
  World world(makeScene("hand", {}), "hand");
  for (int k = 0; k < 60; ++k) drive(world, k);
  SceneDef scene = writtenAndReadBack(world);
  scene.history = nullptr;
  World fresh(scene, "midrun.json");
  EXPECT_EQ(fresh.time(), world.time());
  EXPECT_EQ(fresh.stepCount(), 60);
  bool moved = false;
  for (int j = 0; j < world.jointCount(); ++j) {
    SCOPED_TRACE(j);
    moved = moved || std::abs(world.joint(j).value) > 1e-3;
    EXPECT_NEAR(fresh.joint(j).value, world.joint(j).value, 2e-6);  // Box2D's float angles
    EXPECT_EQ(fresh.joint(j).servoTarget, world.joint(j).servoTarget);
  }
  EXPECT_TRUE(moved);  // the joints left zero: a re-zeroed coordinate would fail above
}

// JointDef::value: the coordinate reads it at the scene's pose, and servo targets are in that
// coordinate: the hand with every value and target shifted by v_j moves as the hand unshifted.
TEST(WorldState, AJointValueIsTheCoordinateAtTheScenesPose) {
  const SceneDef plain = makeScene("hand", {});
  SceneDef shifted = plain;
  for (size_t j = 0; j < shifted.joints.size(); ++j) {
    shifted.joints[j].value = 0.01 * (static_cast<double>(j) + 1);
    shifted.joints[j].servo.target += shifted.joints[j].value;
  }
  World a(plain, "hand"), b(shifted, "hand");
  for (int j = 0; j < b.jointCount(); ++j)
    EXPECT_NEAR(b.joint(j).value, shifted.joints[j].value, 1e-6) << j;
  for (int k = 0; k < 60; ++k) a.step(plain.dt, plain.substeps), b.step(plain.dt, plain.substeps);
  double moved = 0;
  for (int j = 0; j < a.jointCount(); ++j) {
    moved = std::max(moved, std::abs(a.joint(j).value));
    EXPECT_NEAR(b.joint(j).value - shifted.joints[j].value, a.joint(j).value, 1e-5) << j;
  }
  EXPECT_GT(moved, 1e-3);  // the joints moved: the comparison above has something to see
}

TEST(WorldState, AMidRunSceneEditedAfterItWasWrittenIsRefused) {
  World world(makeScene("pulley", {}), "pulley");
  for (int k = 0; k < 10; ++k) drive(world, k);
  SceneDef scene = writtenAndReadBack(world);
  scene.bodies[0].position += Vec2(0.01, 0);
  try {
    World edited(scene, "midrun.json");
    FAIL() << "an edited scene was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find("midrun.json: history: does not lead to the scene's bodies"),
        std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace cablelab
