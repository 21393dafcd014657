// The MuJoCo mapping of the benchmark: same bodies, same cable, same motion as cablelab.
#ifdef CABLELAB_HAVE_MUJOCO
#include "engine/mujoco/mujoco_world.h"

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/dynamics/world.h"
#include "engine/scenes/scale_scenes.h"

namespace cablelab {
namespace {

TEST(MujocoWorld, StepsTheSameAtwoodMachinesAsCablelab) {
  const SceneDef scene = makeAtwoodMachines(4);
  MujocoWorld mj(scene);
  World world(scene);
  EXPECT_EQ(mj.dofs(), 3 * static_cast<int>(scene.bodies.size()));
  for (int c = 0; c < world.cableCount(); ++c)
    EXPECT_NEAR(mj.cableLength(c), world.cable(c).length(), 1e-12);
  for (int s = 0; s < 60; ++s) {
    mj.step();
    world.step(scene.dt, scene.substeps);
  }
  EXPECT_NEAR(mj.time(), 1.0, 1e-9);
  // Equal masses swinging sideways: both engines keep the discs hanging, MuJoCo's soft tendon a
  // few mm long; positions agree to that.
  for (int b = 0; b < world.bodyCount(); ++b)
    EXPECT_LT((mj.bodyPosition(b) - world.body(b).position).norm(), 1e-2) << "body " << b;
}

TEST(MujocoWorld, RefusesWhatItCannotMap) {
  SceneDef scene = makeAtwoodMachines(1);
  scene.cables[0].stiffness = 100;
  EXPECT_THROW(sceneToMjcf(scene), InputError);
  scene = makeAtwoodMachines(1);
  scene.cables[0].pulleys[0].side = WrapSide::Left;
  EXPECT_THROW(sceneToMjcf(scene), InputError);
}

}  // namespace
}  // namespace cablelab
#endif
