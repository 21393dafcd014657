// The built-in scenes' "what to try" slider steps (ui/scene_guide.h) do what the text says, in
// the sandbox with its default settings: each value is within the slider's range and is applied
// as the slider applies it (Sandbox::rebuild on release).
#include "ui/scene_guide.h"

#include <gtest/gtest.h>

#include <iostream>

#include "ui/demo_loop.h"
#include "ui/sandbox.h"
#include "ui/scene_catalog.h"

namespace cablelab::ui {
namespace scene_guide_test {  // named: unity batches join test files

/// Opens `scene`, sets the slider `name` to `value` (nothing when `name` is empty), runs
/// `seconds` and returns how far `body` moved in y (m, up positive).
double riseAfter(const std::string& scene, const std::string& name, double value,
                 const std::string& body, double seconds) {
  Sandbox sandbox(800, 600);
  EXPECT_TRUE(sandbox.open(scene));
  if (!name.empty()) {
    bool known = false;
    for (const SceneParameter& p : sceneParameters(scene))
      if (p.name == name) {
        known = true;
        EXPECT_GE(value, p.lo) << scene << " " << name << ": off the slider";
        EXPECT_LE(value, p.hi) << scene << " " << name << ": off the slider";
      }
    EXPECT_TRUE(known) << scene << " has no slider " << name;
    auto values = sandbox.parameters;
    for (auto& [key, v] : values)
      if (key == name) v = value;
    EXPECT_TRUE(sandbox.rebuild(values)) << sandbox.error;
    EXPECT_NE(whatToTry(scene).find(name), std::string::npos) << "the step names the slider";
  }
  const int b = sandbox.world()->findBody(body);
  EXPECT_GE(b, 0) << scene << ": " << body;
  const double y0 = sandbox.world()->body(b).position.y();
  for (long i = std::lround(seconds / sandbox.dt); i > 0; --i) sandbox.advance(sandbox.dt, true);
  return sandbox.world()->body(b).position.y() - y0;
}

constexpr double kStill = 0.01;  // m in a second: balanced

// A slider's tooltip showed "Default 2.000000." (std::to_string): now the value as typed, with
// its unit, for every parameter of every built-in scene.
TEST(SceneGuide, ParameterTipsGiveTheDefaultAsTypedWithItsUnit) {
  EXPECT_EQ(parameterTip("left body mass (kg)", 2),
            "left body mass (kg)\nDefault 2 kg. Let go of the slider to start the scene again "
            "with the new value (Ctrl+click to type one).");
  EXPECT_NE(parameterTip("drum speed (rad/s)", -0.5).find("Default -0.5 rad/s."),
            std::string::npos);
  int tips = 0;
  for (const SceneEntry& scene : builtinSceneList())
    for (const SceneParameter& p : sceneParameters(scene.name)) {
      const std::string tip = parameterTip(p.description, p.value);
      EXPECT_EQ(tip.find("00000"), std::string::npos) << scene.name << " " << p.name << ": " << tip;
      EXPECT_EQ(tip.rfind(p.description + "\nDefault ", 0), 0u) << tip;
      ++tips;
    }
  EXPECT_GE(tips, 20);
}

TEST(SceneGuide, PulleyBalancesWithEqualMasses) {
  EXPECT_LT(riseAfter("pulley", "", 0, "left", 1), -0.1);  // the heavier left sinks
  EXPECT_LT(std::abs(riseAfter("pulley", "m_left", 1, "left", 1)), kStill);
}

TEST(SceneGuide, WheelWithoutInertiaMovesFaster) {
  const double heavy = riseAfter("wheel", "", 0, "left", 1);
  const double light = riseAfter("wheel", "I", 0, "left", 1);
  EXPECT_LT(heavy, 0);
  EXPECT_LT(light, 1.2 * heavy);  // sinks further
}

TEST(SceneGuide, WinchLowersTheWeightBelowZeroSpeed) {
  EXPECT_GT(riseAfter("winch", "", 0, "weight", 1), 0.05);
  EXPECT_LT(riseAfter("winch", "omega", -1, "weight", 1), -0.05);
}

TEST(SceneGuide, TackleBalancesWithAFourthOfTheLoad) {
  EXPECT_GT(std::abs(riseAfter("tackle", "", 0, "effort", 1)), 0.05);
  EXPECT_LT(std::abs(riseAfter("tackle", "m_effort", 1, "effort", 1)), kStill);
}

/// The fastest the body `name` moves (m/s) over `seconds` of `sandbox`'s scene, stepped as the
/// window steps it.
double topSpeed(Sandbox& sandbox, const std::string& name, double seconds) {
  const int b = sandbox.world()->findBody(name);
  EXPECT_GE(b, 0) << name;
  double top = 0;
  for (long i = std::lround(seconds / sandbox.dt); i > 0; --i) {
    sandbox.advance(sandbox.dt, true);
    top = std::max(top, sandbox.world()->body(b).velocity.norm());
  }
  return top;
}

// "Press Space to pause, then s to step through the impact one frame at a time. Drag the v0y
// slider to 3 and let go: the faster point jerks the ballast harder. Press r to run it again."
TEST(SceneGuide, BallastStepsPausedJerksHarderWhenFasterAndRunsAgain) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("ballast"));
  const Vec2 start = sandbox.world()->body(sandbox.world()->findBody("ballast")).position;
  sandbox.paused = true;  // Space
  for (int i = 0; i < 30; ++i) sandbox.advance(1.0 / 60, false);
  EXPECT_EQ(sandbox.world()->stepCount(), 0) << "paused, nothing moves";
  for (int k = 1; k <= 3; ++k) {  // s, three times: one step each
    ++sandbox.pendingSteps;
    sandbox.advance(1.0 / 60, false);
    EXPECT_EQ(sandbox.world()->stepCount(), k);
  }
  sandbox.paused = false;
  const double slow = topSpeed(sandbox, "ballast", 0.5);

  bool onSlider = false;
  for (const SceneParameter& p : sceneParameters("ballast"))
    if (p.name == "v0y") onSlider = p.lo <= 3 && 3 <= p.hi && p.value < 3;
  EXPECT_TRUE(onSlider) << "v0y = 3 is on the slider, above the default";
  auto values = sandbox.parameters;
  for (auto& [key, v] : values)
    if (key == "v0y") v = 3;
  ASSERT_TRUE(sandbox.rebuild(values)) << sandbox.error;
  const double fast = topSpeed(sandbox, "ballast", 0.5);
  EXPECT_GT(fast, 1.5 * slow) << "the faster point jerks the ballast harder";

  sandbox.reset();  // r
  EXPECT_EQ(sandbox.world()->stepCount(), 0);
  EXPECT_EQ(sandbox.world()->body(sandbox.world()->findBody("ballast")).position, start);
}

// "Drag the point into the band and let go: it bounces and settles where the band's pull
// balances its weight. Select the band (click it) and watch its tension in the Inspector as
// the point bounces."
TEST(SceneGuide, MembranePointDraggedIntoTheBandBouncesAndSettlesBack) {
  Sandbox undisturbed(800, 600);
  ASSERT_TRUE(undisturbed.open("membrane"));
  topSpeed(undisturbed, "finger", 8);
  const int f = undisturbed.world()->findBody("finger");
  const Vec2 rest = undisturbed.world()->body(f).position;

  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("membrane"));
  topSpeed(sandbox, "finger", 1);
  const Vec2 from = sandbox.world()->body(f).position;
  const double width = sandbox.scene.view.height;
  sandbox.beginDrag(f, from);
  sandbox.dragTo(from - Vec2(0, 0.2 * width));  // into the band
  topSpeed(sandbox, "finger", 1);
  const double pressed = sandbox.world()->body(f).position.y();
  EXPECT_LT(pressed, rest.y() - 0.03 * width) << "the drag pressed the point into the band";
  sandbox.endDrag();

  // The band under the mouse is the band: a click there selects it.
  const auto& path = sandbox.world()->cable(0).path();
  ASSERT_GE(path.size(), 2u);
  const Vec2 onBand = 0.5 * (path[0].world + path[1].world);
  EXPECT_EQ(sandbox.cableAt(onBand, 0.01 * width), 0);
  double lowest = 1e300, highest = -1e300, above = -1e300;
  for (int i = 0; i < 8 * 60; ++i) {
    sandbox.advance(sandbox.dt, true);
    const double tension = sandbox.world()->cable(0).tension();
    lowest = std::min(lowest, tension);
    highest = std::max(highest, tension);
    above = std::max(above, sandbox.world()->body(f).position.y());
  }
  EXPECT_GT(above, rest.y() + 0.01 * width) << "it bounces back past where it rests";
  EXPECT_GT(highest - lowest, 0.1 * highest) << "the tension changes as it bounces";
  // Back at the depth where the band's pull balances its weight (sideways the band holds the
  // point only weakly: it may come to rest a little to one side).
  EXPECT_NEAR(sandbox.world()->body(f).position.y(), rest.y(), 0.01 * width)
      << "it settles where the band's pull balances its weight; x "
      << sandbox.world()->body(f).position.x() << " vs " << rest.x();
}

// Demos that end start again, and the view holds the whole run (ui/demo_loop.h): 12 s of each
// such scene as the window plays it, checked every frame against the fitted view.
TEST(DemoLoop, RunsThatEndStartAgainInsideTheFittedView) {
  for (const char* name : {"pulley", "tackle", "ballast", "wheel"}) {
    Sandbox sandbox(1280, 720);
    ASSERT_TRUE(sandbox.open(name));
    sandbox.fitView();
    const Camera view = sandbox.camera;
    const auto first = sandbox.world()->body(1).position;
    // A clip recording through the wheel's restarts keeps its notice (the status line's "starts
    // again" replaced "recording ...": no sign of the clip); the others say they start again.
    const bool clip = std::string(name) == "wheel";
    sandbox.recording = clip;
    if (clip) sandbox.message = "recording cablelab-wheel-1.mp4";
    int restarts = 0, outside = 0, still = 0;
    double longestRun = 0;
    for (int i = 0; i < 12 * 60; ++i) {
      const double before = sandbox.world()->time();
      sandbox.advance(sandbox.dt, true);
      if (sandbox.world()->time() < before) {
        ++restarts;
        EXPECT_EQ(sandbox.world()->body(1).position, first) << name << ": starts as it began";
        longestRun = std::max(longestRun, before);
      }
      for (int b = 0; b < sandbox.world()->bodyCount(); ++b) {
        if (sandbox.scene.bodies[b].type != BodyType::Dynamic) continue;
        const Vec2 p = view.toScreen(sandbox.world()->body(b).position);
        outside += p.x() < 0 || p.y() < 0 || p.x() > view.width || p.y() > view.height;
      }
      double v = 0;
      for (int b = 0; b < sandbox.world()->bodyCount(); ++b)
        v = std::max(v, sandbox.world()->body(b).velocity.norm());
      still += v < 0.01;
    }
    EXPECT_GE(restarts, 1) << name;
    EXPECT_EQ(sandbox.demo.restarts, restarts) << name;
    EXPECT_EQ(outside, 0) << name << ": frames with a body out of the view";
    // Keeps going: at rest only for the second before each restart (and a few frames more).
    EXPECT_LE(still, (restarts + 1) * 70) << name;
    EXPECT_EQ(sandbox.message.rfind(clip ? "recording " : "The run has ended", 0), 0u)
        << name << ": " << sandbox.message;
    std::cout << name << ": " << restarts << " restarts in 12 s, longest run " << longestRun
              << " s\n";
  }
}

TEST(DemoLoop, ScenesThatKeepGoingOnTheirOwnAndScenesOfUsersNeverRestart) {
  for (const char* name : {"hexagon", "membrane", "hand"}) EXPECT_FALSE(demoLoops(name)) << name;
  EXPECT_FALSE(demoLoops("tests/data/good_scene.json"));
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("capstan"));  // holds: at rest from the start, never "ended"
  for (int i = 0; i < 5 * 60; ++i) sandbox.advance(sandbox.dt, true);
  EXPECT_EQ(sandbox.demo.restarts, 0);
  EXPECT_NEAR(sandbox.world()->time(), 5, 1e-9);
}

// The Scene menu's tooltips are for students: each built-in scene's first plain sentence, where
// the menu showed the `cablelab scenes` line ("thesis 2.4.2: ...", "(Box2D's pulley joint test)").
TEST(SceneGuide, SceneMenuTipsAreTheStudentsFirstSentence) {
  for (const SceneEntry& entry : builtinSceneList()) {
    const std::string tip = sceneMenuTip(entry.name, entry.description);
    const std::string whole = studentDescription(entry.name);
    ASSERT_FALSE(whole.empty()) << entry.name;
    EXPECT_EQ(whole.rfind(tip, 0), 0u) << entry.name << ": " << tip;
    EXPECT_EQ(tip.back(), '.') << entry.name << ": " << tip;
    EXPECT_LT(tip.size(), whole.size()) << entry.name << ": one sentence, not the whole text";
    for (const char* word : {"thesis", "figure", "chapter", "Box2D", "section"})
      EXPECT_EQ(tip.find(word), std::string::npos) << entry.name << ": " << tip;
  }
  EXPECT_EQ(sceneMenuTip("my.json", "a file's own words"), "a file's own words");
}

}  // namespace scene_guide_test
}  // namespace cablelab::ui
