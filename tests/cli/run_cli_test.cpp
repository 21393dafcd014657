// CLI tests for `cablelab scenes`, `run` and `wrap` (docs/cli.md): formats, columns, exit codes.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/scenes/scene_registry.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

TEST(ScenesCli, OneLinePerBuiltinScene) {
  const auto r = test::runCli("scenes");
  ASSERT_EQ(r.exitCode, 0);
  std::istringstream lines(r.out);
  std::vector<std::string> names;
  for (std::string line; std::getline(lines, line);)
    names.push_back(line.substr(0, line.find(' ')));
  std::vector<std::string> expected;
  for (const SceneInfo& s : builtinScenes()) expected.push_back(s.name);
  EXPECT_EQ(names, expected);
  for (const char* name : {"ballast", "hexagon", "membrane", "pulley", "hand"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

TEST(RunCli, CsvHasTheContractColumnsAndOneRowPerStep) {
  const std::string csv = "/tmp/cablelab_run_cli_test.csv";
  const auto r = test::runCli("run pulley --time 0.5 --dt 0.01 --csv " + csv);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header,
            "t,left.x,left.y,left.theta,left.vx,left.vy,left.omega,right.x,right.y,right.theta,"
            "right.vx,right.vy,"
            "right.omega,cable.length,cable.tension,cable.wraps");
  int rows = 0;
  for (std::string line; std::getline(in, line);) {
    ++rows;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 15);
    EXPECT_EQ(line.find("nan"), std::string::npos);
  }
  EXPECT_EQ(rows, 51);  // the initial state and 50 steps
  const auto summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["steps"], 50);
}

// Splits one CSV line at its commas.
std::vector<std::string> csvFields(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string f; std::getline(in, f, ',');) fields.push_back(f);
  return fields;
}

TEST(RunCli, CsvEndsWithEveryNamedJointsValueRateAndForce) {
  // The winch's drum on its servo: after the cable's columns, axle.value (rad), axle.rate
  // (rad/s) and axle.force (N m). Winding steadily, the rate is the servo's speed, the value
  // grows by it, and the torque is the rope's tension times the drum's radius (0.1 m).
  const std::string csv = "/tmp/cablelab_run_cli_joint_test.csv";
  const auto r = test::runCli("run winch --set omega=2 --time 3 --csv " + csv);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  const std::vector<std::string> names = csvFields(header);
  ASSERT_GE(names.size(), 3u);
  const size_t n = names.size();
  EXPECT_EQ(names[n - 3], "axle.value");
  EXPECT_EQ(names[n - 2], "axle.rate");
  EXPECT_EQ(names[n - 1], "axle.force");
  EXPECT_EQ(names[n - 6], "cable.length");
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> row;
    for (const std::string& f : csvFields(line)) row.push_back(std::stod(f));
    ASSERT_EQ(row.size(), n);
    rows.push_back(row);
  }
  ASSERT_EQ(rows.size(), 181u);
  const std::vector<double>& a = rows[rows.size() - 2];
  const std::vector<double>& b = rows.back();
  EXPECT_NEAR(b[n - 2], 2.0, 1e-3);
  EXPECT_NEAR((b[n - 3] - a[n - 3]) / (b[0] - a[0]), b[n - 2], 1e-3);
  EXPECT_NEAR(b[n - 1], 0.1 * b[n - 5], 0.01 * 0.1 * b[n - 5]);  // torque = tension r
  EXPECT_NEAR(rows.front()[n - 1], 0.0, 1e-12);                  // no step yet: no force
}

TEST(RunCli, BadOptionsExitTwo) {
  for (const char* args :
       {"run ballast --time -1", "run ballast --dt 0", "run ballast --substeps 0",
        "run ballast --set l=-1", "run ballast --set l", "run nowhere"}) {
    const auto r = test::runCli(args);
    EXPECT_EQ(r.exitCode, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
}

TEST(WrapCli, SquareOverTheTop) {
  const auto r = test::runCli("wrap " + test::sourcePath("tests/data/wrap/square.json"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["contact_vertices"], nlohmann::json::array({3, 2}));
  EXPECT_NEAR(j["length"].get<double>(), 2 * std::hypot(1.5, 0.5) + 1, 1e-14);
  ASSERT_EQ(j["path"].size(), 4u);
  EXPECT_EQ(j["path"][1], nlohmann::json::array({-0.5, 0.5}));
}

TEST(WrapCli, BadInputNamesTheField) {
  const struct {
    const char* file;
    const char* field;
  } cases[] = {{"wrap_not_convex.json", "polygon"},
               {"wrap_bad_side.json", "side"},
               {"wrap_inside.json", "A"},
               {"wrap_missing_b.json", "B"}};
  for (const auto& c : cases) {
    const std::string path = test::sourcePath(std::string("tests/data/bad/") + c.file);
    const auto r = test::runCli("wrap " + path);
    EXPECT_EQ(r.exitCode, 2) << c.file;
    EXPECT_NE(r.err.find(path + ": " + c.field), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace cablelab
