// The sandbox's choice of control law (ui/law_target_scenario.h): synthetic clicks pick "plan
// ahead (MPC)" (or the Jacobian controller with PID) in the hand's controller panel under Xvfb,
// then a click in the view sets the box's target; MPC brings the box within 5 mm sooner than PID.
// Skipped when xvfb-run is not installed.
#include <gtest/gtest.h>

#include "tests/ui/test_support.h"
#include "ui/image.h"

namespace cablelab::test {
namespace law_target_gui_test {  // named: unity batches join test files

nlohmann::json runScenario(const std::string& name) {
  const std::string shot = (outputDir("gui") / (name + ".png")).string();
  const RunResult r =
      run("xvfb-run -a -s \"-screen 0 1280x720x24\" " + std::string(CABLELAB_CLI) +
              " gui hand --size 1280x720 --script " + name + " --screenshot " + shot,
          "gui_" + name);
  return jsonReport(r);
}

TEST(GuiLawTarget, PlanAheadReachesAClickedTargetSoonerThanPid) {
  if (!onPath("xvfb-run")) GTEST_SKIP() << "xvfb-run not installed: GUI tests skipped";
  const nlohmann::json mpc = runScenario("target-mpc"), pid = runScenario("target-pid");
  ASSERT_FALSE(mpc.contains("failure")) << mpc.dump();
  ASSERT_FALSE(pid.contains("failure")) << pid.dump();
  // The clicks picked each law, and only the MPC run planned.
  EXPECT_EQ(mpc["law"], "mpc");
  EXPECT_TRUE(mpc["planned"].get<bool>());
  EXPECT_EQ(pid["law"], "jacobian");
  EXPECT_TRUE(pid["pid"].get<bool>());
  EXPECT_FALSE(pid["planned"].get<bool>());
  EXPECT_EQ(mpc["target"], pid["target"]);
  // MPC settles within 5 mm of the clicked target, with the grasp held, in fewer simulated
  // seconds than PID (which may not settle at all in the run's 12 s).
  EXPECT_TRUE(mpc["settled"].get<bool>()) << mpc.dump();
  EXPECT_LT(mpc["error"].get<double>(), 0.005);
  EXPECT_EQ(mpc["grasp"], "pinch pose");
  const double mpcTime = mpc["time_to_5mm"], pidTime = pid["time_to_5mm"];
  EXPECT_GT(mpcTime, 0);
  if (pid["settled"].get<bool>()) {
    EXPECT_LT(mpcTime, pidTime) << pid.dump();
  }
}

}  // namespace law_target_gui_test
}  // namespace cablelab::test
