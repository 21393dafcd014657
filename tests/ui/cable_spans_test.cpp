// The Inspector's span table (ui/cable_spans.h) without a window: a one-span cable has none; the
// wheel scene's cable, split by its no-slip wheel, lists the two Atwood tensions
// m1 (g - a) and m2 (g + a), a = g (m1 - m2) / (m1 + m2 + I / r^2); the capstan's holding ratio is
// the masses', below e^(mu theta) (its slipping ratio: GuiAcceptance.CapstanInspector...).
#include "ui/cable_spans.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/ui/test_support.h"

namespace cablelab::ui {
namespace {

std::unique_ptr<World> stepped(const SceneDef& scene, int steps) {
  auto world = std::make_unique<World>(scene, scene.name);
  for (int i = 0; i < steps; ++i) world->step(scene.dt, scene.substeps);
  return world;
}

TEST(CableSpans, ACableWithoutGrippingWheelsHasNoSpanTable) {
  const auto world = stepped(loadScene("hexagon"), 10);
  ASSERT_GT(world->cableCount(), 0);
  for (int i = 0; i < world->cableCount(); ++i) {
    EXPECT_EQ(world->cable(i).spanCount(), 1);
    const SpanTable t = spanTable(world->cable(i));
    EXPECT_TRUE(t.spans.empty());
    EXPECT_TRUE(t.wheels.empty());
  }
}

TEST(CableSpans, WheelSceneListsBothAtwoodTensionsAndANoSlipWheel) {
  const double r = 0.2, inertia = 0.2, m1 = 1.2, m2 = 1.0;
  const SceneDef scene = loadScene("wheel", {{"r", r}, {"I", inertia}, {"m1", m1}, {"m2", m2}});
  const auto world = stepped(scene, 30);
  const Cable& cable = world->cable(0);
  const SpanTable t = spanTable(cable);
  ASSERT_EQ(t.spans.size(), 2u);
  ASSERT_EQ(t.wheels.size(), 1u);
  const double g = scene.gravity.norm(), a = g * (m1 - m2) / (m1 + m2 + inertia / (r * r));
  // The cable starts on the left mass: span 0 holds m1.
  EXPECT_NEAR(t.spans[0].tension, m1 * (g - a), 0.005 * m1 * g);
  EXPECT_NEAR(t.spans[1].tension, m2 * (g + a), 0.005 * m2 * g);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(t.spans[k].tension, cable.spanTension(k));
    EXPECT_EQ(t.spans[k].length, cable.spanKinematics(k).length);
    char shown[32];
    std::snprintf(shown, sizeof shown, "%.4g N", cable.spanTension(k));
    EXPECT_NE(t.spans[k].text.find(shown), std::string::npos) << t.spans[k].text;
  }
  const WheelRow& w = t.wheels[0];
  EXPECT_EQ(w.state, "no slip");
  EXPECT_EQ(w.grip, Grip::NoSlip);
  EXPECT_NEAR(w.wrapAngle, M_PI, 1e-6);  // the cable hangs straight down on both sides
  EXPECT_NEAR(w.ratio, t.spans[0].tension / t.spans[1].tension, 1e-12);
  EXPECT_NE(w.text.find("no slip"), std::string::npos) << w.text;
}

TEST(CableSpans, CapstanHoldingRatioIsTheMassRatioBelowTheCapstanBound) {
  const double mu = 0.3, turns = 0.75, mLoad = 3.0, mHold = 1.0;
  const SceneDef scene =
      loadScene("capstan", {{"mu", mu}, {"turns", turns}, {"m_load", mLoad}, {"m_hold", mHold}});
  const auto world = stepped(scene, 60);
  const SpanTable t = spanTable(world->cable(0));
  ASSERT_EQ(t.spans.size(), 2u);
  ASSERT_EQ(t.wheels.size(), 1u);
  const WheelRow& w = t.wheels[0];
  EXPECT_EQ(w.state, "holding");
  EXPECT_NEAR(w.wrapAngle, 2 * M_PI * turns, 1e-6);
  EXPECT_NEAR(w.capstanRatio, std::exp(mu * 2 * M_PI * turns), 1e-6);
  EXPECT_NEAR(w.ratio, mLoad / mHold, 1e-6);  // at rest: the tensions are the weights
  EXPECT_LT(w.ratio, w.capstanRatio);
  // Words for students: the slipping ratio as a number, no formula (issue 38, item 3).
  char slips[32];
  std::snprintf(slips, sizeof slips, "slips at %.4g", w.capstanRatio);
  EXPECT_NE(w.text.find(slips), std::string::npos) << w.text;
  for (const char* term : {"e^", "theta", "mu"})
    EXPECT_EQ(w.text.find(term), std::string::npos) << w.text;
}

// A rope over a fixed square's two top corners (90 degrees each) with mu 0.2: 3 kg against 1 kg
// slides (e^(0.2 pi) = 1.87), each corner at e^(0.2 pi / 2); the Inspector lists both.
TEST(CableSpans, PolygonWithFrictionListsEachCorner) {
  const SceneDef scene = loadScene(std::string(CABLELAB_SOURCE_DIR) +
                                   "/tests/data/polygon_friction/good_polygon_friction_scene.json");
  const auto world = stepped(scene, 30);
  const SpanTable t = spanTable(world->cable(0));
  ASSERT_EQ(t.spans.size(), 2u);
  ASSERT_EQ(t.wheels.size(), 1u);
  const WheelRow& w = t.wheels[0];
  EXPECT_EQ(w.state, "slipping");
  EXPECT_NEAR(w.wrapAngle, M_PI, 1e-6);
  EXPECT_NEAR(w.ratio, std::exp(0.2 * M_PI), 1e-6);
  EXPECT_NE(w.text.find("polygon 0: slipping"), std::string::npos) << w.text;
  ASSERT_EQ(w.corners.size(), 2u);
  for (const CornerRow& c : w.corners) {
    EXPECT_NEAR(c.turn, M_PI / 2, 1e-6);
    EXPECT_NEAR(c.ratio, std::exp(0.2 * M_PI / 2), 1e-6);
    EXPECT_NEAR(c.capstanRatio, std::exp(0.2 * M_PI / 2), 1e-12);
    EXPECT_NE(c.text.find("corner"), std::string::npos) << c.text;
  }
  EXPECT_EQ(w.corners[0].tensionIn, t.spans[0].tension);
  EXPECT_EQ(w.corners[1].tensionOut, t.spans[1].tension);
}

}  // namespace
}  // namespace cablelab::ui
