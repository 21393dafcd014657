// CLI tests for `cablelab statics` (docs/cli.md): output keys, exit codes, error messages.
#include <gtest/gtest.h>

#include "tests/support/engine_test_support.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

namespace {

struct StaticsRun {
  int code = -1;
  std::string out;  // stdout and stderr together
};

StaticsRun runCli(const std::string& args) {
  const auto r = cablelab::test::runCli(args);
  return {r.exitCode, r.out + r.err};
}

std::string data(const std::string& name) {
  return cablelab::test::dataPath(name);
}

TEST(StaticsCli, PrintsTheContractKeysForEverySolver) {
  for (const char* solver : {"", " --solver socp", " --solver newton", " --solver auto"}) {
    const StaticsRun run = runCli("statics " + data("statics/two_cables.json") + solver);
    ASSERT_EQ(run.code, 0) << run.out;
    const auto j = nlohmann::json::parse(run.out);
    for (const char* key : {"p", "lengths", "tensions", "energy", "iterations", "solve_us"})
      EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_NEAR(j["p"][0].get<double>(), 0, 1e-10);
    EXPECT_NEAR(j["p"][1].get<double>(), 0, 1e-10);
    EXPECT_EQ(j["tensions"].size(), 2u);
    EXPECT_NEAR(j["energy"].get<double>(), 150 * std::pow(2 * std::sqrt(2.0) - 1.5, 2), 1e-9);
  }
}

TEST(StaticsCli, FingertipExampleEndsOnTheFingertip) {
  const StaticsRun run = runCli("statics " + data("statics/on_fingertip.json"));
  ASSERT_EQ(run.code, 0) << run.out;
  const auto j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["p"][0].get<double>(), 0.0);
  EXPECT_EQ(j["p"][1].get<double>(), 0.0);
}

TEST(StaticsCli, BadInputExitsTwoNamingTheField) {
  const std::pair<const char*, const char*> cases[] = {
      {"bad/statics_negative_k.json", "cables[1].k"},
      {"bad/statics_negative_rest_length.json", "cables[0].L"},
      {"bad/statics_no_cables.json", "cables"},
      {"bad/statics_truncated.json", "(json)"},
      {"bad/statics_string_number.json", "cables[0].a[1]"},
      {"bad/statics_null_k.json", "cables[0].k"},
      {"bad/statics_huge_number.json", "1e400"},
      {"bad/statics_wrong_size.json", "cables[0].b"},
      {"bad/statics_unknown_key.json", "cables[0].stiffness"},
      {"bad/statics_bad_p0.json", "p0"},
      {"bad/does_not_exist.json", "cannot open"},
  };
  for (const auto& [file, field] : cases) {
    const StaticsRun run = runCli("statics " + data(file));
    EXPECT_EQ(run.code, 2) << file << ": " << run.out;
    EXPECT_NE(run.out.find(field), std::string::npos) << file << ": " << run.out;
    EXPECT_EQ(run.out.find("nan"), std::string::npos) << run.out;
  }
}

TEST(StaticsCli, UnknownSolverExitsTwo) {
  const StaticsRun run = runCli("statics " + data("statics/two_cables.json") + " --solver simplex");
  EXPECT_EQ(run.code, 2);
  EXPECT_NE(run.out.find("solver"), std::string::npos) << run.out;
}

}  // namespace
