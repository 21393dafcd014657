// Presentation mode's fit (ui/presentation.h) without a window: the scene's moving parts fill
// the free area above the colour bar's row, and the view stays fitted through layout changes
// until the user moves it.
#include "ui/presentation.h"

#include <gtest/gtest.h>

#include "ui/authoring.h"
#include "ui/scene_bounds.h"

namespace cablelab::ui {
namespace presentation_test {  // named: unity batches join test files

constexpr double kPixel = 1.0;

/// The scene's moving parts on screen (px), with the whole run of a demo that ends (its stage,
/// ui/demo_loop.h).
LabelBox onScreen(const Sandbox& sandbox) {
  WorldBounds b = sceneBounds(*sandbox.world());
  if (!sandbox.demo.stage.empty()) {
    b.include(sandbox.demo.stage.lo);
    b.include(sandbox.demo.stage.hi);
  }
  const Vec2 lo = sandbox.camera.toScreen(b.lo), hi = sandbox.camera.toScreen(b.hi);
  return {lo.x(), hi.y(), hi.x(), lo.y()};
}

TEST(Presentation, TheSceneFillsTheAreaAboveTheBarRow) {
  for (const char* scene : {"hand", "hexagon", "capstan"}) {
    Sandbox sandbox(1280, 720);
    ASSERT_TRUE(sandbox.open(scene));
    sandbox.panels = {{0, 0, 1280, 30}, {0, 690, 1280, 30}};  // a menu strip and a status line
    togglePresentation(sandbox);
    keepViewFitted(sandbox);
    const PanelRect f = sandbox.freeArea();
    const double reserve = barRowHeight(sandbox);
    ASSERT_GT(reserve, 0);
    const LabelBox s = onScreen(sandbox);
    EXPECT_GE(s.x0, f.x - kPixel) << scene;
    EXPECT_LE(s.x1, f.x + f.width + kPixel) << scene;
    EXPECT_GE(s.y0, f.y - kPixel) << scene;
    EXPECT_LE(s.y1, f.y + f.height - reserve + kPixel) << scene;
    // As large as it fits: the limiting side spans the area less the margins (6% each side).
    const double wide = (s.x1 - s.x0) / f.width, tall = (s.y1 - s.y0) / (f.height - reserve);
    EXPECT_NEAR(std::max(wide, tall), 1 / 1.12, 0.01) << scene;
  }
}

// The wheel, the winch and the tackle hang a long rope under a small wheel: a whole-run fit
// left them 3-5% of the window's width. Presentation mode shows them in close-up: the top of
// the mechanism at the top of the area, the scene's width a kCloseUpSpan-th of the view's
// height or more, and a hanging body within reach in view.
TEST(Presentation, AThinTallDemoIsShownInCloseUp) {
  for (const char* scene : {"wheel", "winch", "tackle"}) {
    Sandbox sandbox(1280, 720);
    ASSERT_TRUE(sandbox.open(scene));
    sandbox.panels = {{0, 0, 1280, 30}, {0, 690, 1280, 30}};
    togglePresentation(sandbox);
    keepViewFitted(sandbox);
    EXPECT_TRUE(sandbox.closeUp) << scene;
    const PanelRect f = sandbox.freeArea();
    const double height = f.height - barRowHeight(sandbox);
    const WorldBounds b = sceneBounds(*sandbox.world());
    const Vec2 lo = sandbox.camera.toScreen(b.lo), hi = sandbox.camera.toScreen(b.hi);
    EXPECT_GE(hi.y(), f.y) << scene;
    EXPECT_LE(hi.y(), f.y + 0.2 * height) << scene << ": the top of the mechanism at the top";
    EXPECT_GE(hi.x() - lo.x(), height / kCloseUpSpan / 3 - kPixel) << scene;
    // The stage fit it replaces, for comparison: 3-5% of the width.
    const Camera whole = fitToContent(*sandbox.world(), sandbox.camera, f, barRowHeight(sandbox),
                                      sandbox.demo.stage);
    EXPECT_GT(whole.metresPerPixel, 1.8 * sandbox.camera.metresPerPixel) << scene;
  }
  Sandbox hexagon(1280, 720);  // not a demo that loops: fitted whole
  ASSERT_TRUE(hexagon.open("hexagon"));
  togglePresentation(hexagon);
  keepViewFitted(hexagon);
  EXPECT_FALSE(hexagon.closeUp);
}

TEST(Presentation, TheViewStaysFittedUntilTheUserMovesIt) {
  Sandbox sandbox(1280, 720);
  ASSERT_TRUE(sandbox.open("hexagon"));
  sandbox.panels = {{0, 0, 1280, 30}, {0, 30, 300, 660}};  // the Simulation panel open
  keepViewFitted(sandbox);
  const double before = sandbox.camera.metresPerPixel;
  // The panel collapses: the free area grows, the view is fitted to it.
  sandbox.panels = {{0, 0, 1280, 30}};
  keepViewFitted(sandbox);
  EXPECT_EQ(sandbox.fittedArea.width, 1280);
  // The UI scale doubles: fitted again (projector mode).
  sandbox.uiScale = 2;
  keepViewFitted(sandbox);
  EXPECT_EQ(sandbox.fittedScale, 2);
  // The user zooms: their view stays through the next layout change.
  sandbox.viewFitted = false;
  sandbox.camera.metresPerPixel = 0.5 * before;
  sandbox.panels = {{0, 0, 1280, 30}, {0, 30, 300, 660}};
  keepViewFitted(sandbox);
  EXPECT_EQ(sandbox.camera.metresPerPixel, 0.5 * before);
  // The fit key fits it again (at the first fit's UI scale: the colour bar's row scales with it).
  sandbox.uiScale = 1;
  sandbox.fitView();
  EXPECT_TRUE(sandbox.viewFitted);
  EXPECT_EQ(sandbox.camera.metresPerPixel, before);
}

}  // namespace presentation_test
}  // namespace cablelab::ui

namespace cablelab::ui {
namespace presentation_test {

// A slider that changes a demo's run (the capstan's "what to try": m_load to 6, the rope slips
// and the load falls) fits the view again to the new run, while the view is the fitted one: the
// falling load stayed off the bottom of the old view.
TEST(Presentation, ASliderStepKeepsTheNewRunInTheFittedView) {
  Sandbox sandbox(1280, 720);
  ASSERT_TRUE(sandbox.open("capstan"));
  sandbox.panels = {{0, 0, 1280, 38}, {0, 672, 1280, 48}};  // the slim strip, the status line
  togglePresentation(sandbox);
  keepViewFitted(sandbox);
  auto values = sandbox.parameters;
  for (auto& [name, v] : values)
    if (name == "m_load") v = 6;
  ASSERT_TRUE(sandbox.rebuild(values)) << sandbox.error;
  keepViewFitted(sandbox);
  const PanelRect f = sandbox.freeArea();
  const int load = sandbox.world()->findBody("load");
  double lowest = -1e300;  // px, down positive
  for (int i = 0; i < 3 * 60; ++i) {
    sandbox.advance(sandbox.dt, true);
    lowest = std::max(lowest, sandbox.camera.toScreen(sandbox.world()->body(load).position).y());
  }
  EXPECT_LE(lowest, f.y + f.height - barRowHeight(sandbox)) << "the load fell out of the view";
  // A view the user chose stays through the slider.
  sandbox.viewFitted = false;
  sandbox.camera.metresPerPixel *= 0.5;
  const Camera mine = sandbox.camera;
  ASSERT_TRUE(sandbox.rebuild(values));
  keepViewFitted(sandbox);
  EXPECT_EQ(sandbox.camera.metresPerPixel, mine.metresPerPixel);
  EXPECT_EQ(sandbox.camera.center, mine.center);
}

/// `b` on screen inside the free area above the bars' row.
void expectAboveTheBars(const Sandbox& sandbox, const WorldBounds& b, const char* what) {
  const PanelRect f = sandbox.freeArea();
  const LabelBox s = screenBox(b, sandbox.camera);
  EXPECT_GE(s.x0, f.x - kPixel) << what;
  EXPECT_LE(s.x1, f.x + f.width + kPixel) << what;
  EXPECT_GE(s.y0, f.y - kPixel) << what;
  EXPECT_LE(s.y1, f.y + f.height - barRowHeight(sandbox) + kPixel) << what;
}

// A student's first mechanism in presentation mode: the ground (a fixed body) is in the fit,
// above the bars' row (it sat under the scale bar, fixed bodies being left out); while a Build
// tool is chosen the view is the scene's own and holds still as the scene grows; Esc (the
// select tool) fits the mechanism and its ground as large as they fit.
TEST(Presentation, AStudentsMechanismAndItsGroundAreFittedAboveTheBars) {
  Sandbox sandbox(1280, 720);
  ASSERT_TRUE(sandbox.open("hexagon"));
  sandbox.panels = {{0, 0, 1280, 38}, {0, 672, 1280, 48}};  // the slim strip, the status line
  togglePresentation(sandbox);
  newScene(sandbox);
  keepViewFitted(sandbox);
  const int ground = sandbox.world()->findBody("ground");
  ASSERT_GE(ground, 0);
  EXPECT_GT(barRowHeight(sandbox), 0) << "no cable, but the scale bar";
  expectAboveTheBars(sandbox, bodyBounds(*sandbox.world(), ground), "the new scene's ground");

  chooseTool(*sandbox.authoring, Authoring::Tool::Box);
  keepViewFitted(sandbox);
  const Camera building = sandbox.camera;
  EXPECT_LE(screenBox(WorldBounds{Vec2(-2, -0.5), Vec2(2, 3.5)}, building).y1,
            sandbox.freeArea().y + sandbox.freeArea().height)
      << "the scene's view (4 m tall about (0, 1.5)) is the canvas";
  for (const Vec2& p : {Vec2(-0.4, 1), Vec2(0.4, 1)}) {
    ASSERT_TRUE(authoringClick(sandbox, p, false)) << sandbox.error;
    keepViewFitted(sandbox);
    EXPECT_EQ(sandbox.camera.center, building.center);
    EXPECT_EQ(sandbox.camera.metresPerPixel, building.metresPerPixel);
  }
  chooseTool(*sandbox.authoring, Authoring::Tool::CirclePulley);
  ASSERT_TRUE(authoringClick(sandbox, Vec2(0, 2.5), false));
  chooseTool(*sandbox.authoring, Authoring::Tool::Cable);
  for (const Vec2& p : {Vec2(-0.4, 1.1), Vec2(0, 2.5), Vec2(0.4, 1.1)})
    ASSERT_TRUE(authoringClick(sandbox, p, false)) << sandbox.error;
  ASSERT_EQ(sandbox.world()->cableCount(), 1);
  keepViewFitted(sandbox);
  EXPECT_EQ(sandbox.camera.metresPerPixel, building.metresPerPixel);

  chooseTool(*sandbox.authoring, Authoring::Tool::None);  // Esc
  keepViewFitted(sandbox);
  expectAboveTheBars(sandbox, bodyBounds(*sandbox.world(), ground), "the ground");
  expectAboveTheBars(sandbox, sceneBounds(*sandbox.world()), "the mechanism");
  // As large as it fits: the limiting side spans the area less the margins (6% each side).
  const LabelBox s = screenBox(sceneBounds(*sandbox.world()), sandbox.camera);
  const PanelRect f = sandbox.freeArea();
  const double wide = (s.x1 - s.x0) / f.width;
  const double tall = (s.y1 - s.y0) / (f.height - barRowHeight(sandbox));
  EXPECT_NEAR(std::max(wide, tall), 1 / 1.12, 0.01);
  EXPECT_GE(wide, 0.6) << "the ground's 6 m";
}

/// A rectangle shape from (x0, y0) to (x1, y1), body frame (m).
ShapeDef rectangle(double x0, double y0, double x1, double y1) {
  ShapeDef r;
  r.kind = ShapeDef::Kind::Polygon;
  r.vertices = {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
  return r;
}

// A ground much wider than the mechanism counts only near it (whole, it would shrink the
// mechanism to a sliver); a fixed body far from it not at all.
TEST(SceneBounds, FixedBodiesCountNearTheMovingParts) {
  SceneDef s;
  BodyDef ground, far, box;
  ground.name = "ground", far.name = "far", box.name = "box";
  ground.type = far.type = BodyType::Static;
  ground.shapes = {rectangle(-50, -0.1, 50, 0)};
  far.position = Vec2(30, 5);
  far.shapes = {rectangle(-1, -1, 1, 1)};
  box.position = Vec2(0, 1);
  box.shapes = {rectangle(-0.5, -0.5, 0.5, 0.5)};
  s.bodies = {ground, far, box};
  const WorldBounds b = sceneBounds(World(s, "fixed"));
  // The box is 1 m across: the ground counts 1 m (kFixedReach) either side of it, down to -0.1.
  EXPECT_NEAR(b.lo.x(), -0.5 - kFixedReach, 1e-6);
  EXPECT_NEAR(b.hi.x(), 0.5 + kFixedReach, 1e-6);
  EXPECT_NEAR(b.lo.y(), -0.1, 1e-6);
  EXPECT_NEAR(b.hi.y(), 1.5, 1e-6);
  // Nothing moving: the fixed bodies whole.
  s.bodies = {ground};
  EXPECT_NEAR(sceneBounds(World(s, "ground")).lo.x(), -50, 1e-6);
}

}  // namespace presentation_test
}  // namespace cablelab::ui
