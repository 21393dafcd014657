// The scale benchmark's worlds: the committed files are the generated scenes, and the scenes do
// what they say (equal masses: nothing runs away; rigid cables stay at length).
#include "engine/scenes/scale_scenes.h"

#include <gtest/gtest.h>

#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

TEST(ScaleScenes, TheFilesAreTheGeneratedScenes) {
  // Regenerate with: build/bin/cablelab_bench --write-scenes=tests/data/bench
  for (const ScaleCase& c : scaleCases()) {
    const SceneDef file = loadSceneFile(test::sourcePath("tests/data/bench/" + c.name + ".json"));
    EXPECT_EQ(sceneToJson(file), sceneToJson(c.scene)) << c.name;
  }
}

TEST(ScaleScenes, AtwoodMachinesAndThePulleyChainKeepTheirCablesAtLength) {
  for (const SceneDef& scene : {makeAtwoodMachines(3), makePulleyChain(16)}) {
    World world(scene);
    double worst = 0;
    for (int s = 0; s < 300; ++s) {
      world.step(scene.dt, scene.substeps);
      for (int c = 0; c < world.cableCount(); ++c)
        worst = std::max(worst, std::abs(world.cable(c).stretch()));
    }
    EXPECT_LT(worst, 1e-4) << scene.name;
    for (int b = 0; b < world.bodyCount(); ++b)
      EXPECT_LT(std::abs(world.body(b).position.y() - scene.bodies[b].position.y()), 0.2)
          << scene.name << " body " << b;
  }
}

}  // namespace
}  // namespace cablelab
