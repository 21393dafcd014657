// Rewind and plots through the real window under Xvfb (ui/timeline_scenarios.h): the step-back
// key and Space replay the hand's run exactly; the plot export writes slide-size PNGs and the
// CSV of what was recorded, and the error chart's range shrinks back after a far target.
// Skipped when xvfb-run is not installed.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/ui/test_support.h"

namespace cablelab::test {
namespace timeline_gui_test {  // named: unity batches join test files

/// The scenario's JSON report; `screenshot` gets the last frame.
nlohmann::json runScript(const std::string& name, const std::string& size,
                         const std::string& screenshot, const std::string& extra = "") {
  const RunResult r = run("xvfb-run -a -s \"-screen 0 1920x1080x24\" " + std::string(CABLELAB_CLI) +
                              " gui hand --size " + size + " --script " + name + " --screenshot " +
                              screenshot + " " + extra,
                          "timeline_gui_" + name);
  return jsonReport(r);
}

TEST(TimelineGui, StepBackAndPlayRepeatTheHandsRunExactly) {
  if (!onPath("xvfb-run")) GTEST_SKIP() << "xvfb-run not installed";
  for (const std::string size : {"1280x720", "1920x1080"}) {
    SCOPED_TRACE(size);
    const std::string shot = (outputDir("timeline_gui") / ("rewind-" + size + ".png")).string();
    const auto j = runScript("rewind", size, shot);
    EXPECT_EQ(j.value("step_after_back", -1), 120) << j.dump();
    EXPECT_TRUE(j.value("equal_after_back", false)) << j.dump();
    EXPECT_GE(j.value("compared", 0), 29) << j.dump();  // steps 121 .. 150 again
    EXPECT_LE(j.value("largest_difference", 1.0), 1e-12) << j.dump();
    EXPECT_TRUE(j.value("paused", false));
    EXPECT_TRUE(j.value("rewound", false));
    EXPECT_TRUE(j.value("help_has_b", false));
    const ui::Image image = ui::readPng(shot);
    EXPECT_EQ(image.width, std::stoi(size.substr(0, size.find('x'))));
  }
}

TEST(TimelineGui, PlotsExportAtSlideSizeAndTheRangeShrinksBack) {
  if (!onPath("xvfb-run")) GTEST_SKIP() << "xvfb-run not installed";
  const std::string stem = (outputDir("timeline_gui") / "hand-plot").string();
  const std::string shot = (outputDir("timeline_gui") / "plots-1920x1080.png").string();
  const auto j = runScript("plot-export", "1920x1080", shot, "--script-out " + stem);
  ASSERT_EQ(j.value("files", nlohmann::json::array()).size(), 3u) << j.dump();
  // The far target (5 m) is in view, then it has left the 2 s shown.
  EXPECT_GE(j["range_far"][1].get<double>(), 4.9) << j.dump();
  EXPECT_LE(j["range_after"][1].get<double>(), 0.5) << j.dump();
  for (const auto& f : j["files"]) {
    const ui::Image image = ui::readPng(f.get<std::string>() + ".png");
    EXPECT_GE(image.width, 1600);
    EXPECT_GE(image.height, 900);
  }
  // The error chart's CSV ends with the last sample the sandbox recorded.
  std::ifstream csv(j["files"][0].get<std::string>() + ".csv");
  std::string line, last;
  std::getline(csv, line);
  EXPECT_EQ(line, "time (s),controller error (m)");
  while (std::getline(csv, line)) last = line;
  std::stringstream fields(last);
  std::string t, e;
  std::getline(fields, t, ',');
  std::getline(fields, e, ',');
  EXPECT_EQ(std::stod(t), j["last_time"].get<double>());
  EXPECT_EQ(std::stod(e), j["last_error"].get<double>());
}

}  // namespace timeline_gui_test
}  // namespace cablelab::test
