// cablelab track / reach from the command line (docs/cli.md).
#include <gtest/gtest.h>

#include "tests/support/engine_test_support.h"

#include <array>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

namespace {

struct CliRun {
  int code;
  std::string out;  // stdout only
};

CliRun run(const std::string& args) {
  const auto r = cablelab::test::runCli(args);
  return {r.exitCode, r.out};
}

// Measured (15 s): constant target 0.023 mm (PD) and 0.007 mm (PID); ramp 1.0 mm (PD) and
// 0.7 mm (PID). The simulation is deterministic; the bounds are the acceptance goals.
constexpr double kConstantTolerance = 1e-3;  // m
constexpr double kRampTolerance = 1e-2;      // m

TEST(TrackCli, ConstantTargetFromOpenPose) {
  const CliRun r = run("track --target 0,0 --time 15");
  ASSERT_EQ(r.code, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LT(j["final_error"].get<double>(), kConstantTolerance);
  EXPECT_GT(j["grasp_time"].get<double>(), 0);
}

TEST(TrackCli, RampTarget) {
  const CliRun r = run("track --ramp 0.5,1.0,5 --time 15");
  ASSERT_EQ(r.code, 0);
  EXPECT_LT(nlohmann::json::parse(r.out)["final_error"].get<double>(), kRampTolerance);
}

// The acceptance goals with the integral term.
TEST(TrackCli, PidConstantTargetWithinOneMillimetre) {
  const CliRun r = run("track --target 0,0 --pid --time 15");
  ASSERT_EQ(r.code, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LT(j["final_error"].get<double>(), kConstantTolerance);
  EXPECT_GT(j["grasp_time"].get<double>(), 0);
}
TEST(TrackCli, PidRampWithinOneCentimetre) {
  const CliRun r = run("track --ramp 0.5,1.0,5 --pid --time 15");
  ASSERT_EQ(r.code, 0);
  EXPECT_LT(nlohmann::json::parse(r.out)["final_error"].get<double>(), kRampTolerance);
}

TEST(TrackCli, BadValuesExitTwo) {
  EXPECT_EQ(run("track --target abc").code, 2);
  EXPECT_EQ(run("track --ramp 1,2").code, 2);
  EXPECT_EQ(run("track --time -1").code, 2);
  EXPECT_EQ(run("track --help").code, 0);
}

TEST(ReachCli, ControllerReachesMoreThanTheFingertips) {
  const CliRun r = run("reach --grid 20");
  ASSERT_EQ(r.code, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["ratio"].get<double>(), 1.0);
  EXPECT_EQ(j["points"].get<int>(), 400);
}

TEST(ReachCli, BadValuesExitTwo) {
  EXPECT_EQ(run("reach --grid 0").code, 2);
  EXPECT_EQ(run("reach --grid abc").code, 2);
  EXPECT_EQ(run("reach --help").code, 0);
}

}  // namespace
