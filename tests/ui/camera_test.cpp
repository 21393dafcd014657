#include "ui/camera.h"

#include <gtest/gtest.h>

namespace cablelab::ui {
namespace {

constexpr double kTol = 1e-9;

TEST(Camera, FitPutsTheViewCentreInTheMiddleAndItsHeightOnTheViewport) {
  const Camera c = Camera::fit({Vec2(1, 2), 3.0}, 400, 300);
  EXPECT_NEAR(c.metresPerPixel, 0.01, kTol);
  EXPECT_NEAR(c.toScreen({1, 2}).x(), 200, kTol);
  EXPECT_NEAR(c.toScreen({1, 2}).y(), 150, kTol);
  EXPECT_NEAR(c.top() - c.bottom(), 3.0, kTol);
  EXPECT_LT(c.toScreen({1, 3}).y(), 150);  // y up in the world is up on screen
}

TEST(Camera, ScreenAndWorldRoundTrip) {
  const Camera c = Camera::fit({Vec2(-0.5, 0.25), 2.0}, 640, 480);
  const Vec2 p(0.3, -0.7);
  EXPECT_NEAR((c.toWorld(c.toScreen(p)) - p).norm(), 0, kTol);
}

TEST(Camera, ZoomKeepsThePointUnderTheCursor) {
  Camera c = Camera::fit({Vec2(0, 0), 4.0}, 800, 600);
  const Vec2 cursor(123, 456);
  const Vec2 before = c.toWorld(cursor);
  c.zoomAt(cursor, 1.7);
  EXPECT_NEAR((c.toWorld(cursor) - before).norm(), 0, kTol);
  EXPECT_NEAR(c.metresPerPixel, 4.0 / 600 / 1.7, kTol);
}

TEST(Camera, PanMovesTheSceneWithTheMouse) {
  Camera c = Camera::fit({Vec2(0, 0), 4.0}, 800, 600);
  const Vec2 p(0.5, 0.5);
  const Vec2 s = c.toScreen(p);
  c.panPixels({10, -20});
  EXPECT_NEAR((c.toScreen(p) - (s + Vec2(10, -20))).norm(), 0, 1e-9);
}

}  // namespace
}  // namespace cablelab::ui
