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

namespace cablelab::ui {
namespace {

// Issue 38: labels never cover each other, the scale bar or the colour bar. Ten labels crowd one
// anchor beside a reserved box (a colour bar) in a small view: each shown label is clear of the
// box, of the others and of the edges; one that finds no such place is left out.
TEST(LabelLayout, ReservedBoxesAndOtherLabelsAreNeverCovered) {
  const LabelBox view{0, 0, 300, 200};
  const std::vector<LabelBox> reserved = {{150, 120, 300, 200}, {0, 170, 120, 200}};
  std::vector<LabelRequest> labels(10, {Vec2(160, 130), Vec2(6, -16), 70, 13});
  const auto placed = placeLabels(labels, {}, view, 4, reserved);
  ASSERT_EQ(placed.size(), 10u);
  int shown = 0;
  for (size_t i = 0; i < placed.size(); ++i) {
    if (!placed[i].shown) continue;
    ++shown;
    const LabelBox& b = placed[i].box;
    for (const LabelBox& r : reserved) EXPECT_FALSE(b.overlaps(r)) << i;
    EXPECT_TRUE(b.x0 >= view.x0 && b.y0 >= view.y0 && b.x1 <= view.x1 && b.y1 <= view.y1) << i;
    for (size_t j = 0; j < i; ++j)
      EXPECT_FALSE(placed[j].shown && b.overlaps(placed[j].box)) << i << " " << j;
  }
  EXPECT_GE(shown, 6);  // the free part of the view holds most of them
  // The preferred place (on the reserved box) was not taken: the first label moved off it.
  EXPECT_TRUE(placed[0].shown);
  EXPECT_NE(placed[0].box.x0, 166);
}

// A view with room for no label at all: nothing is drawn rather than drawn over the bars.
TEST(LabelLayout, ALabelWithNoFreePlaceIsLeftOut) {
  const LabelBox view{0, 0, 100, 40};
  const auto placed =
      placeLabels({{Vec2(50, 20), Vec2(6, -16), 60, 13}}, {}, view, 4, {{0, 0, 100, 40}});
  ASSERT_EQ(placed.size(), 1u);
  EXPECT_FALSE(placed[0].shown);
}

}  // namespace
}  // namespace cablelab::ui

namespace cablelab::ui {
namespace label_layout_strip_test {  // named: unity batches join test files

// A cable's line is a strip 3 px wide: no sample point of a 60x20 label falls on it, yet the
// label at its preferred place would be drawn across it. It moves off the line.
TEST(LabelLayout, ALabelKeepsOffACablesThinStrip) {
  const LabelObstacle strip = {{129, 0}, {131, 0}, {131, 400}, {129, 400}};  // x = 130, vertical
  const LabelBox across{100, 50, 160, 70};
  EXPECT_TRUE(crossesConvex(across, strip));
  EXPECT_FALSE(crossesConvex({140, 50, 200, 70}, strip));
  EXPECT_GT(obstacleCover(across, {strip}), 0);
  const auto placed =
      placeLabels({{Vec2(125, 60), Vec2(-25, -10), 60, 20}}, {strip}, {0, 0, 400, 400}, 4);
  ASSERT_EQ(placed.size(), 1u);
  EXPECT_TRUE(placed[0].shown);
  EXPECT_FALSE(crossesConvex(placed[0].box, strip)) << placed[0].box.x0 << " " << placed[0].box.x1;
}

}  // namespace label_layout_strip_test
}  // namespace cablelab::ui
