// The sandbox's tension colour scale (ui/tension_scale.h, loadTensionScale): from the scene's
// loads, the same for the same scene whatever a run does.
#include "ui/tension_scale.h"

#include <gtest/gtest.h>

#include "ui/sandbox.h"
#include "ui/scene_catalog.h"

namespace cablelab::ui {
namespace tension_scale_test {  // named: unity batches join test files

TEST(TensionScale, FromTheScenesLoads) {
  // hexagon: the hexagon turns on an axle (its weight is the axle's), the 1 kg weight hangs:
  // 9.81 N, rounded up to 10 N.
  EXPECT_EQ(loadTensionScale(loadScene("hexagon")), 10);
  // capstan: 3 kg + 1 kg hang on the rope, 39.2 N -> 50 N.
  EXPECT_EQ(loadTensionScale(loadScene("capstan")), 50);
  // A heavier weight, a larger scale: 5 kg -> 49 N -> 50 N.
  EXPECT_EQ(loadTensionScale(loadScene("hexagon", {{"m_weight", 5.0}})), 50);
  // The hand has no gravity: its membranes' preload tension at the start sets the scale.
  const double hand = loadTensionScale(loadScene("hand"));
  World world(loadScene("hand"), "hand");
  double start = 0;
  for (int i = 0; i < world.cableCount(); ++i) {  // k (length - rest + preload)
    const Cable& c = world.cable(i);
    start = std::max(start, c.stiffness() * (c.length() - c.restLength() + c.preload()));
  }
  EXPECT_GT(start, 10);
  EXPECT_GE(hand, start);
  EXPECT_LE(hand, 2.5 * start);
}

TEST(TensionScale, ANewSceneWithoutLoadsStartsAtOneNewton) {
  SceneDef scene = loadScene("hexagon");
  for (BodyDef& b : scene.bodies) b.mass = 1e-6;  // next to no weight: 1 N, not 1e-5 N
  EXPECT_EQ(loadTensionScale(scene), kLeastTensionScale);
  scene.cables.clear();
  EXPECT_EQ(loadTensionScale(scene), 1);
}

// The sandbox keeps it through a hard drag and a reset, and a locked scale through another scene.
TEST(TensionScale, TheSandboxNeverRescalesBehindTheUsersBack) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("hexagon"));
  EXPECT_EQ(sandbox.tensionScale, 10);
  World& world = *sandbox.world();
  const int weight = world.findBody("weight");
  sandbox.dragWeights = 20;
  sandbox.beginDrag(weight, world.body(weight).position);
  sandbox.dragTo(world.body(weight).position + Vec2(0, -3));
  double largest = 0;
  for (int i = 0; i < 60; ++i) {
    sandbox.advance(sandbox.dt, true);
    largest = std::max(largest, world.cable(0).tension());
    ASSERT_EQ(sandbox.tensionScale, 10) << "frame " << i;
  }
  EXPECT_GT(largest, 20) << "the drag should pull well past the scale";
  sandbox.endDrag();
  sandbox.reset();
  EXPECT_EQ(sandbox.tensionScale, 10);
  sandbox.tensionScaleLocked = true;
  sandbox.tensionScale = 20;
  ASSERT_TRUE(sandbox.open("capstan"));
  EXPECT_EQ(sandbox.tensionScale, 20) << "a locked scale is the user's";
  sandbox.tensionScaleLocked = false;
  ASSERT_TRUE(sandbox.open("capstan"));
  EXPECT_EQ(sandbox.tensionScale, 50);
}

// The tackle's "what to try" (m_effort 2 -> 1) rescaled the bar from 0..100 N to 0..50 N: the
// lighter run's rope looked as taut as the heavier one's. A slider step keeps the scale unless
// the new loads need more (the capstan's heavier load).
TEST(TensionScale, ASliderStepNeverShrinksTheScale) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("tackle"));
  const double before = sandbox.tensionScale;
  EXPECT_EQ(before, 100);
  ASSERT_TRUE(sandbox.rebuild({{"m_effort", 1}}));
  EXPECT_EQ(sandbox.tensionScale, before);
  ASSERT_TRUE(sandbox.open("capstan"));
  const double light = sandbox.tensionScale;
  ASSERT_TRUE(sandbox.rebuild({{"m_load", 6}}));
  EXPECT_GT(sandbox.tensionScale, light);
  ASSERT_TRUE(sandbox.open("tackle"));
  EXPECT_EQ(sandbox.tensionScale, before) << "a new scene starts from its own loads";
}

}  // namespace tension_scale_test
}  // namespace cablelab::ui
