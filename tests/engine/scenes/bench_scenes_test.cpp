// The bench's timing helper also reports the tensions span by span (cablelab bench --json,
// "span_tensions_n"): a cable gripped by a wheel has one per span, in the physics' ratio.
#include "engine/scenes/bench_scenes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/scenes/scene_registry.h"

namespace cablelab {
namespace {

TEST(BenchScenes, SpanTensionsOfAHoldingCapstanAreInTheMassRatio) {
  // m_load / m_hold = 2 < e^(0.3 * 1.5 pi) = 4.1: the rope holds, the spans carry the weights.
  const SceneDef capstan = makeScene("capstan", {{"m_load", 4.0}, {"m_hold", 2.0}});
  const SceneTiming t = measureScene(capstan, 60, 60, 1);
  ASSERT_EQ(t.withCables.spanTensions.size(), 1u);
  const auto& [name, tensions] = t.withCables.spanTensions[0];
  EXPECT_EQ(name, "rope");
  ASSERT_EQ(tensions.size(), 2u);
  const double high = std::max(tensions[0], tensions[1]), low = std::min(tensions[0], tensions[1]);
  EXPECT_NEAR(high, 4.0 * 9.81, 0.01 * 4.0 * 9.81);
  EXPECT_NEAR(low, 2.0 * 9.81, 0.01 * 2.0 * 9.81);
  EXPECT_LT(high / low, std::exp(0.3 * 2 * M_PI * 0.75));
}

TEST(BenchScenes, ACableWithoutGrippingWheelsHasOneSpanTension) {
  const SceneTiming t = measureScene(makeScene("pulley"), 30, 30, 1);
  ASSERT_EQ(t.withCables.spanTensions.size(), 1u);
  EXPECT_EQ(t.withCables.spanTensions[0].second.size(), 1u);
  EXPECT_GT(t.withCables.spanTensions[0].second[0], 0);
}

}  // namespace
}  // namespace cablelab
