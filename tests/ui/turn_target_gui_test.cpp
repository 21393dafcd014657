// The sandbox's angle target for a box that turns (ui/turn_target_scenario.h): synthetic mouse
// events drag the handle on the target marker's arm under Xvfb, and the controller turns the
// box to the angle the drag set. Skipped when xvfb-run is not installed.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/ui/test_support.h"
#include "ui/image.h"

namespace cablelab::test {
namespace turn_target_gui_test {  // named: unity batches join test files

TEST(GuiTurnTarget, DraggingTheArmTurnsTheBox) {
  if (!onPath("xvfb-run")) GTEST_SKIP() << "xvfb-run not installed: GUI tests skipped";
  const std::string shot = (outputDir("gui") / "turn-target.png").string();
  for (const char* mu : {"0", "0.5"}) {
    SCOPED_TRACE(std::string("mu ") + mu);
    const RunResult r =
        run("xvfb-run -a -s \"-screen 0 1280x720x24\" " + std::string(CABLELAB_CLI) +
                " gui hand --set turn=1 --set mu=" + mu +
                " --size 1280x720 --script turn-target --screenshot " + shot,
            std::string("gui_turn_target_") + mu);
    const nlohmann::json j = jsonReport(r);
    ASSERT_FALSE(j.contains("failure")) << j.dump();
    // The drag set the angle it was taken to (to the pixel: the arm is 60 px long).
    EXPECT_NEAR(j["target_angle"].get<double>(), j["wanted"].get<double>(), 1.0 / 60);
    // The box turned to it and stayed within 0.02 rad for a second.
    EXPECT_TRUE(j["settled"].get<bool>()) << j.dump();
    EXPECT_NEAR(j["box_angle"].get<double>(), j["target_angle"].get<double>(), 0.02);
    // The arm is drawn in the target's colour from the marker to the handle's end.
    const ui::Image image = ui::readPng(shot);
    const double x = j["handle_to"][0], y = j["handle_to"][1];
    int magenta = 0;
    for (int dy = -6; dy <= 6; ++dy)
      for (int dx = -6; dx <= 6; ++dx) {
        const auto* p = image.pixel(static_cast<int>(x) + dx, static_cast<int>(y) + dy);
        magenta += p[0] > 150 && p[1] < 90 && p[2] > 90;
      }
    EXPECT_GT(magenta, 3) << "no angle arm at the handle in " << shot;
  }
}

}  // namespace turn_target_gui_test
}  // namespace cablelab::test
