// The built-in scenes' "what to try" slider steps (ui/scene_guide.h) do what the text says, in
// the sandbox with its default settings: each value is within the slider's range and is applied
// as the slider applies it (Sandbox::rebuild on release).
#include "ui/scene_guide.h"

#include <gtest/gtest.h>

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

}  // namespace scene_guide_test
}  // namespace cablelab::ui
