// Overlay lines kept off the screen pieces (ui/overlay_clip.h): a drag arrow pulled onto the
// colour bar stops at its edge and goes on past it.
#include "ui/overlay_clip.h"

#include <gtest/gtest.h>

namespace cablelab::ui {
namespace overlay_clip_test {  // named: unity batches join test files

const LabelBox kBar{100, 100, 200, 150};

TEST(OverlayClip, ASegmentClearOfTheBoxesIsWhole) {
  const auto parts = partsOutside(Vec2(0, 0), Vec2(90, 300), {kBar});
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].a, Vec2(0, 0));
  EXPECT_EQ(parts[0].b, Vec2(90, 300));
}

TEST(OverlayClip, AnArrowIntoTheBarStopsAtItsEdge) {
  // From (0, 125) to the bar's middle: the part left of x = 100 stays.
  const auto parts = partsOutside(Vec2(0, 125), Vec2(150, 125), {kBar});
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_NEAR(parts[0].b.x(), 100, 1e-9);
  EXPECT_NEAR(parts[0].b.y(), 125, 1e-9);
}

TEST(OverlayClip, ALineAcrossTheBarGoesOnPastIt) {
  // The diagonal (0, 0) -> (300, 300) enters the bar at x = 100 (y = 100) and leaves it at
  // y = 150 (x = 150).
  const auto parts = partsOutside(Vec2(0, 0), Vec2(300, 300), {kBar});
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_NEAR(parts[0].b.x(), 100, 1e-9);
  EXPECT_NEAR(parts[1].a.x(), 150, 1e-9);
  EXPECT_NEAR(parts[1].a.y(), 150, 1e-9);
  EXPECT_EQ(parts[1].b, Vec2(300, 300));
}

TEST(OverlayClip, OverlappingBoxesLeaveOneGapAndAnInsideLineVanishes) {
  const LabelBox key{180, 90, 260, 160};  // overlaps the bar
  const auto parts = partsOutside(Vec2(0, 120), Vec2(400, 120), {key, kBar});
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_NEAR(parts[0].b.x(), 100, 1e-9);
  EXPECT_NEAR(parts[1].a.x(), 260, 1e-9);
  EXPECT_TRUE(partsOutside(Vec2(110, 110), Vec2(190, 140), {kBar}).empty());
  // An empty box keeps nothing off.
  EXPECT_EQ(partsOutside(Vec2(110, 110), Vec2(190, 140), {LabelBox{}}).size(), 1u);
}

}  // namespace overlay_clip_test
}  // namespace cablelab::ui
