// cablelab track --controller / --compare and reach --controller (docs/cli.md): the JSON keys
// and the errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/engine_test_support.h"

namespace hand_mpc_cli_test {  // named: unity batches join test files

TEST(TrackMpcCli, JsonKeys) {
  const auto r = cablelab::test::runCli("track --target 0.2,0.1 --time 5 --controller mpc");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["controller"], "mpc");
  // Within 5 mm in under a second of control (measured 0.83 s; PID has not arrived by 5 s).
  ASSERT_TRUE(j["time_to_5mm"].is_number());
  EXPECT_GT(j["time_to_5mm"].get<double>(), 0.2);
  EXPECT_LT(j["time_to_5mm"].get<double>(), 2.0);
  EXPECT_LT(j["final_error"].get<double>(), 0.005);
  EXPECT_TRUE(j["grasp_held"].get<bool>());
  EXPECT_GT(j["controller_solve_us"].get<double>(), 0);
  EXPECT_GE(j["controller_solve_max_us"].get<double>(), j["controller_solve_us"].get<double>());
  EXPECT_EQ(j["joint_limit_hits"], 0);
  EXPECT_GE(j["overshoot"].get<double>(), 0);

  // The default law says so too; a run that has not arrived has no time_to_5mm.
  const auto d = cablelab::test::runCli("track --target 0.2,0.1 --time 2");
  ASSERT_EQ(d.exitCode, 0);
  const auto k = nlohmann::json::parse(d.out);
  EXPECT_EQ(k["controller"], "jacobian");
  EXPECT_TRUE(k["time_to_5mm"].is_null());
}

TEST(TrackMpcCli, CompareKeysAndFigure) {
  const std::string png =
      (std::filesystem::temp_directory_path() / "cablelab_mpc_compare.png").string();
#ifdef CABLELAB_HAVE_OFFSCREEN
  const auto r = cablelab::test::runCli("track --compare --time 6 --png " + png);
#else  // a build without the offscreen renderer (the sanitizer's) draws no figure
  const auto r = cablelab::test::runCli("track --compare --time 6");
#endif
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["targets"].size(), 20u);
  for (const char* law : {"jacobian", "mpc"})
    for (const char* key :
         {"median_time_to_5mm", "median_final_error", "max_final_error", "median_overshoot",
          "max_overshoot", "grasp_losses", "joint_limit_hits", "settled", "controller_solve_us"})
      EXPECT_TRUE(j[law].contains(key)) << law << "." << key;
  EXPECT_EQ(j["mpc"]["grasp_losses"], 0);
#ifdef CABLELAB_HAVE_OFFSCREEN
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
  std::filesystem::remove(png);
#endif
}

TEST(TrackMpcCli, BadValuesExitTwo) {
  const auto c = cablelab::test::runCli("track --controller pid");
  EXPECT_EQ(c.exitCode, 2);
  EXPECT_NE(c.err.find("command line: --controller: must be jacobian or mpc (got \"pid\")"),
            std::string::npos)
      << c.err;
  const auto h = cablelab::test::runCli("track --controller mpc --horizon 0");
  EXPECT_EQ(h.exitCode, 2);
  EXPECT_NE(h.err.find("--horizon: must be a whole number in [1, 40] (got 0)"), std::string::npos)
      << h.err;
  EXPECT_EQ(cablelab::test::runCli("track --compare --csv x.csv").exitCode, 2);
  EXPECT_EQ(cablelab::test::runCli("reach --controller nope --grid 2").exitCode, 2);
}

TEST(TrackMpcCli, AngleTarget) {
  // A box that turns, with membrane friction: the plan turns it to THETA (measured: 0.13 mm and
  // 3.3e-4 rad at 4 s, within 5 mm after 1.25 s).
  const auto r = cablelab::test::runCli(
      "track --set mu=0.5 --set turn=1 --target 0.1,0.05,0.2 --controller mpc --time 4");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["controller"], "mpc");
  EXPECT_LT(j["final_error"].get<double>(), 0.005);
  EXPECT_LT(j["final_angle_error"].get<double>(), 0.02);
  EXPECT_NEAR(j["final_angle"].get<double>(), 0.2, 0.02);
  EXPECT_TRUE(j["grasp_held"].get<bool>());
}

TEST(ReachMpcCli, ControllerKey) {
  const auto r = cablelab::test::runCli("reach --grid 2 --controller mpc --model quasi-static");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["controller"], "mpc");
}

}  // namespace hand_mpc_cli_test
