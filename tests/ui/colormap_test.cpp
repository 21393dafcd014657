#include "ui/colormap.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cablelab::ui {
namespace {

TEST(Colormap, EndsAreBlueAndRedAndInputIsClamped) {
  EXPECT_GT(tensionColour(0)[2], tensionColour(0)[0]);
  EXPECT_GT(tensionColour(1)[0], tensionColour(1)[2]);
  EXPECT_EQ(tensionColour(-3), tensionColour(0));
  EXPECT_EQ(tensionColour(7), tensionColour(1));
  EXPECT_EQ(tensionColour(NAN), tensionColour(0));
}

TEST(Colormap, NiceNumbers) {
  EXPECT_DOUBLE_EQ(niceCeil(0), 1);
  EXPECT_DOUBLE_EQ(niceCeil(1), 1);
  EXPECT_DOUBLE_EQ(niceCeil(1.2), 2);
  EXPECT_DOUBLE_EQ(niceCeil(3.1), 5);
  EXPECT_DOUBLE_EQ(niceCeil(7), 10);
  EXPECT_NEAR(niceCeil(0.031), 0.05, 1e-15);
  EXPECT_DOUBLE_EQ(niceFloor(7), 5);
  EXPECT_DOUBLE_EQ(niceFloor(19), 10);
  EXPECT_NEAR(niceFloor(0.3), 0.2, 1e-15);
}

}  // namespace
}  // namespace cablelab::ui
