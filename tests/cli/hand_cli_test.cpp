// cablelab track / reach from the command line (docs/cli.md).
#include <gtest/gtest.h>

#include "tests/support/engine_test_support.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace {

struct HandRun {
  int code;
  std::string out;  // stdout only
};

HandRun run(const std::string& args) {
  const auto r = cablelab::test::runCli(args);
  return {r.exitCode, r.out};
}

// Measured (15 s, from the default start 157 mm off): constant target 0.08 mm (PD) and 0.10 mm
// (PID); ramp 1.0 mm (PD and PID). The simulation is deterministic; the bounds are the
// acceptance goals.
constexpr double kConstantTolerance = 1e-3;  // m
constexpr double kRampTolerance = 1e-2;      // m

TEST(TrackCli, ConstantTargetFromOpenPose) {
  const HandRun r = run("track --target 0,0 --time 15");
  ASSERT_EQ(r.code, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LT(j["final_error"].get<double>(), kConstantTolerance);
  EXPECT_GT(j["grasp_time"].get<double>(), 0);
  EXPECT_GE(j["start_error"].get<double>(), 0.05);  // the box does not start on the target
  EXPECT_TRUE(j["grasp_held"].get<bool>());
}

TEST(TrackCli, StartPlacesTheGrasp) {
  const HandRun r = run("track --target 0.2,0.3 --start -0.1,0.2 --time 3");
  ASSERT_EQ(r.code, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["start"][0].get<double>(), -0.1, 1e-12);
  EXPECT_NEAR(j["start"][1].get<double>(), 0.2, 1e-12);
  // The box is grasped where it was placed: it starts about |(0.3, 0.1)| off the target.
  EXPECT_NEAR(j["start_error"].get<double>(), std::hypot(0.3, 0.1), 0.03);
  EXPECT_EQ(run("track --start 9,9").code, 2);
  EXPECT_EQ(run("track --start 1").code, 2);
}

TEST(TrackCli, AngleTargetTurnsTheBox) {
  // A box that may turn (--set turn=1) turned to 0.2 rad while it moves 0.1 m, 0.05 m: measured
  // 1.3 mm and 0.0002 rad at 15 s (docs/control.md#a-box-that-turns).
  const std::string csv = (std::filesystem::temp_directory_path() /
                           ("cablelab_turn_" + std::to_string(getpid()) + ".csv"))
                              .string();
  const HandRun r = run("track --set turn=1 --target 0.1,0.05,0.2 --pid --csv " + csv);
  ASSERT_EQ(r.code, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LT(j["final_error"].get<double>(), 0.005);
  EXPECT_LT(j["final_angle_error"].get<double>(), 0.02);
  EXPECT_GT(j["rms_angle_error"].get<double>(), 0.0);  // it started at angle 0
  EXPECT_TRUE(j["grasp_held"].get<bool>());
  std::FILE* f = std::fopen(csv.c_str(), "r");
  ASSERT_NE(f, nullptr);
  char header[128];
  ASSERT_NE(std::fgets(header, sizeof header, f), nullptr);
  std::fclose(f);
  std::filesystem::remove(csv);
  EXPECT_STREQ(header, "t,target_x,target_y,x,y,target_angle,angle\n");
  // Bad angle targets: one line, exit 2.
  for (const char* bad : {"--set turn=1 --target 1,2,3,4", "--set turn=1 --target 0.1,0.1,nan",
                          "--target 0.1,0.1,0.2", "--set turn=2"}) {
    const auto e = cablelab::test::runCli(std::string("track ") + bad);
    EXPECT_EQ(e.exitCode, 2) << bad;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << bad << ": " << e.err;
  }
}

TEST(TrackCli, RampTarget) {
  const HandRun r = run("track --ramp 0.5,1.0,5 --time 15");
  ASSERT_EQ(r.code, 0);
  EXPECT_LT(nlohmann::json::parse(r.out)["final_error"].get<double>(), kRampTolerance);
}

// The acceptance goals with the integral term.
TEST(TrackCli, PidConstantTargetWithinOneMillimetre) {
  const HandRun r = run("track --target 0,0 --pid --time 15");
  ASSERT_EQ(r.code, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LT(j["final_error"].get<double>(), kConstantTolerance);
  EXPECT_GT(j["grasp_time"].get<double>(), 0);
}
TEST(TrackCli, PidRampWithinOneCentimetre) {
  const HandRun r = run("track --ramp 0.5,1.0,5 --pid --time 15");
  ASSERT_EQ(r.code, 0);
  EXPECT_LT(nlohmann::json::parse(r.out)["final_error"].get<double>(), kRampTolerance);
}

TEST(TrackCli, BadValuesExitTwo) {
  EXPECT_EQ(run("track --target abc").code, 2);
  EXPECT_EQ(run("track --ramp 1,2").code, 2);
  EXPECT_EQ(run("track --time -1").code, 2);
  EXPECT_EQ(run("track --help").code, 0);
}

// The simulated sweep (every target a full run of the hand) reaches more than the fingertips;
// a sample of the targets it counts beyond the fingertips, re-run one by one through `track`,
// are reached there too. Under the sanitizers (about 20 times slower) on a 12 x 12 grid, which
// still has 8 targets beyond the fingertips.
TEST(ReachCli, SimulatedReachExceedsTheFingertipsAndTrackAgrees) {
  const int grid = CABLELAB_SANITIZED ? 12 : 20;
  const std::string csv = (std::filesystem::temp_directory_path() /
                           ("cablelab_reach_" + std::to_string(getpid()) + ".csv"))
                              .string();
  const HandRun r = run("reach --grid " + std::to_string(grid) + " --csv " + csv);
  ASSERT_EQ(r.code, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["ratio"].get<double>(), 1.0);
  EXPECT_EQ(j["points"].get<int>(), grid * grid);
  EXPECT_EQ(j["model"].get<std::string>(), "simulation");
  std::FILE* f = std::fopen(csv.c_str(), "r");
  ASSERT_NE(f, nullptr);
  char header[128];
  ASSERT_NE(std::fgets(header, sizeof header, f), nullptr);
  EXPECT_STREQ(header, "x,y,object_reached,fingertip_reachable\n");
  std::vector<std::array<double, 2>> beyond;
  double x, y;
  int reached, tip, rows = 0, counted = 0;
  while (std::fscanf(f, "%lf,%lf,%d,%d", &x, &y, &reached, &tip) == 4) {
    ++rows, counted += reached;
    if (reached && !tip) beyond.push_back({x, y});
  }
  std::fclose(f);
  EXPECT_EQ(rows, grid * grid);
  EXPECT_EQ(counted, j["object_points"].get<int>());
  ASSERT_GE(beyond.size(), 3u);
  for (size_t k = 0; k < beyond.size(); k += beyond.size() / 3) {  // three spread samples
    char target[96];
    std::snprintf(target, sizeof target, "%.17g,%.17g", beyond[k][0], beyond[k][1]);
    const HandRun t = run(std::string("track --pid --target ") + target);
    ASSERT_EQ(t.code, 0);
    const auto tj = nlohmann::json::parse(t.out);
    EXPECT_LT(tj["final_error"].get<double>(), 0.005) << target;
    EXPECT_TRUE(tj["grasp_held"].get<bool>()) << target;
  }
}

TEST(ReachCli, QuasiStaticModel) {
  const HandRun r = run("reach --grid 12 --model quasi-static");
  ASSERT_EQ(r.code, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["model"].get<std::string>(), "quasi-static");
  EXPECT_DOUBLE_EQ(j["object_area"].get<double>(), j["quasi_static_area"].get<double>());
}

TEST(ReachCli, BadValuesExitTwo) {
  EXPECT_EQ(run("reach --grid 0").code, 2);
  EXPECT_EQ(run("reach --grid abc").code, 2);
  EXPECT_EQ(run("reach --model statics").code, 2);
  EXPECT_EQ(run("reach --help").code, 0);
}

}  // namespace
