// Label placement (ui/label_layout.h): off the bodies, off each other, inside the view.
#include "ui/label_layout.h"

#include <gtest/gtest.h>

namespace cablelab::ui {
namespace {

LabelObstacle square(const Vec2& c, double half) {
  return {c + Vec2(-half, -half), c + Vec2(half, -half), c + Vec2(half, half),
          c + Vec2(-half, half)};
}

const LabelBox kView{0, 0, 800, 600};

TEST(LabelLayout, AFreeLabelStaysAtItsPreferredPlace) {
  const auto placed = placeLabels({{Vec2(400, 300), Vec2(6, -16), 50, 13}}, {}, kView, 4);
  ASSERT_EQ(placed.size(), 1u);
  EXPECT_DOUBLE_EQ(placed[0].box.x0, 406);
  EXPECT_DOUBLE_EQ(placed[0].box.y0, 284);
  EXPECT_FALSE(placed[0].leader);
}

TEST(LabelLayout, ABodysLabelGoesOffTheBodyWithALeader) {
  // A 90 px box labelled at its centre: no nearby place is free, the label goes outside.
  const std::vector<LabelObstacle> bodies = {square(Vec2(400, 300), 45)};
  const auto placed = placeLabels({{Vec2(400, 300), Vec2(4, 2), 30, 13}}, bodies, kView, 4);
  EXPECT_EQ(obstacleCover(placed[0].box, bodies), 0);
  EXPECT_TRUE(placed[0].leader);
  // The same label with the body's cover checked: the preferred place was on the body.
  EXPECT_GT(obstacleCover({404, 302, 434, 315}, bodies), 0.5);
}

TEST(LabelLayout, CrowdedLabelsAvoidEachOtherBodiesAndTheEdges) {
  // Five labels on one point between two thin links, near the top-left corner of the view.
  const std::vector<LabelObstacle> bodies = {
      {Vec2(20, 40), Vec2(300, 40), Vec2(300, 50), Vec2(20, 50)},
      {Vec2(20, 70), Vec2(300, 70), Vec2(300, 80), Vec2(20, 80)}};
  std::vector<LabelRequest> labels(5, {Vec2(30, 60), Vec2(6, -16), 60, 13});
  const auto placed = placeLabels(labels, bodies, kView, 4);
  ASSERT_EQ(placed.size(), 5u);
  for (size_t i = 0; i < placed.size(); ++i) {
    const LabelBox& b = placed[i].box;
    EXPECT_EQ(obstacleCover(b, bodies), 0) << i;
    EXPECT_GE(b.x0, kView.x0) << i;
    EXPECT_GE(b.y0, kView.y0) << i;
    for (size_t j = 0; j < i; ++j) EXPECT_FALSE(b.overlaps(placed[j].box)) << i << " " << j;
  }
}

TEST(LabelLayout, CoverCountsASmallBodyUnderALabel) {
  // A 2 px body inside the label's box misses every sample point; its corners count.
  const std::vector<LabelObstacle> bodies = {square(Vec2(107, 106), 1)};
  EXPECT_GT(obstacleCover({100, 100, 160, 113}, bodies), 0);
  EXPECT_EQ(obstacleCover({200, 100, 260, 113}, bodies), 0);
}

}  // namespace
}  // namespace cablelab::ui
